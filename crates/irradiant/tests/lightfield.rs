//! Light-field probes: the baked maps against the BVH, light-field ray traces against the
//! BVH's, the three shading algorithms against the path tracer, the disk cache, and bad input.

mod common;

use common::*;
use irradiant::TechniqueSpec;
use irradiant::lightfield::{Lightfield, LightfieldSettings};

/// Small bakes for lavapipe: 2×2×2 probes, 64² maps.
fn small(settings: &mut LightfieldSettings) {
    settings.bake.probe_counts = [2, 2, 2];
    settings.bake.resolution = 64;
    settings.bake.prefilter_resolution = 16;
    settings.bake.irradiance_texels = 8;
    settings.bake.distance_texels = 16;
    settings.bake.bounces = 1;
    settings.bake.emitter_samples = 4;
    settings.shade.naive_rays = 4;
}

fn spec(name: &str, settings: &LightfieldSettings) -> TechniqueSpec {
    TechniqueSpec::with_settings(name, settings)
}

#[test]
fn smoke() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut settings = LightfieldSettings::balanced();
    small(&mut settings);
    for name in ["lightfield", "lightfield-traced", "lightfield-naive"] {
        let mut session = session(&ctx, &scene, (64, 64), spec(name, &settings));
        for _ in 0..4 {
            session.render().unwrap();
        }
        let lf = session.technique_as::<Lightfield>().unwrap();
        eprintln!("{name}: {:?}", lf.bake_report());
        let indirect = session.indirect().unwrap();
        eprintln!(
            "{name}: mean indirect {:?}, total {:?}",
            indirect.mean(),
            session.image().unwrap().mean()
        );
        irradiant::frame::write_png(
            std::path::Path::new(&format!("/tmp/lf/{name}.png")),
            &session.tonemapped().unwrap(),
            64,
            64,
        )
        .unwrap();
        session.set_show_probes(true);
        session.render().unwrap();
        irradiant::frame::write_png(
            std::path::Path::new(&format!("/tmp/lf/{name}-view.png")),
            &session.tonemapped().unwrap(),
            64,
            64,
        )
        .unwrap();
    }
}

#[test]
fn agreement_probe() {
    let Some(ctx) = gpu() else { return };
    for (scene_name, counts, res) in [
        ("cornell", [2, 2, 2], 64),
        ("cornell", [2, 2, 2], 128),
        ("cornell", [3, 3, 3], 128),
    ] {
        let scene = irradiant_scene::load(scene_name).unwrap().scene;
        let mut settings = LightfieldSettings::balanced();
        small(&mut settings);
        settings.bake.probe_counts = counts;
        settings.bake.resolution = res;
        let mut session = session(&ctx, &scene, (64, 64), spec("lightfield", &settings));
        session.render().unwrap();
        let a = irradiant::lightfield::agreement::measure(&session, 4096, 7).unwrap();
        eprintln!(
            "{scene_name} {counts:?} {res}: share {:.3} {a:?}",
            a.share()
        );
    }
}
