//! The platform: the frame's G-buffer pyramid against a CPU oracle, settings that change live
//! against those that rebuild, and DDGI over several probe volumes and the light between them.

mod common;

use common::*;
use irradiant::ddgi::{Ddgi, DdgiSettings};
use irradiant::frame::{Frame, FrameNeeds, FrameSettings};
use irradiant::{GpuScene, TechniqueSpec};
use std::sync::Arc;

/// Each level of the pyramid takes the voted normal and depth (Soler et al. eq. 5) and the mean
/// radiance and albedo of the 2×2 texels under it that see a surface.
#[test]
fn pyramid_levels_vote_and_average_the_level_below() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let gpu_scene = GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    let levels = 4;
    let mut frame = Frame::new(
        &ctx,
        &gpu_scene,
        (48, 40),
        FrameSettings::default(),
        FrameNeeds {
            pyramid_levels: levels,
        },
    )
    .unwrap();
    frame.prepare(&ctx, &scene.camera);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    frame.record_inputs(&mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
    frame.finish();
    let (mut w, mut h) = frame.size();
    let mut below: Vec<Vec<[f32; 4]>> =
        ["pyramid_normal_depth", "pyramid_radiance", "pyramid_albedo"]
            .iter()
            .map(|n| read_level(&ctx, &frame, n, 0))
            .collect();
    // Level 0 is the G-buffer: sky where its depth is negative, surfaces elsewhere.
    let depth: Vec<f32> = bytemuck::pod_collect_to_vec(
        &irradiant_gpu::read_texture(&ctx, frame.resources.texture("gbuffer_depth"), 4).unwrap(),
    );
    for (i, d) in depth.iter().enumerate() {
        assert_eq!(
            *d < 0.0,
            below[0][i][3] < 0.0,
            "texel {i}: G-buffer depth {d}, pyramid {:?}",
            below[0][i]
        );
    }
    let mut checked = 0;
    for level in 1..levels {
        let (lw, lh) = ((w / 2).max(1), (h / 2).max(1));
        let this: Vec<Vec<[f32; 4]>> =
            ["pyramid_normal_depth", "pyramid_radiance", "pyramid_albedo"]
                .iter()
                .map(|n| read_level(&ctx, &frame, n, level))
                .collect();
        let sigma = FrameSettings::default().pyramid;
        let gaussian = |x: f32, s: f32| (-x * x / (2.0 * s * s)).exp();
        let at = |x: i64, y: i64| -> Option<[f32; 4]> {
            (x >= 0 && y >= 0 && x < w as i64 && y < h as i64)
                .then(|| below[0][(y as u32 * w + x as u32) as usize])
                .filter(|t| t[3] >= 0.0)
        };
        let vote = |x: i64, y: i64| {
            let own = at(x, y).unwrap();
            let n = glam::Vec3::new(own[0], own[1], own[2]);
            [(0, 0), (1, 0), (-1, 0), (0, 1), (0, -1)]
                .iter()
                .filter_map(|&(dx, dy)| {
                    at(x + dx, y + dy).map(|o| {
                        gaussian(
                            (dx as i32).abs() as f32 + (dy as i32).abs() as f32,
                            sigma.pixel_sigma,
                        ) * gaussian(
                            1.0 - glam::Vec3::new(o[0], o[1], o[2]).dot(n),
                            sigma.normal_sigma,
                        ) * gaussian((o[3] - own[3]) / own[3].max(1e-6), sigma.depth_sigma)
                    })
                })
                .sum::<f32>()
        };
        for y in 0..lh {
            for x in 0..lw {
                let mut sums = [[0f32; 4]; 3];
                let mut count = 0.0;
                let mut votes = Vec::new();
                for k in 0..4 {
                    let (sx, sy) = ((2 * x + (k & 1)).min(w - 1), (2 * y + (k >> 1)).min(h - 1));
                    let i = (sy * w + sx) as usize;
                    if below[0][i][3] >= 0.0 {
                        for c in 0..3 {
                            for j in 0..4 {
                                sums[c][j] += below[c][i][j];
                            }
                        }
                        count += 1.0;
                        votes.push((vote(sx as i64, sy as i64), below[0][i]));
                    }
                }
                let got = |c: usize| this[c][(y * lw + x) as usize];
                if count == 0.0 {
                    assert!(got(0)[3] < 0.0, "level {level} ({x}, {y}) should be sky");
                    continue;
                }
                // The winner's normal and depth, as they are: any texel whose vote is the
                // largest (to rounding).
                let top = votes.iter().map(|v| v.0).fold(f32::MIN, f32::max);
                assert!(
                    votes
                        .iter()
                        .any(|(score, t)| *score >= top - 1e-4 * top.max(1.0) && *t == got(0)),
                    "level {level} ({x}, {y}): {:?} is not the voted texel of {votes:?}",
                    got(0)
                );
                for (c, channel_sums) in sums.iter().enumerate().skip(1) {
                    for (j, sum) in channel_sums.iter().enumerate() {
                        let want = sum / count;
                        // f16 storage: 1e-3 relative.
                        assert!(
                            (got(c)[j] - want).abs() <= 2e-3 * want.max(0.05),
                            "level {level} ({x}, {y}) channel {c}: {} against {want}",
                            got(c)[j]
                        );
                    }
                }
                checked += 1;
            }
        }
        below = this;
        (w, h) = (lw, lh);
    }
    assert!(checked > 500, "{checked} texels checked");
}

