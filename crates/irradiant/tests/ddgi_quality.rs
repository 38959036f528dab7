//! DDGI against the path tracer on the built-in test scenes (lavapipe-sized), with figures
//! printed for docs/ddgi.md.

mod common;

use common::*;
use irradiant::ddgi::{DdgiSettings, ProbeWeights};

/// Settings for converging a static scene quickly on a CPU adapter: hysteresis 0.9 (about ten
/// frames of memory) instead of 0.97, so that 120 frames carry light through several bounces.
fn converging(weights: ProbeWeights) -> DdgiSettings {
    let mut s = DdgiSettings::balanced();
    s.update.weights = weights;
    s.update.hysteresis = 0.9;
    s.volume.rays_per_probe = 256;
    s
}

#[test]
fn two_rooms_full_ddgi_is_sixteen_times_closer_than_classic_probes_in_the_dark_room() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("two-rooms").unwrap().scene;
    let size = (64, 48);
    let classic = render_frames(
        &ctx,
        &scene,
        size,
        Some(&converging(ProbeWeights::Classic)),
        120,
    );
    let full = render_frames(
        &ctx,
        &scene,
        size,
        Some(&converging(ProbeWeights::Full)),
        120,
    );
    let reference = path_trace(&ctx, &scene, size, 1024);
    let mask = region_mask(&full.gbuffer, scene.region("dark-room").unwrap());
    let pt = masked_mean(&path_traced_indirect(&reference, &full), &mask);
    let (c, f) = (
        masked_mean(&classic.indirect, &mask),
        masked_mean(&full.indirect, &mask),
    );
    eprintln!(
        "two-rooms dark-room mean indirect luminance: path tracer {pt:.5}, classic probes {c:.5} (error {:.5}), full DDGI {f:.5} (error {:.5})",
        (c - pt).abs(),
        (f - pt).abs()
    );
    assert!(
        (f - pt).abs() * 16.0 <= (c - pt).abs(),
        "full DDGI must be at least 16× closer to the path tracer than classic probes (issue 15: fixes may not bring leaks back)"
    );
}

/// The self-shadow bias is a share of the probe spacing along each axis (docs/ddgi.md, "The
/// query"): on a grid of long cells across a wall (two-rooms at 4 × 6 × 7 probes: 2.6 m across
/// the dividing wall, 0.5–0.6 m along it) 003's bias, a share of the smallest spacing, leaves
/// the dark room's points beside the wall in the lit room's probes' Chebyshev slack.
#[test]
fn long_cells_across_a_wall_keep_the_dark_room_dark() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("two-rooms").unwrap().scene;
    let size = (64, 48);
    let mut settings = converging(ProbeWeights::Full);
    settings.volume.probe_counts = [4, 6, 7];
    let frames = render_frames(&ctx, &scene, size, Some(&settings), 120);
    let reference = path_trace(&ctx, &scene, size, 1024);
    let mask = region_mask(&frames.gbuffer, scene.region("dark-room").unwrap());
    let truth = masked_mean(&path_traced_indirect(&reference, &frames), &mask);
    let ddgi = masked_mean(&frames.indirect, &mask);
    eprintln!(
        "two-rooms at 4 × 6 × 7 probes, dark-room mean indirect luminance: path tracer {truth:.5}, DDGI {ddgi:.5} ({:+.1} %)",
        (ddgi / truth - 1.0) * 100.0
    );
    // Seen on lavapipe: +12.8 % with the bias per axis, +18.0 % with 003's (the default grid,
    // 0.9 m cells: −0.2 %). What is left is the coarse grid's.
    assert!(
        ddgi < 1.15 * truth,
        "light leaks into the dark room through long cells"
    );
}

/// Cornell box colour bleeding: FLIP of converged DDGI against the path-traced reference.
#[test]
fn cornell_box_converged_ddgi_is_within_flip_0_1_of_the_path_tracer() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let ddgi = render_frames(
        &ctx,
        &scene,
        size,
        Some(&converging(ProbeWeights::Full)),
        120,
    );
    let reference = path_trace(&ctx, &scene, size, 1024);
    let flip = irradiant_eval::flip(
        &reference.to_srgb8(1.0, true),
        &ddgi.total.to_srgb8(1.0, true),
        size.0,
        size.1,
    )
    .unwrap();
    let none = render_frames(&ctx, &scene, size, None, 60);
    let flip_none = irradiant_eval::flip(
        &reference.to_srgb8(1.0, true),
        &none.total.to_srgb8(1.0, true),
        size.0,
        size.1,
    )
    .unwrap();
    eprintln!(
        "cornell FLIP against the path tracer: DDGI mean {:.4} p95 {:.4}; direct light only mean {:.4}",
        flip.mean, flip.p95, flip_none.mean
    );
    // Bound from issue 3 (mean FLIP ≤ 0.1). The reference's own noise at 1024 spp adds about
    // 0.01–0.02 of FLIP at 64×64; without indirect light the error is several times larger.
    assert!(flip.mean <= 0.1, "mean FLIP {} above 0.1", flip.mean);
    assert!(
        flip.mean * 2.0 < flip_none.mean,
        "DDGI must be much closer to the reference than no indirect light"
    );
}

