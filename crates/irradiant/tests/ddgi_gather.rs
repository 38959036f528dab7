//! DDGI's final gather (`DdgiSettings::gather`): rays traced from the pixels, their hits lit by
//! the probes, averaged over frames by ddgi/temporal. Against the path tracer on lavapipe-sized
//! built-in scenes, with figures printed for docs/ddgi.md.

mod common;

use common::*;
use irradiant::ddgi::DdgiSettings;

/// The balanced settings, converging quickly on a CPU adapter (as ddgi_quality.rs's), with the
/// gather at `rays` a pixel every `interval` frames (0: the query alone).
fn gathering(rays: u32, interval: u32) -> DdgiSettings {
    let mut s = DdgiSettings::balanced();
    s.update.hysteresis = 0.9;
    s.gather.rays_per_pixel = rays;
    s.gather.pixel_interval = interval;
    s.gather.history_frames = 32;
    s
}

/// The Cornell box's error at its 4×4×4 probes lies in the query's interpolation between probe
/// layers (docs/ddgi.md, "Targets"); traced rays from the pixels take the first bounce off it.
/// Four rays a pixel, so that the gather's noise at 32 frames of history stays under the
/// reference's own at 64×64 (lavapipe: 0.0526 against the query's 0.0817).
#[test]
fn the_gather_brings_the_cornell_box_closer_to_the_path_tracer() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let reference = path_trace(&ctx, &scene, size, 1024);
    let query = render_frames(&ctx, &scene, size, Some(&gathering(0, 1)), 150);
    let gather = render_frames(&ctx, &scene, size, Some(&gathering(4, 1)), 150);
    let (q, g) = (
        flip_mean(&reference, &query.total),
        flip_mean(&reference, &gather.total),
    );
    eprintln!("cornell FLIP against the path tracer: query {q:.4}, gather {g:.4}");
    assert!(
        g < 0.8 * q,
        "the gather must take a fifth of the query's FLIP off at least"
    );
}

/// Traced rays see the dividing wall, so no light may leak through it; and a ray's hit beside
/// the wall it left from must not read the probes beyond it (the bias towards the viewer, which
/// is capped at half the ray's length: without the cap the wall's seams with the floor, the
/// ceiling and the outer walls read bright).
#[test]
fn the_gather_keeps_the_dark_room_dark_to_its_seams() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("two-rooms").unwrap().scene;
    let size = (64, 48);
    let gather = render_frames(&ctx, &scene, size, Some(&gathering(1, 1)), 150);
    let reference = path_trace(&ctx, &scene, size, 1024);
    let truth = path_traced_indirect(&reference, &gather);
    let mask = region_mask(&gather.gbuffer, scene.region("dark-room").unwrap());
    let (pt, g) = (
        masked_mean(&truth, &mask),
        masked_mean(&gather.indirect, &mask),
    );
    let tiles = block_ratios(&gather.indirect, &truth, &mask, 4);
    let worst = tiles.iter().cloned().fold(0.0, f64::max);
    eprintln!(
        "two-rooms dark room with the gather: {:+.1} % against the path tracer; brightest 4×4 tile {worst:.2} of the truth",
        (g / pt - 1.0) * 100.0
    );
    assert!(
        (g / pt - 1.0).abs() < 0.1,
        "the dark room must stay within 10 % of the path tracer"
    );
    assert!(
        worst < 1.5,
        "a tile of the dark room reads {worst:.2} of the truth"
    );
}

