//! Manifests round-trip without loss, and the shipped ones load.

use std::path::Path;

use irradiant_scene::Manifest;

fn repo() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

fn shipped_manifests() -> Vec<std::path::PathBuf> {
    let mut found = Vec::new();
    for dir in std::fs::read_dir(repo().join("scenes")).unwrap().flatten() {
        if dir.path().is_dir() {
            for f in std::fs::read_dir(dir.path()).unwrap().flatten() {
                if f.path().extension().is_some_and(|e| e == "toml") {
                    found.push(f.path());
                }
            }
        }
    }
    found
}

#[test]
fn every_shipped_manifest_round_trips() {
    let manifests = shipped_manifests();
    assert!(manifests.len() >= 3, "{manifests:?}");
    for path in manifests {
        let text = std::fs::read_to_string(&path).unwrap();
        let mut warnings = Vec::new();
        let parsed = Manifest::parse(&text, &path, &mut warnings).unwrap();
        assert!(warnings.is_empty(), "{}: {warnings:?}", path.display());
        let again = Manifest::parse(&parsed.to_toml(), &path, &mut warnings).unwrap();
        assert_eq!(parsed, again, "{}", path.display());
    }
}

/// The shared scenes (../shared/scenes) load through their manifests with their textures.
#[test]
fn every_shipped_manifest_loads() {
    for path in shipped_manifests() {
        // The scenes at scale (millions of triangles) are for the lent GPU's bench; what they
        // use is `repeat_copies_instances_and_flatten_merges_them`'s.
        let text = std::fs::read_to_string(&path).unwrap();
        if Manifest::parse(&text, &path, &mut Vec::new())
            .unwrap()
            .mesh
            .repeat
            .is_some()
        {
            continue;
        }
        let loaded =
            irradiant_scene::load(path.to_str().unwrap()).unwrap_or_else(|e| panic!("{e}"));
        assert!(loaded.scene.triangle_count() > 0);
        assert!(
            !loaded.warnings.iter().any(|w| w.contains("texture")),
            "{}: {:?}",
            path.display(),
            loaded.warnings
        );
    }
}

#[test]
fn builtin_scenes_are_valid_and_carry_their_fixtures() {
    for (name, _) in irradiant_scene::BUILTIN_SCENES {
        let loaded = irradiant_scene::load(name).unwrap();
        assert!(loaded.warnings.is_empty(), "{name}: {:?}", loaded.warnings);
    }
    let rooms = irradiant_scene::load("two-rooms").unwrap().scene;
    assert!(rooms.region("dark-room").is_some() && !rooms.probe_volumes.is_empty());
    let cylinders = irradiant_scene::load("box-cylinders").unwrap().scene;
    // Some probes of the grid must lie inside the cylinders: that is the test's point.
    let v = &cylinders.probe_volumes[0];
    let step = (v.max - v.min) / (glam::Vec3::from(v.counts.map(|c| c as f32)) - 1.0);
    let mut inside = 0;
    for i in 0..v.counts[0] {
        for k in 0..v.counts[2] {
            let p = v.min + step * glam::Vec3::new(i as f32, 0.0, k as f32);
            if [
                (-0.75f32, -0.75f32),
                (0.75, -0.75),
                (-0.75, 0.75),
                (0.75, 0.75),
            ]
            .iter()
            .any(|(x, z)| (p.x - x).hypot(p.z - z) < 0.35)
            {
                inside += 1;
            }
        }
    }
    assert_eq!(
        inside, 4,
        "four probe columns should be swallowed by the cylinders"
    );
}

/// `[[material]]` overrides reach the scene's materials; the keys left out keep the file's.
#[test]
fn material_overrides_change_only_what_they_name() {
    let path = repo().join("scenes/cornell-box/mirror.toml");
    let mirror = irradiant_scene::load(path.to_str().unwrap()).unwrap().scene;
    let plain = irradiant_scene::load(
        repo()
            .join("../shared/scenes/cornell-box/CornellBox-Mirror.obj")
            .to_str()
            .unwrap(),
    )
    .unwrap()
    .scene;
    let find = |s: &irradiant_scene::Scene, name: &str| {
        s.materials.iter().find(|m| m.name == name).unwrap().clone()
    };
    let (tall, tall_before) = (find(&mirror, "tallBox"), find(&plain, "tallBox"));
    assert_eq!((tall.metallic, tall.roughness), (1.0, 0.05));
    assert_ne!(tall_before.metallic, 1.0);
    assert_eq!(tall.specular, tall_before.specular);
    assert_eq!(
        format!("{:?}", find(&mirror, "floor")),
        format!("{:?}", find(&plain, "floor"))
    );
}