/// Settings that only change the update apply between frames (the probes keep their light);
/// settings that size the volumes rebuild them (the probes start over).
#[test]
fn live_settings_apply_between_frames_and_sizes_rebuild() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut settings = DdgiSettings::fast();
    settings.volume.rays_per_probe = 32;
    let mut session = session(&ctx, &scene, (24, 24), spec(Some(&settings)));
    for _ in 0..4 {
        session.render().unwrap();
    }
    let frames = |s: &irradiant::Session| s.technique_as::<Ddgi>().unwrap().volume().frame;
    assert_eq!(frames(&session), 4);
    settings.update.hysteresis = 0.5;
    settings.update.self_shadow_bias = 0.1;
    session
        .set_technique(TechniqueSpec::with_settings("ddgi", &settings))
        .unwrap();
    assert_eq!(frames(&session), 4, "a live change keeps the probes");
    assert_eq!(
        session
            .technique_as::<Ddgi>()
            .unwrap()
            .settings()
            .update
            .hysteresis,
        0.5
    );
    session.render().unwrap();
    assert_eq!(frames(&session), 5);
    settings.volume.rays_per_probe = 64;
    session
        .set_technique(TechniqueSpec::with_settings("ddgi", &settings))
        .unwrap();
    assert_eq!(frames(&session), 0, "a new ray count rebuilds the volume");
    session.render().unwrap();
    // Another technique entirely, and an unknown one: refused with the registry's names.
    session.set_technique(spec(None)).unwrap();
    assert_eq!(session.technique().name(), "none");
    let e = session
        .set_technique(TechniqueSpec::new("magic", irradiant::Preset::Fast))
        .unwrap_err()
        .to_string();
    assert!(e.contains("'magic'") && e.contains("ddgi"), "{e}");
}

/// Two probe volumes: both update, and the resolve's weights sum to one at every surface
/// pixel, so the light is the blend of the two volumes' and no pixel is lit twice or not at all.
#[test]
fn ddgi_blends_every_volume_of_the_scene() {
    let Some(ctx) = gpu() else { return };
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    let coarse = scene.probe_volumes[0].clone();
    let mut fine = coarse.clone();
    fine.name = "fine".into();
    fine.counts = [6, 6, 6];
    fine.max = (coarse.min + coarse.max) * 0.5 + (coarse.max - coarse.min) * 0.25;
    let single = {
        let mut s = session(&ctx, &scene, (32, 32), spec(Some(&DdgiSettings::fast())));
        for _ in 0..30 {
            s.render().unwrap();
        }
        masked_mean(&s.indirect().unwrap(), &vec![true; 32 * 32])
    };
    scene.probe_volumes.push(fine);
    let mut s = session(&ctx, &scene, (32, 32), spec(Some(&DdgiSettings::fast())));
    for _ in 0..30 {
        s.render().unwrap();
    }
    let ddgi = s.technique_as::<Ddgi>().unwrap();
    assert_eq!(ddgi.volumes.len(), 2);
    // Finest first.
    assert_eq!(ddgi.volumes[0].grid.probe_count, 216);
    assert!(
        ddgi.volumes.iter().all(|v| v.frame == 30),
        "every volume updates"
    );
    let weights: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(
        &irradiant_gpu::read_texture(&ctx, s.frame().resources.texture("indirect"), 16).unwrap(),
    );
    let gbuffer = s.gbuffer().unwrap();
    for (w, g) in weights.iter().zip(&gbuffer) {
        if g.depth >= 0.0 {
            assert!(
                (w[3] - 1.0).abs() < 1e-5,
                "a surface pixel's volume weights sum to {}",
                w[3]
            );
        }
    }
    let blended = masked_mean(&s.indirect().unwrap(), &vec![true; 32 * 32]);
    eprintln!("mean indirect: one volume {single:.5}, two volumes {blended:.5}");
    // Bound: the same light seen through two grids; they differ by interpolation and noise.
    assert!(
        (blended / single - 1.0).abs() < 0.15,
        "{blended} against {single}"
    );
}

