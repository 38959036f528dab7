//! Sizes (issues 10 and 14): every pass's dispatch fits the adapter at the largest sizes the
//! settings accept, and a run too large for the adapter is refused before anything is
//! allocated, with a message that names the setting to change.

mod common;

use irradiant::ddgi::DdgiSettings;
use irradiant::frame::{Frame, FrameNeeds, FrameSettings};
use irradiant::lightfield::LightfieldSettings;
use irradiant::pathtrace::PathTracer;
use irradiant::raycast::RayCaster;
use irradiant::registry::REGISTRY;
use irradiant::ssil::{HybridSettings, SsilSettings, StartResolution};
use irradiant::{Preset, Session, SessionSettings, TechniqueSpec};
use irradiant_gpu::MAX_WORKGROUPS_PER_DIMENSION;

/// The largest image side `--size` accepts.
const LARGEST_SIDE: u32 = 16384;

/// The Cornell box with the largest probe grid a manifest accepts.
fn largest_grid_scene() -> irradiant_scene::Scene {
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    let limit = irradiant_scene::MAX_PROBES_PER_AXIS;
    scene.probe_volumes[0].counts = [limit; 3];
    scene
}

/// A spec of every registered technique at its most demanding settings.
fn largest_spec(name: &str, probes_per_group: u32) -> TechniqueSpec {
    let mut ddgi = DdgiSettings::quality();
    ddgi.volume.rays_per_probe = 4096;
    ddgi.volume.irradiance_texels = 16;
    ddgi.volume.distance_texels = 30;
    ddgi.speed.probes_per_group = probes_per_group;
    let mut ssil = SsilSettings::quality();
    ssil.start = StartResolution::Full;
    ssil.levels = 6;
    ssil.samples = 1024;
    ssil.bounces = 4;
    // Light-field probes: the most probes one bake dispatch holds, the largest maps.
    let mut lightfield = LightfieldSettings::quality();
    lightfield.bake.probe_counts = [64, 64, 15];
    lightfield.bake.resolution = 4096;
    lightfield.bake.prefilter_resolution = 256;
    lightfield.bake.irradiance_texels = 128;
    lightfield.bake.distance_texels = 128;
    match name {
        "none" => TechniqueSpec::new(name, Preset::Quality),
        n if n.starts_with("lightfield") => TechniqueSpec::with_settings(name, &lightfield),
        "ssil" => TechniqueSpec::with_settings(name, &ssil),
        "ssil+ddgi" => TechniqueSpec::with_settings(
            name,
            &HybridSettings {
                ssil,
                ddgi,
                near_field: 4.0,
                far_field_while_young: true,
                bent_fill: true,
            },
        ),
        _ => TechniqueSpec::with_settings(name, &ddgi),
    }
}

#[test]
fn every_registered_pass_fits_the_adapter_at_the_largest_sizes() {
    // The adapter's limit where there is one (no GPU work is done); every adapter allows 65 535.
    let limit = common::gpu().map_or(MAX_WORKGROUPS_PER_DIMENSION, |ctx| {
        ctx.device.limits().max_compute_workgroups_per_dimension
    });
    let scene = largest_grid_scene();
    let sizes = [
        (LARGEST_SIDE, LARGEST_SIDE),
        (LARGEST_SIDE, 1),
        (1, 1),
        (7680, 4320),
    ];
    let mut checked = 0;
    for size in sizes {
        let mut all = Frame::dispatches(size, FrameNeeds { pyramid_levels: 5 });
        all.push(("pathtrace/trace", PathTracer::workgroups(size.0, size.1)));
        all.push((
            "raycast/trace",
            RayCaster::workgroups(size.0 as u64 * size.1 as u64),
        ));
        for kind in REGISTRY {
            for probes_per_group in [1, 64] {
                all.extend(
                    kind.dispatches(&largest_spec(kind.name(), probes_per_group), &scene, size)
                        .unwrap(),
                );
            }
        }
        for (label, groups) in &all {
            assert!(
                groups.fits(limit),
                "{label} at {size:?} asks for {:?} workgroups; the adapter allows {limit} a dimension",
                groups.counts()
            );
            checked += 1;
        }
        // Each dispatch covers its work: the image passes every pixel, DDGI every probe ray.
        let image = all.iter().find(|(l, _)| *l == "frame/compose").unwrap().1;
        assert!(
            image.counts()[0] as u64 * 8 >= size.0 as u64
                && image.counts()[1] as u64 * 8 >= size.1 as u64
        );
        let rays = all.iter().find(|(l, _)| *l == "ddgi/trace").unwrap().1;
        let probes = 256u64.pow(3);
        assert!(
            rays.total() * 64 >= probes * 4096,
            "ddgi/trace covers {:?}",
            rays.counts()
        );
    }
    assert!(checked > 50, "only {checked} dispatches were checked");
}

