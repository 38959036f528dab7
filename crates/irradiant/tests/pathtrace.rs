//! The reference path tracer is proved, not assumed: a white furnace, and agreement with an
//! external renderer (Mitsuba 3) on the Cornell box.

mod common;

use glam::Vec3;
use irradiant::GpuScene;
use irradiant::frame::Image;
use irradiant::pathtrace::{PathSchedule, PathTraceSettings, PathTracer};
use irradiant_scene::{Light, LightKind, Scene};

fn render(
    ctx: &irradiant::GpuContext,
    scene: &irradiant_scene::Scene,
    size: u32,
    spp: u32,
    seed: u32,
) -> Image {
    let settings = PathTraceSettings {
        samples_per_pixel: spp,
        samples_per_dispatch: 16,
        max_bounces: 64,
        seed,
        light_sampling: Default::default(),
        schedule: Default::default(),
    };
    render_with(ctx, scene, size, &settings)
}

fn render_with(
    ctx: &irradiant::GpuContext,
    scene: &irradiant_scene::Scene,
    size: u32,
    settings: &PathTraceSettings,
) -> Image {
    let gpu_scene = GpuScene::new(ctx, scene, &Default::default()).unwrap();
    let mut tracer = PathTracer::new(ctx, &gpu_scene, size, size).unwrap();
    let image = tracer
        .render(ctx, &gpu_scene, &scene.camera, settings, |_, _| {})
        .unwrap();
    assert_eq!(tracer.traced_with(), settings.schedule.on(ctx));
    image
}