/// With a pixel interval the tiles gather in turn and keep their mean in between: the image
/// converges to the one every pixel gathers for, tile by tile.
#[test]
fn tiles_that_gather_in_turn_converge_to_the_every_frame_gather() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let every = render_frames(&ctx, &scene, size, Some(&gathering(1, 1)), 120);
    let mut in_turn = gathering(1, 4);
    in_turn.gather.history_frames = 128;
    let turns = render_frames(&ctx, &scene, size, Some(&in_turn), 120);
    let query = render_frames(&ctx, &scene, size, Some(&gathering(0, 1)), 120);
    let mask: Vec<bool> = every.gbuffer.iter().map(|g| g.depth >= 0.0).collect();
    let against_every = block_ratios(&turns.indirect, &every.indirect, &mask, 8);
    let query_against_every = block_ratios(&query.indirect, &every.indirect, &mask, 8);
    let spread = |ratios: &[f64]| ratios.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max);
    eprintln!(
        "8×8 tiles, largest departure from the every-frame gather: in turn (1 in 4) {:.3}, the query {:.3}",
        spread(&against_every),
        spread(&query_against_every)
    );
    assert!(
        spread(&against_every) < 0.5 * spread(&query_against_every),
        "every tile must have gathered: the image still reads the query somewhere"
    );
}

/// Each volume gathers with its own probes at the rays' hits and weighs in as its query did:
/// inside a finer volume over part of the Cornell box, the gathered light is what one volume
/// gathers (the weights are tested with the query in platform.rs).
#[test]
fn the_gather_lights_two_volumes_as_one() {
    let Some(ctx) = gpu() else { return };
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (32, 32);
    let coarse = scene.probe_volumes[0].clone();
    let mut fine = coarse.clone();
    fine.name = "fine".into();
    fine.counts = [6, 6, 6];
    fine.max = (coarse.min + coarse.max) * 0.5 + (coarse.max - coarse.min) * 0.25;
    let inside = irradiant_scene::Region::new("fine", fine.min, fine.max);
    let single = render_frames(&ctx, &scene, size, Some(&gathering(1, 1)), 60);
    scene.probe_volumes.push(fine);
    let two = render_frames(&ctx, &scene, size, Some(&gathering(1, 1)), 60);
    let mask = region_mask(&single.gbuffer, &inside);
    let (one, both) = (
        masked_mean(&single.indirect, &mask),
        masked_mean(&two.indirect, &mask),
    );
    eprintln!(
        "mean indirect with the gather inside the finer volume ({} pixels): one volume {one:.5}, two volumes {both:.5}",
        mask.iter().filter(|&&m| m).count()
    );
    assert!((both / one - 1.0).abs() < 0.1, "{both} against {one}");
}

/// The filter across the image (`gather.filter_passes`) takes the noise of a one-ray gather
/// away and no light with it: against sixteen rays a pixel unfiltered (the same estimator with
/// a sixteenth of the variance), the filtered one-ray image's squared error must be under half
/// the unfiltered one's, and its mean within 2 % of the sixteen rays'.
#[test]
fn the_filter_takes_the_gathers_noise_and_keeps_its_light() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let frames = 40;
    let many = render_frames(&ctx, &scene, size, Some(&gathering(16, 1)), frames);
    let one = render_frames(&ctx, &scene, size, Some(&gathering(1, 1)), frames);
    let mut filtered_settings = gathering(1, 1);
    filtered_settings.gather.filter_passes = 2;
    let filtered = render_frames(&ctx, &scene, size, Some(&filtered_settings), frames);
    let mask: Vec<bool> = many.gbuffer.iter().map(|g| g.depth >= 0.0).collect();
    let squared_error = |test: &irradiant::frame::Image| {
        let mut sum = 0.0;
        for ((t, m), &inside) in test.pixels.iter().zip(&many.indirect.pixels).zip(&mask) {
            if inside {
                sum += (pixel_luminance(t) - pixel_luminance(m)).powi(2);
            }
        }
        sum
    };
    let (raw, smooth) = (
        squared_error(&one.indirect),
        squared_error(&filtered.indirect),
    );
    let (truth, mean) = (
        masked_mean(&many.indirect, &mask),
        masked_mean(&filtered.indirect, &mask),
    );
    eprintln!(
        "cornell, one-ray gather against sixteen rays: squared error unfiltered {raw:.4}, filtered {smooth:.4}; mean {mean:.5} against {truth:.5}"
    );
    assert!(
        smooth < 0.5 * raw,
        "the filter must halve the one-ray gather's squared error at least"
    );
    assert!(
        (mean / truth - 1.0).abs() < 0.02,
        "the filter moved the light: {mean} against {truth}"
    );
}

