//! The probe rays' layout on the GPU (ray order, probes per workgroup) changes speed only: the
//! same rays give the same light.

mod common;

use common::*;
use irradiant::ddgi::DdgiSettings;

fn luminance(image: &irradiant::frame::Image) -> f64 {
    masked_mean(image, &vec![true; image.pixels.len()])
}

fn settings(coherent_rays: bool, probes_per_group: u32) -> DdgiSettings {
    let mut s = DdgiSettings::balanced();
    // Not a multiple of 64: the last workgroup of each probe is partly idle.
    s.volume.rays_per_probe = 100;
    s.speed.coherent_rays = coherent_rays;
    s.speed.probes_per_group = probes_per_group;
    s
}

#[test]
fn probes_per_group_trace_the_same_rays() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let reference = render_frames(&ctx, &scene, (24, 24), Some(&settings(true, 1)), 3).indirect;
    assert!(luminance(&reference) > 0.01, "no indirect light to compare");
    for per_group in [4, 64] {
        let grouped = render_frames(&ctx, &scene, (24, 24), Some(&settings(true, per_group)), 3);
        // Each ray keeps its slot (and so its random numbers): results match to the bit.
        assert_eq!(
            grouped.indirect.pixels, reference.pixels,
            "{per_group} probes a workgroup changed the light"
        );
    }
}

#[test]
fn coherent_order_converges_to_the_same_light() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let fibonacci = render_frames(&ctx, &scene, (32, 32), Some(&settings(false, 1)), 30);
    let coherent = render_frames(&ctx, &scene, (32, 32), Some(&settings(true, 1)), 30);
    let (a, b) = (
        luminance(&fibonacci.indirect),
        luminance(&coherent.indirect),
    );
    // Same directions, shaded with different random numbers: the means differ by noise only
    // (1.2 % measured on lavapipe; another seed of the plain order differs by 0.7 %). Rays
    // paired with the wrong directions would be off by far more.
    assert!((a - b).abs() < 0.05 * a, "fibonacci {a} vs coherent {b}");
}

/// ddgi/trace's and ddgi/shadow's lanes fetch their next ray (`speed.fetch_rays`) on a scene of
/// one wide tree: the same hits, so the same light to the bit. `two-rooms`' point light sends
/// the probe rays' hits shadow rays through ddgi/shadow's queue; dispatches of at most two
/// workgroups give runs past 64 rays, across probes.
#[test]
fn lanes_that_fetch_their_rays_give_the_same_light() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("two-rooms").unwrap().scene;
    assert!(
        !scene.lights.is_empty(),
        "no punctual light: no queued shadow rays"
    );
    let gpu_scene = irradiant::GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    let mut fetching = settings(true, 1);
    fetching.speed.fetch_workgroups = 2;
    let probe_rays = irradiant::ddgi::volume_descs(&scene, &fetching)
        .iter()
        .map(|desc| irradiant::probes::ProbeGrid::new(desc).probe_count as u64 * 100)
        .max()
        .unwrap();
    assert!(
        fetching.fetches_rays(&gpu_scene, probe_rays),
        "the scene does not take the fetching loop"
    );
    let mut one_a_thread = fetching.clone();
    one_a_thread.speed.fetch_rays = false;
    let a = render_frames(&ctx, &scene, (24, 24), Some(&fetching), 3).indirect;
    let b = render_frames(&ctx, &scene, (24, 24), Some(&one_a_thread), 3).indirect;
    assert!(luminance(&a) > 0.01, "no indirect light to compare");
    assert_eq!(a.pixels, b.pixels, "fetching changed the light");
}