#[test]
fn repeat_copies_instances_and_flatten_merges_them() {
    let dir = std::env::temp_dir().join(format!("irradiant-repeat-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let load = |extra: &str| {
        let path = dir.join("grid.toml");
        std::fs::write(&path, format!("[mesh]\npath = \"two-rooms\"\n{extra}")).unwrap();
        irradiant_scene::load(path.to_str().unwrap()).map(|l| l.scene)
    };
    let one = load("").unwrap();
    let spacing = glam::Vec3::new(20.0, 0.0, 30.0);
    let grid = load("repeat = [2, 1, 3]\nrepeat_spacing = [20.0, 0.0, 30.0]").unwrap();
    assert_eq!(grid.instances.len(), 6 * one.instances.len());
    assert_eq!(grid.triangle_count(), 6 * one.triangle_count());
    assert_eq!(
        grid.meshes.len(),
        one.meshes.len(),
        "copies share their meshes"
    );
    let last = grid.instances.last().unwrap();
    let original = one.instances.last().unwrap();
    assert_eq!(
        last.transform.w_axis.truncate(),
        original.transform.w_axis.truncate() + spacing * glam::Vec3::new(1.0, 0.0, 2.0)
    );
    let flat =
        load("repeat = [2, 1, 3]\nrepeat_spacing = [20.0, 0.0, 30.0]\nflatten = true").unwrap();
    assert_eq!((flat.meshes.len(), flat.instances.len()), (1, 1));
    assert_eq!(flat.triangle_count(), grid.triangle_count());
    // The flattened mesh is the instances in world space: the same bounds.
    let bounds = |s: &irradiant_scene::Scene| {
        s.instances
            .iter()
            .fold((glam::Vec3::MAX, glam::Vec3::MIN), |(lo, hi), i| {
                s.meshes[i.mesh as usize]
                    .positions
                    .iter()
                    .fold((lo, hi), |(lo, hi), &p| {
                        let w = i.transform.transform_point3(p);
                        (lo.min(w), hi.max(w))
                    })
            })
    };
    let (a, b) = (bounds(&grid), bounds(&flat));
    assert!(
        a.0.abs_diff_eq(b.0, 1e-3) && a.1.abs_diff_eq(b.1, 1e-3),
        "{a:?} {b:?}"
    );
    for (extra, key) in [
        ("repeat = [0, 1, 1]", "mesh.repeat"),
        ("repeat = [100, 100, 1]", "mesh.repeat"),
        (
            "repeat = [2, 1, 1]\nrepeat_spacing = [1e39, 0.0, 0.0]",
            "mesh.repeat_spacing",
        ),
    ] {
        let message = load(extra).unwrap_err().to_string();
        assert!(
            message.contains(key) && message.contains("grid.toml"),
            "{message}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `[[place]]` tables merge more scenes into the manifest's: their instances and lights moved
/// into place and named after the placement, their materials still theirs; a bad placement is
/// refused by name.
#[test]
fn places_merge_scenes_into_one_world() {
    let dir = std::env::temp_dir().join(format!("irradiant-place-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let load = |places: &str| {
        let path = dir.join("world.toml");
        std::fs::write(&path, format!("[mesh]\npath = \"cornell\"\n{places}")).unwrap();
        irradiant_scene::load(path.to_str().unwrap()).map(|l| l.scene)
    };
    let cornell = irradiant_scene::load("cornell").unwrap().scene;
    let rooms = irradiant_scene::load("two-rooms").unwrap().scene;
    let world = load(
        "[[place]]\nname = \"east\"\npath = \"two-rooms\"\nscale = 2.0\nrotation_y_degrees = 90.0\ntranslation = [100.0, 0.0, 0.0]\n",
    )
    .unwrap();
    assert_eq!(
        world.instances.len(),
        cornell.instances.len() + rooms.instances.len()
    );
    assert_eq!(
        world.triangle_count(),
        cornell.triangle_count() + rooms.triangle_count()
    );
    let placed = world.instances.last().unwrap();
    assert_eq!(placed.name, format!("east/{}", rooms.instances[0].name));
    // Its triangles keep their own materials, past the Cornell box's.
    let mesh = &world.meshes[placed.mesh as usize];
    let names: Vec<&str> = (mesh.triangle_materials.iter())
        .map(|&m| world.materials[m as usize].name.as_str())
        .collect();
    assert!(
        names.iter().all(|n| ["plaster", "floor"].contains(n)),
        "{names:?}"
    );
    // The lamp at (-2, 2.5, 0): doubled, turned 90° about y ((x, z) → (z, −x)), moved 100 m.
    let lamp = world.lights.iter().find(|l| l.name == "east/lamp").unwrap();
    assert!(
        lamp.position
            .abs_diff_eq(glam::Vec3::new(100.0, 5.0, 4.0), 1e-4),
        "{}",
        lamp.position
    );
    for (places, says) in [
        (
            "[[place]]\nname = \"a\"\npath = \"cornell\"\n[[place]]\nname = \"a\"\npath = \"cornell\"\n",
            "used twice",
        ),
        ("[[place]]\nname = \"\"\npath = \"cornell\"\n", "non-empty"),
        (
            "[[place]]\nname = \"a\"\npath = \"cornell\"\nscale = 0.0\n",
            "scale",
        ),
        (
            "[[place]]\nname = \"a\"\npath = \"missing.obj\"\n",
            "missing.obj",
        ),
    ] {
        let message = load(places).unwrap_err().to_string();
        assert!(message.contains(says), "{places}: {message}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