/// The wavefront traces the megakernel's paths: the same `path_step` from the same random
/// numbers, one bounce a pass instead of one path a thread. On the Cornell box (its emitter
/// sampled and hit under MIS, Russian roulette past the third bounce) and cut at two bounces,
/// every pixel agrees up to the order the samples are summed in. By default the box's tree is
/// too cheap for the wavefront to trace a bounce's rays apart; it is one wide tree, so the
/// wavefront can be made to, by lanes that fetch (`pathtrace/hits`): wherever more paths are
/// alive than its dispatch holds in runs of 64, so never with the default dispatch (1 024
/// paths: the kernels that can split, tracing in the bounce), and with one of at most 3 or 1
/// workgroups in runs of up to 384 or 1 024 paths, where a lane takes up to 6 or 16 rays, until
/// 192 or 64 paths or fewer are alive. Made so, a sample's first passes also defer their
/// vertices' shadow rays in those runs (`pathtrace/shadows`, `pathtrace/shadow_resolve`): the
/// emitter sample's, and on the box lit by a point light and the sun as well, three a vertex
/// (at 27×27, whose edge tiles are partly outside the image). With four point lights more, six
/// rays a vertex pass `DEFERRED_SHADOWS_MAX` and are traced in place. That the split then takes
/// part was checked by hand: a `pathtrace/hits` that leaves each run's last ray untraced fails
/// this test, and so do a `pathtrace/shadows` that lets blocked rays through and a punctual
/// light's deferred ray that stops short.
#[test]
fn the_wavefront_traces_the_megakernels_paths() {
    let Some(ctx) = common::gpu() else { return };
    let boxed = irradiant_scene::load("cornell").unwrap().scene;
    let mut lit = boxed.clone();
    lit.lights.push(Light::point(
        "lamp",
        Vec3::new(0.3, 1.2, 0.2),
        Vec3::ONE,
        0.5,
    ));
    lit.lights.push(Light {
        kind: LightKind::Directional,
        direction: Vec3::new(0.2, -0.4, -1.0).normalize(),
        ..Light::point("sun", Vec3::ZERO, Vec3::ONE, 1.0)
    });
    let all_dispatches = [
        None,
        Some(irradiant::shaders::FETCH_WORKGROUPS),
        Some(3),
        Some(1),
    ];
    let mut crowded = lit.clone();
    for i in 0..4 {
        let x = i as f32 * 0.4 - 0.6;
        crowded
            .lights
            .push(Light::point("lamp", Vec3::new(x, 1.5, 0.0), Vec3::ONE, 0.2));
    }
    struct Run<'a> {
        scene: &'a Scene,
        max_bounces: u32,
        size: u32,
        dispatches: &'a [Option<u32>],
        /// Whether a forced dispatch makes the wavefront with its shadow passes.
        defers: bool,
    }
    let run = |scene, max_bounces, size, dispatches, defers| Run {
        scene,
        max_bounces,
        size,
        dispatches,
        defers,
    };
    let runs = [
        run(&boxed, 64, 32, &all_dispatches, true),
        run(&boxed, 2, 32, &all_dispatches, true),
        // Paths that end within a few steps of the tail's pass (`WAVEFRONT_PASSES`, 4), its
        // lanes taking several paths each with one fetching workgroup.
        run(&boxed, 7, 32, &[None, Some(1)], true),
        // Two tail workgroups with runs of more than 64 paths, the second's starting past the
        // first's, and the bounce rays of the tail's queue traced apart before it.
        run(&boxed, 7, 64, &[Some(16)], true),
        // Paths that all end at the tail's first step.
        run(&boxed, 4, 32, &[None, Some(1)], true),
        run(&lit, 64, 27, &[None, Some(1)], true),
        run(&crowded, 64, 27, &[Some(1)], false),
    ];
    for Run {
        scene,
        max_bounces,
        size,
        dispatches,
        defers,
    } in runs
    {
        let gpu_scene = GpuScene::new(&ctx, scene, &Default::default()).unwrap();
        let settings = |schedule| PathTraceSettings {
            samples_per_pixel: 8,
            max_bounces,
            seed: 5,
            schedule,
            ..PathTraceSettings::fast()
        };
        let mega = render_with(&ctx, scene, size, &settings(PathSchedule::Megakernel));
        let mean = mega.mean();
        assert!(mean[0] > 0.01, "the megakernel's image is black: {mean:?}");
        for &fetch_workgroups in dispatches {
            let mut tracer = PathTracer::new(&ctx, &gpu_scene, size, size).unwrap();
            if let Some(workgroups) = fetch_workgroups {
                tracer = tracer.with_fetch_workgroups(workgroups);
            }
            let wave = tracer
                .render(
                    &ctx,
                    &gpu_scene,
                    &scene.camera,
                    &settings(PathSchedule::Wavefront),
                    |_, _| {},
                )
                .unwrap();
            assert_eq!(tracer.traced_with(), PathSchedule::Wavefront);
            assert_eq!(
                tracer.fetched_rays(),
                fetch_workgroups.is_some(),
                "whether the wavefront was made to trace the Cornell box's bounce rays apart"
            );
            // Made with the shadow passes; that they take rays depends on the dispatch (above).
            assert_eq!(
                tracer.deferred_shadows(),
                fetch_workgroups.is_some() && defers,
                "whether the wavefront was made with the passes that trace shadow rays apart"
            );
            let worst = mega
                .pixels
                .iter()
                .flatten()
                .zip(wave.pixels.iter().flatten())
                .map(|(m, w)| (m - w).abs() / m.abs().max(1e-3))
                .fold(0.0f32, f32::max);
            println!(
                "{} lights, max bounces {max_bounces}, fetching workgroups {fetch_workgroups:?}: \
                 mean {mean:?} against {:?}, worst relative difference {worst:.2e}",
                scene.lights.len(),
                wave.mean()
            );
            assert!(
                worst < 1e-4,
                "a pixel differs by {worst:.2e} (relative) between the schedules"
            );
        }
    }
}