/// The light-field paper's Figure 10 setup: probes swallowed by cylinders must not darken the
/// surfaces around the cylinders (the "dark halo"). A halo is local: measured as the ratio of
/// DDGI's to the path tracer's indirect light over 8×8-pixel tiles around the cylinders, no
/// tile may fall far below the typical tile. Nor may one stand far above it: the tied probes on
/// the columns' axes count little where a cell has probes with a clear view, which must not
/// light the shaded gaps between the columns as a bright band.
#[test]
fn box_cylinders_has_no_dark_halo_around_swallowed_probes() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("box-cylinders").unwrap().scene;
    let size = (64, 48);
    let reference = path_trace(&ctx, &scene, size, 1024);
    let tiles = |settings: &DdgiSettings| {
        let frames = render_frames(&ctx, &scene, size, Some(settings), 120);
        let mask = region_mask(&frames.gbuffer, scene.region("around-cylinders").unwrap());
        let mut ratios = block_ratios(
            &frames.indirect,
            &path_traced_indirect(&reference, &frames),
            &mask,
            8,
        );
        ratios.sort_by(f64::total_cmp);
        (
            ratios[0],
            ratios[ratios.len() / 2],
            ratios[ratios.len() - 1],
        )
    };
    let full = tiles(&converging(ProbeWeights::Full));
    let mut unrelocated = converging(ProbeWeights::Full);
    unrelocated.update.relocation = false;
    let unrelocated = tiles(&unrelocated);
    let classic = tiles(&converging(ProbeWeights::Classic));
    let mut barely_tied = converging(ProbeWeights::Full);
    barely_tied.update.tied_probe_weight = 0.01;
    let barely_tied = tiles(&barely_tied);
    eprintln!(
        "box-cylinders, DDGI ÷ path tracer indirect over 8×8 tiles around the cylinders (worst, median, best): full {full:.2?}, without relocation {unrelocated:.2?}, classic {classic:.2?}, tied probes weighing 0.01 {barely_tied:.2?}"
    );
    // Seen on lavapipe (commit 2eecf16): full 0.79 / 0.94 / 1.20, without relocation 0.27 / 0.87
    // (black between the four cylinders, whose eight cage probes are all swallowed), classic
    // 0.71 / 0.83, tied probes weighing 0.01 1.41 against 0.98 (the gaps between the columns
    // read the probes beyond them). Bounds: the worst tile at least 75 % of the median one — no
    // local dark spot — and the best at most the median ÷ 75 %.
    assert!(
        full.0 >= 0.75 * full.1,
        "a dark halo: worst tile {:.2} against median {:.2}",
        full.0,
        full.1
    );
    assert!(
        full.2 * 0.75 <= full.1,
        "a bright band: best tile {:.2} against median {:.2}",
        full.2,
        full.1
    );
    assert!(
        unrelocated.0 < 0.75 * unrelocated.1,
        "without relocation the swallowed probes should show the halo this test exists to catch"
    );
    assert!(
        barely_tied.2 * 0.75 > barely_tied.1,
        "tied probes weighing 0.01 should show the bright band this test exists to catch"
    );
    assert!(
        full.1 > classic.1,
        "full DDGI must be brighter (closer) than classic probes around the cylinders"
    );
}