/// Light passes between volumes (003 §7.4): two-rooms with a finer volume over its dark room, reaching past the room's outer walls as a cascade does. The dark room's light comes
/// through the door as the lit room's bounce. Its probe rays that land in the lit room read the
/// volume over both rooms, so the room's indirect light is that volume's alone; read from
/// their own volume, which holds no light of the lit room, it falls short.
#[test]
fn light_passes_between_volumes() {
    let Some(ctx) = gpu() else { return };
    let mut scene = irradiant_scene::load("two-rooms").unwrap().scene;
    let dark_room = scene
        .regions
        .iter()
        .find(|r| r.name == "dark-room")
        .unwrap()
        .clone();
    let mut settings = DdgiSettings::fast();
    let dark_room_light = |scene: &irradiant_scene::Scene, settings: &DdgiSettings| {
        let mut s = session(&ctx, scene, (32, 32), spec(Some(settings)));
        for _ in 0..40 {
            s.render().unwrap();
        }
        let mask = region_mask(&s.gbuffer().unwrap(), &dark_room);
        assert!(
            mask.iter().filter(|&&m| m).count() > 200,
            "the camera sees the dark room"
        );
        masked_mean(&s.indirect().unwrap(), &mask)
    };
    let one_volume = dark_room_light(&scene, &settings);
    // The dark room is x in [0.05, 3.9], y in [0, 3], z in [-1.9, 1.9] inside.
    let mut dark = scene.probe_volumes[0].clone();
    assert_eq!(
        dark.counts,
        [10, 4, 5],
        "the volume over both rooms is the coarser"
    );
    dark.name = "dark-room".into();
    dark.min = glam::Vec3::new(0.45, -0.6, -2.6);
    dark.max = glam::Vec3::new(4.6, 3.6, 2.6);
    dark.counts = [6, 6, 7];
    scene.probe_volumes.push(dark);
    let between = dark_room_light(&scene, &settings);
    settings.update.light_between_volumes = false;
    let own = dark_room_light(&scene, &settings);
    eprintln!(
        "dark room's indirect light: one volume {one_volume:.5}, a finer one nested {between:.5}, \
         its rays reading their own volume {own:.5}"
    );
    // Bounds: on lavapipe 0.3 % and 13.5 % apart; two grids and their noise differ by a few
    // per cent.
    assert!(
        (between / one_volume - 1.0).abs() < 0.04,
        "{between} against one volume's {one_volume}"
    );
    assert!(
        own < one_volume * 0.92,
        "without the lit room's bounce the nested volume's probes are darker: {own} against \
         {one_volume}"
    );
}

/// A pass made again on one context is the one made before, so that a technique made again (a
/// preset changed in the viewer, a bench's `--vary`) compiles none of its pipelines twice;
/// other constants make another pass, and another context makes its own.
#[test]
fn a_pass_made_again_is_taken_from_its_context() {
    let Some(ctx) = gpu() else { return };
    let source = "@group(0) @binding(0) var<storage, read_write> out: array<u32>;\n\
                  @compute @workgroup_size(1) fn main() { out[0] = K; }";
    let make = |ctx: &irradiant::GpuContext, k: &str| {
        let desc = irradiant_gpu::PassDesc::new("test/cache", source).constants([("K", k.into())]);
        irradiant::shaders::pass(ctx, &desc).unwrap()
    };
    let first = make(&ctx, "1u");
    assert!(Arc::ptr_eq(&first, &make(&ctx, "1u")), "made twice");
    assert!(!Arc::ptr_eq(&first, &make(&ctx, "2u")), "other constants");
    let Some(other) = gpu() else { return };
    assert!(!Arc::ptr_eq(&first, &make(&other, "1u")), "another context");
}