/// A white Lambertian sphere under a uniform sky of radiance 1 must look exactly like the sky:
/// with albedo 1 nothing is absorbed, so every pixel converges to 1 whatever the bounce count.
#[test]
fn white_furnace_every_pixel_converges_to_the_sky() {
    let Some(ctx) = common::gpu() else { return };
    let scene = irradiant_scene::load("furnace").unwrap().scene;
    let image = render(&ctx, &scene, 32, 64, 1);
    let mean = image.mean();
    for c in mean {
        // The sphere is convex, so its pixels see the sky after one bounce: no path is ever
        // cut short, and the only noise is which sky direction was picked — none, the sky is
        // uniform. So the mean is 1 up to float error.
        assert!((c - 1.0).abs() < 2e-3, "furnace mean {mean:?} should be 1");
    }
    let worst = image
        .pixels
        .iter()
        .flatten()
        .map(|v| (v - 1.0).abs())
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-2, "a pixel deviates from 1 by {worst}");
}

/// A furnace with a dimmer sphere: a convex Lambertian sphere of albedo ρ under sky 1 shows ρ
/// where it covers the pixel, 1 elsewhere; so the image mean lies between ρ and 1 and every
/// pixel lies in [ρ, 1]. Catches a BRDF that creates or loses energy.
#[test]
fn grey_furnace_reflects_exactly_its_albedo() {
    let Some(ctx) = common::gpu() else { return };
    let mut scene = irradiant_scene::load("furnace").unwrap().scene;
    scene.materials[0].base_color = glam::Vec4::new(0.5, 0.5, 0.5, 1.0);
    let image = render(&ctx, &scene, 32, 16, 2);
    // The centre pixel is fully covered by the sphere.
    let centre = image.pixels[(16 * 32 + 16) as usize];
    for c in centre {
        assert!(
            (c - 0.5).abs() < 1e-3,
            "centre pixel {centre:?} should equal the albedo 0.5"
        );
    }
    for p in &image.pixels {
        for c in p {
            assert!(
                *c > 0.5 - 1e-3 && *c < 1.0 + 1e-3,
                "pixel {p:?} outside [albedo, 1]"
            );
        }
    }
}

/// Inside a closed sphere whose wall emits E and reflects ρ (Lambertian), every point sees the
/// same wall, so light that bounced k times adds exactly Eρ^k: a path tracer limited to n
/// indirect bounces must see E(1 + ρ + … + ρ^(n+1)) — the 1 is the wall's own emission, the
/// ρ its direct light — and E/(1 − ρ) with every bounce. Proves the one-bounce mode the
/// comparison lab measures SSIL against.
#[test]
fn an_integrating_sphere_counts_its_bounces_exactly() {
    let Some(ctx) = common::gpu() else { return };
    let mut scene = irradiant_scene::load("furnace").unwrap().scene;
    let mesh = &mut scene.meshes[0];
    for triangle in mesh.indices.chunks_exact_mut(3) {
        triangle.swap(1, 2);
    }
    for n in &mut mesh.normals {
        *n = -*n;
    }
    let (albedo, emission) = (0.5f32, 1.0f32);
    scene.materials[0].base_color = glam::Vec4::new(albedo, albedo, albedo, 1.0);
    scene.materials[0].emission = glam::Vec3::splat(emission);
    scene.sky = glam::Vec3::ZERO;
    scene.camera = irradiant_scene::Camera {
        position: glam::Vec3::ZERO,
        target: glam::Vec3::Z,
        up: glam::Vec3::Y,
        fov_y_degrees: 60.0,
    };
    let gpu_scene = GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    let mut tracer = PathTracer::new(&ctx, &gpu_scene, 16, 16).unwrap();
    let base = PathTraceSettings {
        samples_per_pixel: 256,
        samples_per_dispatch: 64,
        max_bounces: 64,
        seed: 3,
        light_sampling: Default::default(),
        schedule: Default::default(),
    };
    let mut measured = Vec::new();
    for bounces in [Some(0), Some(1), Some(2), None] {
        let settings = bounces.map_or(base.clone(), |n| base.clone().with_indirect_bounces(n));
        let image = tracer
            .render(&ctx, &gpu_scene, &scene.camera, &settings, |_, _| {})
            .unwrap();
        let mean = image.mean()[1] as f32;
        let expected = match bounces {
            Some(n) => (0..=n + 1)
                .map(|k| emission * albedo.powi(k as i32))
                .sum::<f32>(),
            None => emission / (1.0 - albedo),
        };
        measured.push((bounces, mean, expected));
    }
    eprintln!("indirect bounces, mean, expected: {measured:?}");
    for (bounces, mean, expected) in measured {
        // The tessellated sphere (24×48 quads) is not quite a sphere; 0.5% covers that and the
        // noise of 256 samples (lavapipe: within 0.04%) and keeps the counts (6% apart or
        // more) distinct.
        assert!(
            (mean - expected).abs() < 0.005 * expected,
            "{bounces:?} indirect bounces: mean {mean}, expected {expected}"
        );
    }
}