#[test]
fn runs_too_large_for_the_adapter_are_refused_before_anything_is_allocated() {
    let Some(ctx) = common::gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let settings = |size, technique| SessionSettings {
        size,
        frame: FrameSettings::default(),
        technique,
        ..Default::default()
    };
    // The image: 16384² needs about 36 GiB of frame textures, more than this adapter's memory
    // (lavapipe reports the machine's) — the message names --size.
    let message = Session::new(
        ctx.clone(),
        scene.clone(),
        settings(
            (LARGEST_SIDE, LARGEST_SIDE),
            TechniqueSpec::new("none", Preset::Balanced),
        ),
    )
    .err()
    .expect("a 16384² frame does not fit")
    .to_string();
    assert!(
        message.contains("--size") && message.contains("GiB"),
        "{message}"
    );
    // The probe grid: 256³ probes' rays need tens of GiB in one buffer — the message names the
    // probe counts and the rays per probe.
    let huge = largest_grid_scene();
    let message = Session::new(
        ctx.clone(),
        huge.clone(),
        settings((64, 64), TechniqueSpec::new("ddgi", Preset::Balanced)),
    )
    .err()
    .expect("256³ probes do not fit")
    .to_string();
    assert!(
        message.contains("probe counts") && message.contains("rays_per_probe"),
        "{message}"
    );
    // Cascades too large: the message names the cascade settings, not the scene's counts.
    let mut cascades = TechniqueSpec::new("ddgi", Preset::Balanced);
    cascades.settings = toml::from_str(
        "[volume]\ncascades = 2\ncascade_probes = [256, 64, 256]\nrays_per_probe = 1024",
    )
    .unwrap();
    let message = Session::new(ctx.clone(), scene.clone(), settings((64, 64), cascades))
        .err()
        .expect("two cascades of 256 × 64 × 256 probes do not fit")
        .to_string();
    assert!(
        message.contains("cascade_probes") && !message.contains("probe_volume"),
        "{message}"
    );
    // Nothing reached the device: no validation error is pending, and the device still works.
    ctx.check("the refusals").unwrap();
    // The per-technique budget: what DDGI would allocate is listed before anything is made,
    // sized by its settings.
    let plan = Session::plan(
        &scene,
        &settings((64, 64), TechniqueSpec::new("ddgi", Preset::Balanced)),
    )
    .unwrap();
    let samples = plan
        .iter()
        .find(|a| a.label == "ddgi/samples")
        .expect("DDGI's ray samples are planned");
    let probes: u64 = scene.probe_volumes[0]
        .counts
        .iter()
        .map(|&c| c as u64)
        .product();
    assert_eq!(samples.bytes, probes * 256 * 16, "probes × rays × 16 bytes");
    assert!(plan.iter().any(|a| a.label == "frame/gbuffer_depth"));
    let mut session = Session::new(
        ctx.clone(),
        scene,
        settings((16, 16), TechniqueSpec::new("ddgi", Preset::Fast)),
    )
    .unwrap();
    session.render().unwrap();
}
