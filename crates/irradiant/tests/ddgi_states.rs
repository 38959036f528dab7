//! Probe states (003 §6): probes that no surface reads — inside geometry, or with no surface
//! within a grid cell — stop tracing and blending, and the image stays what it was.

mod common;

use common::*;
use irradiant::GpuScene;
use irradiant::ddgi::{Ddgi, DdgiSettings, ProbeStateCounts};
use irradiant::frame::{FrameRenderer, FrameSettings, Technique};
use irradiant_scene::Scene;

/// Mean indirect radiance of the whole image after `frames` frames, and the probe states.
fn indirect_and_states(
    ctx: &irradiant::GpuContext,
    scene: &Scene,
    settings: &DdgiSettings,
    frames: u32,
) -> (f64, ProbeStateCounts) {
    let (indirect, states, _) = render_ddgi(ctx, scene, settings, frames);
    (indirect, states)
}

/// indirect_and_states, and the shadow rays ddgi/shade queued in the last frame.
fn render_ddgi(
    ctx: &irradiant::GpuContext,
    scene: &Scene,
    settings: &DdgiSettings,
    frames: u32,
) -> (f64, ProbeStateCounts, u32) {
    let size = (32, 32);
    let gpu_scene = GpuScene::new(ctx, scene, &Default::default()).unwrap();
    let mut frame =
        FrameRenderer::new(ctx, &gpu_scene, size.0, size.1, FrameSettings::default()).unwrap();
    let mut ddgi = Ddgi::new(ctx, &gpu_scene, &scene.probe_volumes[0], settings).unwrap();
    ddgi.bind_frame(ctx, &frame.buffers);
    for _ in 0..frames {
        frame
            .render(
                ctx,
                &gpu_scene,
                &scene.camera,
                Some(&mut ddgi as &mut dyn Technique),
                false,
                None,
            )
            .unwrap();
    }
    let indirect = frame.read(ctx, &frame.buffers.indirect).unwrap();
    let everywhere = vec![true; (size.0 * size.1) as usize];
    (
        masked_mean(&indirect, &everywhere),
        ddgi.read_state_counts(ctx).unwrap(),
        ddgi.read_queued_shadow_rays(ctx).unwrap(),
    )
}

#[test]
fn probes_no_surface_reads_stop_without_changing_the_image() {
    let Some(ctx) = gpu() else { return };
    // The Cornell box with a dense grid (0.3 apart): probes in mid-air sleep, probes in the
    // tall block switch off, probes near walls and blocks stay vigilant.
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    scene.probe_volumes[0].counts = [7, 7, 7];
    let on = DdgiSettings {
        rays_per_probe: 32,
        ..DdgiSettings::balanced()
    };
    let off = DdgiSettings {
        probe_states: false,
        ..on.clone()
    };
    // Classification ends at frame 5; a few more frames blend with the states in force.
    let frames = 12;
    let (with_states, counts) = indirect_and_states(&ctx, &scene, &on, frames);
    let (without, all) = indirect_and_states(&ctx, &scene, &off, frames);
    eprintln!("states {counts:?}: indirect {with_states:.5}; every probe {all:?}: {without:.5}");
    assert_eq!(all.vigilant, 343, "with states off every probe updates");
    assert_eq!(
        counts.vigilant + counts.off + counts.sleeping + counts.awake,
        343
    );
    assert!(counts.sleeping > 0, "mid-air probes should sleep");
    assert!(
        counts.off > 0,
        "probes inside the tall block should switch off"
    );
    assert!(counts.vigilant > 0 && counts.updating() < 300);
    assert!(with_states > 0.01, "the box should have indirect light");
    // Bound: the skipped probes are not read by any surface, so only the self-shadow bias's
    // shift of the query point into a sleeping probe's cell and the bounce light differ:
    // measured 0.03 % apart on lavapipe, allowed 5 %.
    assert!(
        (with_states / without - 1.0).abs() < 0.05,
        "probe states changed the image: {with_states} against {without}"
    );
}

/// ddgi/trace_shade (DdgiSettings::fuse_trace_and_shade) traces and shades in one pass: the same
/// rays, hits and random numbers as ddgi/trace then ddgi/shade, so the same image.
#[test]
fn fused_trace_and_shade_renders_what_the_two_passes_render() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let two = DdgiSettings {
        rays_per_probe: 32,
        ..DdgiSettings::balanced()
    };
    let one = DdgiSettings {
        fuse_trace_and_shade: true,
        ..two.clone()
    };
    let (separate, _) = indirect_and_states(&ctx, &scene, &two, 8);
    let (fused, _) = indirect_and_states(&ctx, &scene, &one, 8);
    eprintln!("indirect: trace + shade {separate:.6}, fused {fused:.6}");
    assert!(separate > 0.01, "the box should have indirect light");
    // Bound: the same arithmetic in another pass; only the compiler's float contraction may
    // differ.
    assert!(
        (fused / separate - 1.0).abs() < 1e-4,
        "fused {fused} against separate {separate}"
    );
}

/// With DdgiSettings::shadow_queue, ddgi/shade leaves the chosen light's shadow ray to
/// ddgi/shadow: the same rays and random numbers, so the same image but for the light's
/// contribution kept as f16.
#[test]
fn queued_shadow_rays_render_what_inline_shadow_rays_render() {
    let Some(ctx) = gpu() else { return };
    // two-rooms: a point light in one room, so that most hits need a shadow ray.
    let scene = irradiant_scene::load("two-rooms").unwrap().scene;
    let inline = DdgiSettings {
        rays_per_probe: 32,
        shadow_queue: false,
        ..DdgiSettings::balanced()
    };
    let queued = DdgiSettings {
        shadow_queue: true,
        ..inline.clone()
    };
    let (direct, _, none) = render_ddgi(&ctx, &scene, &inline, 8);
    let (deferred, states, count) = render_ddgi(&ctx, &scene, &queued, 8);
    let rays = states.updating() * 32;
    eprintln!("indirect: inline {direct:.6}, queued {deferred:.6}; {count} of {rays} rays queued");
    assert_eq!(none, 0, "nothing is queued with the queue off");
    // Rays that miss, hit backfaces or face away from the light queue nothing.
    assert!(
        count > rays / 10 && count < rays,
        "{count} of {rays} probe rays queued a shadow ray"
    );
    assert!(direct > 1e-3, "the rooms should have indirect light");
    // Bound: f16 rounding of each contribution (2⁻¹¹ relative) and float contraction.
    assert!(
        (deferred / direct - 1.0).abs() < 2e-3,
        "queued {deferred} against inline {direct}"
    );
}