/// Our path tracer against Mitsuba 3 (scalar_rgb, 32768 spp, tools/mitsuba/cornell_reference.py)
/// on the original Cornell box at 64×64.
#[test]
fn cornell_box_matches_mitsuba() {
    let Some(ctx) = common::gpu() else { return };
    let manifest = common::repo_root().join("scenes/cornell-box/original.toml");
    let scene = irradiant_scene::load(manifest.to_str().unwrap())
        .unwrap()
        .scene;
    let reference = Image::read_exr(
        &common::repo_root().join("tests/golden/cornell-box/mitsuba-original-64.exr"),
        Some((64, 64)),
    )
    .unwrap();
    let ours = render(&ctx, &scene, 64, 256, 3);
    let (ours_mean, ref_mean) = (ours.mean(), reference.mean());
    let mut worst_mean = 0.0f64;
    for c in 0..3 {
        worst_mean = worst_mean.max((ours_mean[c] - ref_mean[c]).abs() / ref_mean[c]);
    }
    // 8×8 blocks: 64 pixels × 256 spp each, so per-block noise is a few per cent at most.
    let mut block_errors = Vec::new();
    for by in 0..8 {
        for bx in 0..8 {
            let mut sums = [[0f64; 3]; 2];
            for y in 0..8 {
                for x in 0..8 {
                    let i = ((by * 8 + y) * 64 + bx * 8 + x) as usize;
                    for (c, (o, r)) in ours.pixels[i].iter().zip(&reference.pixels[i]).enumerate() {
                        sums[0][c] += *o as f64;
                        sums[1][c] += *r as f64;
                    }
                }
            }
            let lum = |s: [f64; 3]| 0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2];
            let reference_lum = lum(sums[1]);
            if reference_lum > 1e-3 {
                block_errors.push((lum(sums[0]) - reference_lum).abs() / reference_lum);
            }
        }
    }
    let mean_block_error = block_errors.iter().sum::<f64>() / block_errors.len() as f64;
    eprintln!(
        "image mean: ours {ours_mean:?}, Mitsuba {ref_mean:?}; worst channel error {worst_mean:.4}; mean 8×8-block error {mean_block_error:.4}"
    );
    // Bounds: the issue asks for mean relative error under 2 %. At 256 spp the noise of the
    // whole-image mean is ~0.3 %, so 2 % leaves room for noise but not for a missing bounce
    // (one bounce less is −20 %), a wrong light pdf (×2) or a one-sided wall.
    assert!(
        worst_mean < 0.02,
        "image mean differs from Mitsuba by {:.2} %",
        worst_mean * 100.0
    );
    // Per-block noise at 256 spp × 64 pixels is about 1 % (0.65 % seen on lavapipe, with the
    // image mean 0.16 % off); 4 % catches local errors (a wrong
    // shadow, a misplaced light) that the global mean can hide.
    assert!(
        mean_block_error < 0.04,
        "8×8 blocks differ from Mitsuba by {:.2} % on average",
        mean_block_error * 100.0
    );
}