/// The DDGI furnace (issue 15): in a closed box whose walls emit Le and reflect ρ, light leaves
/// every point at Le / (1 − ρ) after every bounce — 2 for Le = 1, ρ = ½ — and the indirect term
/// the probes add is ρ²·Le / (1 − ρ) = ½. Probes carry the bounces from frame to frame (each
/// frame's probe rays read last frame's probes), so the converged update must reach it: energy
/// lost or gained per bounce would compound. With and without the convergence heuristics: as
/// the paper states them (judging each frame's sample) they added 12 % indirect light here on
/// the noisy emitter samples (docs/ddgi.md); they now judge the bounce copy.
#[test]
fn a_glowing_box_converges_to_its_closed_form_radiance() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("glowing-box").unwrap().scene;
    let (le, albedo) = (
        irradiant_scene::GLOWING_BOX_EMISSION,
        irradiant_scene::GLOWING_BOX_ALBEDO,
    );
    let mean = |image: &irradiant::frame::Image| {
        image
            .pixels
            .iter()
            .map(|p| (p[0] + p[1] + p[2]) / 3.0)
            .sum::<f32>()
            / image.pixels.len() as f32
    };
    let (total_expected, indirect_expected) =
        (le / (1.0 - albedo), albedo * albedo * le / (1.0 - albedo));
    let mut measured = Vec::new();
    for heuristics in [false, true] {
        let mut settings = DdgiSettings::balanced();
        settings.update.convergence_heuristics = heuristics;
        let frames = render_frames(&ctx, &scene, (32, 32), Some(&settings), 300);
        let (total, indirect) = (mean(&frames.total), mean(&frames.indirect));
        eprintln!(
            "glowing box, heuristics {heuristics}: total {total:.4} (closed form {total_expected:.4}), indirect {indirect:.4} (closed form {indirect_expected:.4})"
        );
        measured.push((total, indirect));
    }
    // With the convergence heuristics too: their per-texel rule once judged each frame's noisy
    // sample and read this box 12 % bright; it now judges the bounce copy.
    for (heuristics, (total, indirect)) in [false, true].into_iter().zip(measured) {
        assert!(
            (total - total_expected).abs() <= 0.02 * total_expected
                && (indirect - indirect_expected).abs() <= 0.05 * indirect_expected,
            "heuristics {heuristics}: the converged update holds {total:.4} ({indirect:.4} indirect), not Le / (1 − ρ) = {total_expected:.4} ({indirect_expected:.4})"
        );
    }
}

/// Past the outermost probes the query extrapolates with trilinear weights that go negative;
/// where visibility culls the probes that carry the positive ones, the blend would divide by
/// almost nothing. A volume that stops 1.5 cells short of the Cornell box's walls (and holds
/// the tall box) puts every wall past the grid: the extrapolated light stays finite and within
/// the twice-and-half band of the clamped query (with some slack: the probes themselves differ
/// a little between the two runs). Without that guard 430 of 2080 pixels left the band. Both
/// are far from the truth on a volume this short of the walls (printed): extrapolation is no
/// substitute for placing the outer probes within half a cell of them.
#[test]
fn the_query_past_the_outermost_probes_stays_bounded() {
    let Some(ctx) = gpu() else { return };
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    scene.probe_volumes = vec![irradiant_scene::ProbeVolumeDesc {
        name: "middle".into(),
        min: glam::Vec3::new(-0.4, 0.6, -0.4),
        max: glam::Vec3::new(0.4, 1.4, 0.4),
        counts: [3, 3, 3],
        follow: None,
    }];
    let mut clamped = converging(ProbeWeights::Full);
    clamped.update.extrapolation = 0.0;
    let frames = [converging(ProbeWeights::Full), clamped]
        .map(|settings| render_frames(&ctx, &scene, (48, 48), Some(&settings), 40));
    let images = [&frames[0].indirect, &frames[1].indirect];
    let truth = path_traced_indirect(&path_trace(&ctx, &scene, (48, 48), 256), &frames[0]);
    let (mut outside_band, mut lit) = (0, 0);
    for (e, c) in images[0].pixels.iter().zip(&images[1].pixels) {
        assert!(e.iter().all(|v| v.is_finite() && *v >= 0.0), "{e:?}");
        let (e, c) = (e.iter().sum::<f32>(), c.iter().sum::<f32>());
        if c > 1e-3 {
            lit += 1;
            if !(0.4 * c..=2.5 * c).contains(&e) {
                outside_band += 1;
            }
        }
    }
    let mean = |i: &irradiant::frame::Image| i.mean().iter().sum::<f64>();
    eprintln!(
        "cornell, volume 1.5 cells short of the walls: indirect mean {:.4} extrapolated, {:.4} clamped, {:.4} path traced; {outside_band} of {lit} lit pixels outside the band",
        mean(images[0]),
        mean(images[1]),
        mean(&truth)
    );
    assert!(lit > 1000, "{lit} lit pixels");
    assert_eq!(outside_band, 0);
}
