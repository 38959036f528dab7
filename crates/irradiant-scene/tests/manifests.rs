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