/// `quality` is never worse than `balanced` (issue 41): FLIP and relative MSE against the path
/// tracer, on the Cornell box's image and on `many-lights`' indirect light (120 tiles, where
/// the gather's emitter samples made fireflies before its filter; at lavapipe's sizes its
/// direct light's noise, the same in both presets, would hide the difference in the whole
/// image). The presets as shipped but for 64 rays a probe in both. On `many-lights` at 64×40
/// the two presets' FLIP ties within its noise, and the filter, whose reach is in pixels,
/// spans a ninth of the view: FLIP may read 3 % over there (lavapipe, 2026-12-07: 0.0412
/// against 0.0437, once 0.0641 against 0.0627; 0.0361 against 0.0407 at 320×240 on an H200,
/// docs/ddgi.md), the relative MSE none.
#[test]
fn quality_is_no_worse_than_balanced_on_the_cornell_box_and_many_lights() {
    let Some(ctx) = gpu() else { return };
    for (name, size, indirect_only) in [
        ("cornell", (64, 64), false),
        ("many-lights", (64, 40), true),
    ] {
        let scene = irradiant_scene::load(name).unwrap().scene;
        let mut reference = path_trace(&ctx, &scene, size, 2048);
        if indirect_only {
            // The same seed: the direct light's samples are the same paths' and cancel.
            let direct = path_trace_view(&ctx, &scene, &scene.camera, size, 2048, 1);
            for (p, d) in reference.pixels.iter_mut().zip(&direct.pixels) {
                *p = [0, 1, 2].map(|c| p[c] - d[c]);
            }
        }
        let errors = |mut settings: DdgiSettings| {
            settings.volume.rays_per_probe = 64;
            let frame = render_frames(&ctx, &scene, size, Some(&settings), 100);
            let image = if indirect_only {
                frame.indirect
            } else {
                frame.total
            };
            (
                flip_mean(&reference, &image),
                irradiant_eval::relative_mse(&reference.pixels, &image.pixels).unwrap(),
            )
        };
        let (balanced, quality) = (
            errors(DdgiSettings::balanced()),
            errors(DdgiSettings::quality()),
        );
        eprintln!(
            "{name}: FLIP / relative MSE, balanced {:.4} / {:.5}, quality {:.4} / {:.5}",
            balanced.0, balanced.1, quality.0, quality.1
        );
        let flip_noise = if indirect_only { 1.03 } else { 1.0 };
        assert!(
            quality.0 <= flip_noise * balanced.0,
            "{name}: quality's FLIP is higher"
        );
        assert!(
            quality.1 <= balanced.1,
            "{name}: quality's relative MSE is higher"
        );
    }
}

/// At half resolution (`gather.half_resolution`) one pixel of each 2×2 block gathers and
/// ddgi/gather_upsample brings the light to the other three: the image converges to the one
/// every pixel gathers for, as tiles that gather in turn do.
#[test]
fn a_half_size_gather_converges_to_the_full_size_gather() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let every = render_frames(&ctx, &scene, size, Some(&gathering(1, 1)), 120);
    let mut half_settings = gathering(1, 1);
    half_settings.gather.half_resolution = true;
    let half = render_frames(&ctx, &scene, size, Some(&half_settings), 120);
    let query = render_frames(&ctx, &scene, size, Some(&gathering(0, 1)), 120);
    let mask: Vec<bool> = every.gbuffer.iter().map(|g| g.depth >= 0.0).collect();
    let spread = |test: &irradiant::frame::Image| {
        let ratios = block_ratios(test, &every.indirect, &mask, 8);
        ratios.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max)
    };
    let (h, q) = (spread(&half.indirect), spread(&query.indirect));
    eprintln!(
        "8×8 tiles, largest departure from the full-size gather: half size {h:.3}, the query {q:.3}"
    );
    // Seen on lavapipe: 0.066 against the query's 0.453.
    assert!(
        h < 0.15,
        "the half-size gather departs from the full-size one by {h:.3}"
    );
}

