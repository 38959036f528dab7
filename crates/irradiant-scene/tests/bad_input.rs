//! Bad input gets a clear error (naming the file, the problem and the fix) or a warning,
//! never a panic.

use std::path::PathBuf;

use irradiant_scene::{SceneError, load};

/// A fresh folder under the system temp dir for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "irradiant-scene-test-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &std::path::Path, file: &str, text: &str) -> String {
    let path = dir.join(file);
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

const TRIANGLE_OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

fn error_text(spec: &str) -> String {
    let e = load(spec).expect_err("must fail");
    e.to_string()
}

#[test]
fn a_missing_file_names_the_path() {
    let text = error_text("/nonexistent/scene.obj");
    assert!(
        text.contains("/nonexistent/scene.obj") && text.contains("cannot read"),
        "{text}"
    );
}

#[test]
fn an_unknown_builtin_lists_the_builtins() {
    let text = error_text("cornel");
    assert!(
        text.contains("cornell") && text.contains("two-rooms"),
        "{text}"
    );
}

#[test]
fn a_malformed_obj_is_an_error_naming_the_file() {
    let dir = scratch("malformed-obj");
    let path = write(&dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    let e = load(&path).unwrap_err();
    assert!(matches!(e, SceneError::Obj { .. }), "{e}");
    assert!(e.to_string().contains("bad.obj"));
}

#[test]
fn nan_and_infinite_vertices_are_refused() {
    let dir = scratch("nan");
    for (name, v) in [("nan.obj", "nan"), ("inf.obj", "inf")] {
        let path = write(
            &dir,
            name,
            &format!("v 0 0 0\nv {v} 0 0\nv 0 1 0\nf 1 2 3\n"),
        );
        let text = error_text(&path);
        assert!(
            text.contains(name)
                && text.contains("not a finite number")
                && text.contains("vertex 1"),
            "{text}"
        );
    }
}

#[test]
fn degenerate_triangles_are_dropped_with_a_warning() {
    let dir = scratch("degenerate");
    let path = write(
        &dir,
        "mixed.obj",
        &format!("{TRIANGLE_OBJ}v 2 2 2\nf 1 1 4\nf 1 2 2\n"),
    );
    let loaded = load(&path).unwrap();
    assert_eq!(loaded.scene.triangle_count(), 1);
    assert!(
        loaded.warnings.iter().any(|w| w.contains("2 degenerate")),
        "{:?}",
        loaded.warnings
    );
}

#[test]
fn an_empty_scene_is_an_error() {
    let dir = scratch("empty");
    let path = write(&dir, "empty.obj", "# nothing\nv 0 0 0\n");
    let text = error_text(&path);
    assert!(text.contains("no triangles"), "{text}");
    let path = write(&dir, "flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
    assert!(error_text(&path).contains("no triangles"));
}

#[test]
fn a_missing_texture_warns_and_renders_flat() {
    let dir = scratch("texture");
    write(
        &dir,
        "m.mtl",
        "newmtl stone\nKd 0.5 0.5 0.5\nmap_Kd missing.png\n",
    );
    let path = write(
        &dir,
        "t.obj",
        &format!("mtllib m.mtl\nusemtl stone\n{TRIANGLE_OBJ}"),
    );
    let loaded = load(&path).unwrap();
    assert!(
        loaded
            .warnings
            .iter()
            .any(|w| w.contains("missing.png") && w.contains("not found")),
        "{:?}",
        loaded.warnings
    );
    assert!(loaded.scene.materials[0].base_color_texture.is_none());
}

#[test]
fn a_missing_material_library_warns() {
    let dir = scratch("mtl");
    let path = write(
        &dir,
        "t.obj",
        &format!("mtllib absent.mtl\nusemtl stone\n{TRIANGLE_OBJ}"),
    );
    let loaded = load(&path).unwrap();
    assert!(
        loaded
            .warnings
            .iter()
            .any(|w| w.contains("material library")),
        "{:?}",
        loaded.warnings
    );
}

#[test]
fn a_malformed_gltf_is_an_error() {
    let dir = scratch("gltf");
    for (name, text) in [
        ("broken.gltf", "{ \"asset\": "),
        ("notgltf.glb", "this is not binary glTF"),
    ] {
        let path = write(&dir, name, text);
        let e = load(&path).unwrap_err();
        assert!(matches!(e, SceneError::Gltf { .. }), "{e}");
        assert!(e.to_string().contains(name));
    }
}

#[test]
fn manifest_errors_name_the_manifest_and_the_fix() {
    let dir = scratch("manifest");
    write(&dir, "tri.obj", TRIANGLE_OBJ);
    let cases = [
        (
            "syntax.toml",
            "[mesh\npath = 'tri.obj'",
            "invalid scene manifest",
        ),
        ("type.toml", "[mesh]\npath = 3", "invalid scene manifest"),
        ("nomesh.toml", "sky = [1, 1, 1]", "missing field `mesh`"),
        ("gone.toml", "[mesh]\npath = 'gone.obj'", "gone.obj"),
        (
            "light.toml",
            "[mesh]\npath = 'tri.obj'\n[[light]]\nname = 'l'\nkind = 'point'\nintensity = 1.0",
            "has no position",
        ),
        (
            "anim.toml",
            "[mesh]\npath = 'tri.obj'\n[[animation]]\nlight = 'ghost'\nintensity_scale = [[0.0, 1.0]]",
            "ghost",
        ),
        (
            "probes.toml",
            "[mesh]\npath = 'tri.obj'\n[[probe_volume]]\nmin = [0, 0, 0]\nmax = [1, 1, 1]\ncounts = [100000, 1, 1]",
            "probes per axis",
        ),
        (
            "box.toml",
            "[mesh]\npath = 'tri.obj'\n[[region]]\nname = 'r'\nmin = [1, 1, 1]\nmax = [0, 0, 0]",
            "min ≥ max",
        ),
        (
            "fov.toml",
            "[mesh]\npath = 'tri.obj'\n[camera]\nposition = [0, 0, 1]\ntarget = [0, 0, 0]\nfov_y_degrees = 500.0",
            "field of view",
        ),
        (
            "sky.toml",
            "sky = [-1, 0, 0]\n[mesh]\npath = 'tri.obj'",
            "sky",
        ),
        (
            "material.toml",
            "[mesh]\npath = 'tri.obj'\n[[material]]\nname = 'ghost'\nmetallic = 1.0",
            "names 'ghost'",
        ),
        (
            "roughness.toml",
            "[mesh]\npath = 'tri.obj'\n[[material]]\nname = 'default'\nroughness = 0.0",
            "roughness = 0 is out of range",
        ),
        (
            "metal.toml",
            "[mesh]\npath = 'tri.obj'\n[[material]]\nname = 'default'\nmetallic = nan",
            "metallic = NaN is out of range",
        ),
    ];
    for (name, text, expected) in cases {
        let path = write(&dir, name, text);
        let message = error_text(&path);
        assert!(message.contains(expected), "{name}: {message}");
        assert!(
            message.contains(name) || message.contains("gone.obj"),
            "{name}: the message must name the file: {message}"
        );
    }
}

#[test]
fn unknown_manifest_keys_warn_but_load() {
    let dir = scratch("unknown");
    write(&dir, "tri.obj", TRIANGLE_OBJ);
    let path = write(
        &dir,
        "typo.toml",
        "skye = [1, 1, 1]\n[mesh]\npath = 'tri.obj'\nscael = 2.0\n",
    );
    let loaded = load(&path).unwrap();
    let w = loaded.warnings.join("\n");
    assert!(
        w.contains("skye") && w.contains("scael") && w.contains("typo.toml"),
        "{w}"
    );
}

/// The inputs on which the fuzz targets (fuzz/) found a panic, in the targets' own form:
/// `*.gltf`/`*.glb` as they are, `*.objmtl` an OBJ and, after a NUL byte, the `m.mtl` it
/// names. Each must load or fail with an error naming its file.
#[test]
fn inputs_the_fuzzers_broke_are_errors_not_panics() {
    let dir = scratch("fuzz-regressions");
    let regressions =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-regressions");
    let mut checked = 0;
    for entry in std::fs::read_dir(&regressions).unwrap() {
        let input = std::fs::read(entry.unwrap().path()).unwrap();
        let path = match input.iter().position(|&b| b == 0) {
            Some(nul) if !input.starts_with(b"{") && !input.starts_with(b"glTF") => {
                std::fs::write(dir.join("m.mtl"), &input[nul + 1..]).unwrap();
                std::fs::write(dir.join("f.obj"), &input[..nul]).unwrap();
                dir.join("f.obj")
            }
            _ => {
                let name = if input.starts_with(b"{") {
                    "f.gltf"
                } else {
                    "f.glb"
                };
                std::fs::write(dir.join(name), &input).unwrap();
                dir.join(name)
            }
        };
        if let Err(e) = load(path.to_str().unwrap()) {
            assert!(e.to_string().contains(path.to_str().unwrap()), "{e}");
        }
        checked += 1;
    }
    assert!(
        checked >= 2,
        "the regression inputs are missing from {}",
        regressions.display()
    );
}

/// The two panics the fuzzers found, written small: an MTL colour with one number (tobj
/// unwraps three) and a primitive whose POSITION accessor does not exist (gltf-json indexes
/// it while validating).
#[test]
fn parser_panics_become_errors_naming_the_file() {
    let dir = scratch("parser-panics");
    write(&dir, "short.mtl", "newmtl grey\nKd 0.5\n");
    let obj = write(
        &dir,
        "short.obj",
        &format!("mtllib short.mtl\nusemtl grey\n{TRIANGLE_OBJ}"),
    );
    match load(&obj) {
        Ok(loaded) => assert!(
            loaded.warnings.iter().any(|w| w.contains("short")),
            "{:?}",
            loaded.warnings
        ),
        Err(e) => assert!(
            e.to_string().contains("short.obj") && e.to_string().contains("malformed"),
            "{e}"
        ),
    }
    let gltf = write(
        &dir,
        "missing-accessor.gltf",
        r#"{"asset":{"version":"2.0"},"accessors":[],"meshes":[{"primitives":[{"attributes":{"POSITION":5}}]}]}"#,
    );
    let e = load(&gltf).unwrap_err();
    assert!(matches!(e, SceneError::Gltf { .. }), "{e}");
    assert!(e.to_string().contains("missing-accessor.gltf"), "{e}");
}