/// The gather keeps the light arriving, and each pixel's own diffuse weight multiplies it last:
/// across a floor half white and half nearly black, the light arriving (the indirect light
/// over the pixel's diffuse weight) is the same on both sides of the seam, with the filter's
/// three passes and at half resolution. Upsampling the light with the albedo inside lends the
/// black half the white half's light: lavapipe, the dark half's light over the white half's
/// 1.01 at full size and 1.01 at half size, against 1.01 and 4.22 with the albedo inside (at
/// full size the filter's own test of the light stops at so sharp a seam; the textures of
/// Sponza and Sibenik are where it did not, docs/ddgi.md).
#[test]
fn the_gather_lends_no_albedo_across_a_seam() {
    let Some(ctx) = gpu() else { return };
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    // The floor's upward faces (y = 0), one triangle of two nearly black.
    let dark = scene.materials.len() as u32;
    let mut black = scene.materials[0].clone();
    black.base_color = glam::Vec4::new(0.03, 0.03, 0.03, 1.0);
    black.base_color_texture = None;
    black.emission = glam::Vec3::ZERO;
    scene.materials.push(black);
    let mut darkened = 0;
    for mesh in &mut scene.meshes {
        for (t, corners) in mesh.indices.chunks(3).enumerate() {
            let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[corners[k] as usize]);
            let up = (b - a).cross(c - a).normalize_or_zero().y > 0.9;
            if up && a.y.abs() < 1e-4 && b.y.abs() < 1e-4 && c.y.abs() < 1e-4 && darkened == 0 {
                mesh.triangle_materials[t] = dark;
                darkened += 1;
            }
        }
    }
    assert_eq!(
        darkened, 1,
        "the Cornell box's floor is not where the test looks"
    );
    let size = (64, 64);
    for half in [false, true] {
        let mut settings = gathering(1, 1);
        settings.gather.filter_passes = 3;
        settings.gather.half_resolution = half;
        let frame = render_frames(&ctx, &scene, size, Some(&settings), 60);
        let luminance = |c: [f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        // Floor pixels within a few pixels of the seam, by side: the light arriving's mean.
        let is_dark = |g: &irradiant::frame::GBufferSample| luminance(g.diffuse) < 0.1;
        let floor = |g: &irradiant::frame::GBufferSample| {
            g.depth >= 0.0 && g.normal[1] > 0.9 && g.position[1] < 1e-3
        };
        let (w, h) = (size.0 as i32, size.1 as i32);
        let mut sums = [(0.0f64, 0u32); 2];
        for y in 0..h {
            for x in 0..w {
                let g = &frame.gbuffer[(y * w + x) as usize];
                if !floor(g) {
                    continue;
                }
                let near_seam = (-3..=3)
                    .flat_map(|dy| (-3..=3).map(move |dx| (dx, dy)))
                    .any(|(dx, dy)| {
                        let (qx, qy) = (x + dx, y + dy);
                        let inside = qx >= 0 && qy >= 0 && qx < w && qy < h;
                        inside && {
                            let q = &frame.gbuffer[(qy * w + qx) as usize];
                            floor(q) && is_dark(q) != is_dark(g)
                        }
                    });
                if near_seam {
                    let arriving = luminance(frame.indirect.pixels[(y * w + x) as usize])
                        / luminance(g.diffuse);
                    let side = &mut sums[is_dark(g) as usize];
                    side.0 += arriving as f64;
                    side.1 += 1;
                }
            }
        }
        let [white, black] = sums.map(|(sum, n)| sum / n.max(1) as f64);
        eprintln!(
            "half size {half}: light arriving beside the seam, dark half over white half {:.2} ({} and {} pixels)",
            black / white,
            sums[1].1,
            sums[0].1
        );
        assert!(
            sums[0].1 >= 20 && sums[1].1 >= 20,
            "the seam is not in view"
        );
        assert!(
            (black / white - 1.0).abs() < 0.25,
            "half size {half}: the dark half reads {:.2} of the white half's light",
            black / white
        );
    }
}
