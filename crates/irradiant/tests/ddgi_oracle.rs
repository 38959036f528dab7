//! The oracles of issue 15 (docs/ddgi.md "Oracles"): the probe and query oracles that measure
//! DDGI's update and query against the path tracer's truth (lavapipe-sized). The truth itself
//! is checked against closed forms in pathtrace_gather.rs.

mod common;

use common::*;
use irradiant::GpuScene;
use irradiant::ddgi::DdgiSettings;
use irradiant::ddgi::oracle::{compare_with_truth, converged_atlases, probe_oracle, query_oracle};
use irradiant::pathtrace::PathTraceSettings;

fn truth_settings(samples: u32) -> PathTraceSettings {
    PathTraceSettings {
        samples_per_pixel: samples,
        samples_per_dispatch: 64,
        max_bounces: 64,
        seed: 3,
        light_sampling: Default::default(),
        schedule: Default::default(),
    }
}

/// Cornell's volume cut to 3×3×3 probes, converged quickly (hysteresis 0.9).
fn small_cornell_ddgi() -> DdgiSettings {
    let mut s = DdgiSettings::balanced();
    s.volume.probe_counts = [3, 3, 3];
    s.volume.rays_per_probe = 256;
    s.update.hysteresis = 0.9;
    s
}

/// The probe oracle of a DDGI session after 100 frames, its atlases averaged over `average`
/// more, against `samples` path-traced samples a texel.
fn converged_probe_oracle(
    ctx: &std::sync::Arc<irradiant::GpuContext>,
    scene: &irradiant_scene::Scene,
    size: (u32, u32),
    settings: &DdgiSettings,
    average: u32,
    samples: u32,
) -> irradiant::ddgi::oracle::ProbeOracle {
    let mut session = session(ctx, scene, size, spec(Some(settings)));
    let atlases = converged_atlases(&mut session, 100, average).unwrap();
    let volume = session
        .technique_as::<irradiant::ddgi::Ddgi>()
        .unwrap()
        .volume();
    probe_oracle(
        ctx,
        session.gpu_scene(),
        volume,
        &atlases,
        &truth_settings(samples),
        |_, _| {},
    )
    .unwrap()
}

/// The query oracle of a rendered frame of `scene`, over its regions, against `samples`
/// path-traced samples a pixel.
fn frame_query_oracle(
    ctx: &std::sync::Arc<irradiant::GpuContext>,
    scene: &irradiant_scene::Scene,
    frames: &FrameResult,
    samples: u32,
) -> irradiant::ddgi::oracle::QueryOracle {
    let gpu_scene = GpuScene::new(ctx, scene, &Default::default()).unwrap();
    query_oracle(
        ctx,
        &gpu_scene,
        &frames.gbuffer,
        &frames.indirect,
        &scene.regions,
        &truth_settings(samples),
        |_, _| {},
    )
    .unwrap()
}

#[test]
fn the_probe_oracle_finds_converged_probes_close_and_short_rays_dark() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut measured = Vec::new();
    // A probe whose rays stop at 10 cm sees the sky (black) past that: a deliberately broken
    // update the oracle must catch.
    for max_ray_distance in [0.0, 0.1] {
        let mut settings = small_cornell_ddgi();
        settings.update.max_ray_distance = max_ray_distance;
        let oracle = converged_probe_oracle(&ctx, &scene, (32, 32), &settings, 8, 1024);
        eprintln!(
            "cornell 3×3×3, max ray distance {max_ray_distance}: {} probes ({} skipped), median texel error {:.4}, signed {:+.4}, distance {:.4}, truth precision {:.4}, histogram {:?}",
            oracle.probes.len(),
            oracle.skipped_probes,
            oracle.median_texel_error,
            oracle.signed_error,
            oracle.median_distance_error,
            oracle.truth_precision,
            oracle.histogram
        );
        assert_eq!(
            oracle.probes.len() as u32 + oracle.skipped_probes,
            27,
            "every probe is compared or skipped"
        );
        assert!(oracle.truth_precision < 0.05, "{}", oracle.truth_precision);
        measured.push(oracle);
    }
    let (good, broken) = (&measured[0], &measured[1]);
    assert!(
        good.median_texel_error < 0.15 && good.signed_error.abs() < 0.1,
        "converged probes: median texel error {}, signed {}",
        good.median_texel_error,
        good.signed_error
    );
    assert!(
        good.median_distance_error < 0.1,
        "{}",
        good.median_distance_error
    );
    assert!(
        broken.signed_error < -0.3 && broken.median_texel_error > 2.0 * good.median_texel_error,
        "rays cut at 10 cm: signed {}, median {}",
        broken.signed_error,
        broken.median_texel_error
    );
    let worst = broken.worst(3);
    assert!(worst.len() == 3 && worst[0].signed.abs() >= worst[2].signed.abs());
}

#[test]
fn the_query_oracle_reads_the_glowing_box_in_closed_form() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("glowing-box").unwrap().scene;
    let mut settings = DdgiSettings::balanced();
    // The paper's heuristics are biased upwards on this scene's noise (docs/ddgi.md).
    settings.update.convergence_heuristics = false;
    let frames = render_frames(&ctx, &scene, (24, 24), Some(&settings), 200);
    let oracle = frame_query_oracle(&ctx, &scene, &frames, 128);
    // Every wall reflects ρ·(E/π) = ρ·ρ·Le/(1 − ρ) of indirect light (less the specular
    // layer's share, in the diffuse weight).
    let (le, albedo) = (
        irradiant_scene::GLOWING_BOX_EMISSION,
        irradiant_scene::GLOWING_BOX_ALBEDO,
    );
    let truth_mean =
        oracle.truth.pixels.iter().map(|p| p[1]).sum::<f32>() / oracle.truth.pixels.len() as f32;
    let closed_form = albedo * albedo * le / (1.0 - albedo);
    eprintln!(
        "glowing box query oracle: truth {truth_mean:.4} (closed form ≤ {closed_form}), DDGI signed {:+.4}, median {:.4}",
        oracle.signed_error, oracle.median_error
    );
    assert!(
        truth_mean <= closed_form * 1.02 && truth_mean >= closed_form * 0.9,
        "{truth_mean}"
    );
    assert!(
        oracle.signed_error.abs() < 0.05 && oracle.median_error < 0.1,
        "{} {}",
        oracle.signed_error,
        oracle.median_error
    );
    assert!(oracle.error.iter().all(|e| e.is_finite()));
}

/// Multi-bounce light in a white room converges in about a hundred frames: probe rays read the
/// bounce copy (`bounce_hysteresis`), so the next bounce no longer waits on the slow value. With
/// the paper's single atlas (bounce copy at the value's hysteresis) the probe oracle finds the
/// same probes still far too dark — the check can fail.
#[test]
fn multi_bounce_light_converges_in_a_hundred_frames_with_the_bounce_copy() {
    let Some(ctx) = gpu() else { return };
    let mut copy = DdgiSettings::balanced();
    copy.volume.probe_counts = [4, 3, 4];
    copy.volume.rays_per_probe = 128;
    let mut single = copy.clone();
    single.update.bounce_hysteresis = 0.97;
    let [copy, single] = probe_signed_errors(
        &ctx,
        "thin-frames",
        [
            ("4×3×4, bounce copy", copy),
            ("4×3×4, single atlas", single),
        ],
    );
    assert!(copy.abs() < 0.08, "with the bounce copy: {copy:+.4}");
    // -0.113 since newly vigilant probes start their mean over after classification
    // (-0.13 before: the classification frames' darker light stayed in the mean).
    assert!(
        single < -0.09,
        "the paper's single atlas should still be dark: {single:+.4}"
    );
}

/// The empty box's walls lie half a cell past its outermost probes. Clamped there (the paper's
/// query), the walls read the probes' light, darker than theirs, and the bounce loop compounds
/// it: its probes converge several per cent dark. Extrapolating the last two layers' trend
/// (`update.extrapolation`, on by default) brings them within a few per cent of the truth.
#[test]
fn walls_past_the_outermost_probes_keep_their_light_across_bounces() {
    let Some(ctx) = gpu() else { return };
    let mut extrapolated = DdgiSettings::balanced();
    extrapolated.volume.rays_per_probe = 128;
    let mut clamped = extrapolated.clone();
    clamped.update.extrapolation = 0.0;
    let [extrapolated, clamped] = probe_signed_errors(
        &ctx,
        "empty-box",
        [("extrapolated", extrapolated), ("clamped", clamped)],
    );
    assert!(
        extrapolated.abs() < 0.04,
        "extrapolated: {extrapolated:+.4}"
    );
    assert!(
        clamped < -0.04,
        "the clamped query should be dark: {clamped:+.4}"
    );
}

/// The probe oracle's signed error on a built-in scene after 100 frames of each labelled
/// variant, 256 samples a texel.
/// DDGI's frame of `scene` at 64×48 after `frames` frames under each of `variants`, with its
/// query oracle, all against one truth (`samples` path-traced samples a pixel, traced for the
/// first variant: the G-buffer is the same for all).
fn query_oracles_against_one_truth(
    ctx: &std::sync::Arc<irradiant::GpuContext>,
    scene: &irradiant_scene::Scene,
    variants: &[DdgiSettings],
    frames: u32,
    samples: u32,
) -> Vec<(FrameResult, irradiant::ddgi::oracle::QueryOracle)> {
    let mut truth = None;
    variants
        .iter()
        .map(|settings| {
            let result = render_frames(ctx, scene, (64, 48), Some(settings), frames);
            let oracle = match &truth {
                None => frame_query_oracle(ctx, scene, &result, samples),
                Some(first) => {
                    compare_with_truth(&result.indirect, first, &result.gbuffer, &scene.regions)
                }
            };
            truth.get_or_insert_with(|| oracle.truth.clone());
            (result, oracle)
        })
        .collect()
}

/// `balanced` at hysteresis 0.9 with the traced bounce and the blind bounces each variant names:
/// the tests of the update's extra rays.
fn bounce_variant((traced_bounce, blind_bounces): (bool, u32)) -> DdgiSettings {
    let mut settings = DdgiSettings::balanced();
    settings.update.hysteresis = 0.9;
    settings.update.traced_bounce = traced_bounce;
    settings.update.blind_bounces = blind_bounces;
    settings
}

/// Each variant's (DDGI, truth) mean indirect light over `region` after 120 frames, against one
/// truth of 256 samples a pixel.
fn region_against_one_truth(
    ctx: &std::sync::Arc<irradiant::GpuContext>,
    scene: &irradiant_scene::Scene,
    variants: &[DdgiSettings],
    region: &str,
) -> Vec<(f32, f32)> {
    query_oracles_against_one_truth(ctx, scene, variants, 120, 256)
        .into_iter()
        .map(|(_, oracle)| {
            let (_, ddgi, truth) = oracle.regions.iter().find(|r| r.0 == region).unwrap();
            (*ddgi, *truth)
        })
        .collect()
}

fn probe_signed_errors(
    ctx: &std::sync::Arc<irradiant::GpuContext>,
    scene: &str,
    variants: [(&str, DdgiSettings); 2],
) -> [f32; 2] {
    let loaded = irradiant_scene::load(scene).unwrap().scene;
    variants.map(|(label, settings)| {
        let oracle = converged_probe_oracle(ctx, &loaded, (16, 16), &settings, 4, 256);
        eprintln!(
            "{scene} after 100 frames, {label}: signed {:+.4}, median texel error {:.4} (truth ±{:.4})",
            oracle.signed_error, oracle.median_texel_error, oracle.truth_precision
        );
        oracle.signed_error
    })
}

/// Thin frames before a lit wall (built-in `thin-frames`: bars of 3 cm, a self-shadow bias of
/// about 11 cm): the query oracle's truth at each bar pixel against DDGI's indirect light there.
/// Specks are bar pixels more than twice as bright as the truth or under half of it: a few per
/// cent of the bars at most. Probe rays cut at 5 cm (no bounce light reaches the bars) show
/// the check can fail.
#[test]
fn thin_frames_show_few_specks() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("thin-frames").unwrap().scene;
    let ray_lengths = [0.0, 0.05];
    let variants = ray_lengths.map(|max_ray_distance| {
        let mut settings = DdgiSettings::balanced();
        settings.volume.rays_per_probe = 128;
        settings.update.max_ray_distance = max_ray_distance;
        settings
    });
    let mut specks = Vec::new();
    for (max_ray_distance, (frames, oracle)) in ray_lengths.into_iter().zip(
        query_oracles_against_one_truth(&ctx, &scene, &variants, 100, 256),
    ) {
        // The bars are the only wood: diffuse red well above blue.
        let bars: Vec<usize> = (0..frames.gbuffer.len())
            .filter(|&i| {
                let d = frames.gbuffer[i].diffuse;
                frames.gbuffer[i].depth >= 0.0 && d[0] > 2.0 * d[2]
            })
            .collect();
        let share = |test: &dyn Fn(f32) -> bool| {
            bars.iter().filter(|&&i| test(oracle.error[i])).count() as f32 / bars.len() as f32
        };
        let (bright, dark) = (share(&|e| e > 1.0), share(&|e| e < -0.5));
        eprintln!(
            "thin-frames, max ray distance {max_ray_distance}: {} bar pixels, bright specks {:.2} %, dark {:.2} %; whole image signed {:+.4}, median {:.4}; regions {:?}",
            bars.len(),
            100.0 * bright,
            100.0 * dark,
            oracle.signed_error,
            oracle.median_error,
            oracle.regions
        );
        assert!(bars.len() > 50, "the bars cover {} pixels", bars.len());
        specks.push(bright.max(dark));
    }
    assert!(
        specks[0] < 0.03,
        "specks on {:.2} % of the bars",
        100.0 * specks[0]
    );
    assert!(
        specks[1] > 0.05,
        "rays cut at 5 cm should leave the bars dark: {:.2} %",
        100.0 * specks[1]
    );
}

/// Box-cylinders (issue 15's "deficit ≤ 10 %"): its sixteen probes stand on the four columns'
/// axes, where backfaces all round tie for the closest. Whichever way such a probe leaves, it
/// lights some of its eight cells and misleads the others: counted like any probe (weight 1),
/// the query over the view reads 14 % dark here; at the default weight (0.1) against probes
/// with a clear view, 6.6 % (lavapipe, commit 2eecf16). Weight 1 shows the check can fail.
#[test]
fn tied_probes_on_the_columns_axes_keep_box_cylinders_within_ten_percent() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("box-cylinders").unwrap().scene;
    let weights = [DdgiSettings::balanced().update.tied_probe_weight, 1.0];
    let variants = weights.map(|tied_probe_weight| {
        let mut settings = DdgiSettings::balanced();
        settings.update.tied_probe_weight = tied_probe_weight;
        settings
    });
    let mut errors = Vec::new();
    for (tied_probe_weight, (_, oracle)) in weights.into_iter().zip(
        query_oracles_against_one_truth(&ctx, &scene, &variants, 120, 256),
    ) {
        eprintln!(
            "box-cylinders, tied probes weighing {tied_probe_weight}: signed {:+.4}, median {:.4}; regions {:?}",
            oracle.signed_error, oracle.median_error, oracle.regions
        );
        errors.push(oracle.signed_error);
    }
    assert!(
        errors[0].abs() <= 0.10,
        "box-cylinders' query is {:+.1} % off the truth",
        100.0 * errors[0]
    );
    assert!(
        errors[1].abs() > errors[0].abs() + 0.03,
        "tied probes weighing 1 should read darker: {:+.4} against {:+.4}",
        errors[1],
        errors[0]
    );
}

/// Two-rooms with a probe layer on the dividing wall's middle plane: each of the wall's probes
/// leaves into one room and serves it as any probe does, and the dark room's light stays
/// within 3 % of the truth (−0.4 % here). When those probes were tied and counted at a tenth
/// (the rule before commit 1db3573), it read +5.1 % here (+6.3 % at seed 0 and +6.5 % at seed 1
/// from `irradiant oracle` at this size; docs/ddgi.md, "A probe in a wall's middle").
#[test]
fn probes_in_a_walls_middle_keep_the_dark_room_right() {
    let Some(ctx) = gpu() else { return };
    let scene = two_rooms_with_probes_in_the_wall();
    let settings = DdgiSettings::balanced();
    let frames = render_frames(&ctx, &scene, (64, 48), Some(&settings), 120);
    let oracle = frame_query_oracle(&ctx, &scene, &frames, 256);
    eprintln!(
        "two-rooms, probes in the wall: signed {:+.4}, median {:.4}; regions {:?}",
        oracle.signed_error, oracle.median_error, oracle.regions
    );
    let (_, ddgi, truth) = oracle.regions.iter().find(|r| r.0 == "dark-room").unwrap();
    let error = ddgi / truth - 1.0;
    assert!(
        error.abs() <= 0.03,
        "the dark room reads {:+.1} % off the truth",
        100.0 * error
    );
}

/// A volume fitted to a room's walls (its box the room's inside, as a user who gives the
/// room's bounds places it) reads the room nearly as well as one inset from them: the Cornell
/// box's one-sided walls and two-rooms' solid ones (−7.9 and +4.5 % here). Before commit 1db3573
/// the probes in the walls' planes saw half the void beyond the Cornell box's quads (−40.7 %
/// here) and turned off in two-rooms' slabs, which lit the rooms from the probes a cell away
/// (+45 % at 128×96). A box 5 cm outside the Cornell box's walls leaves 9.1 % of the pixels
/// under half the truth (16.7 % before its edge and corner probes, which see only the walls'
/// backs and the void, learnt to cross a backface into the room).
#[test]
fn a_volume_fitted_to_the_walls_reads_the_room() {
    let Some(ctx) = gpu() else { return };
    let v = glam::Vec3::new;
    let settings = DdgiSettings::balanced();
    for (name, lo, hi) in [
        ("cornell", v(-1.0, 0.0, -1.0), v(1.0, 2.0, 1.0)),
        ("two-rooms", v(-4.0, 0.0, -2.0), v(4.0, 3.0, 2.0)),
        // 5 cm outside the Cornell box's one-sided walls.
        ("cornell", v(-1.05, -0.05, -1.05), v(1.05, 2.05, 1.05)),
    ] {
        let scene = fitted_to_the_walls(name, lo, hi);
        let frames = render_frames(&ctx, &scene, (64, 48), Some(&settings), 120);
        let oracle = frame_query_oracle(&ctx, &scene, &frames, 256);
        eprintln!(
            "{name}, volume on the walls: signed {:+.4}, median {:.4}, specks {:?}; regions {:?}",
            oracle.signed_error, oracle.median_error, oracle.specks, oracle.regions
        );
        assert!(
            oracle.signed_error.abs() <= 0.12
                && oracle.median_error <= 0.25
                && oracle.specks.1 <= 0.12,
            "{name}: the query reads {:+.1} % off the truth, median {:.1} %, {:.1} % of the pixels under half the truth",
            100.0 * oracle.signed_error,
            100.0 * oracle.median_error,
            100.0 * oracle.specks.1
        );
    }
}

/// The table (built-in `table`): the floor under its top lies half a cell below the lowest probe
/// layer, and the probes of the layer at the top's height relocate under it, 3 cm from its
/// underside. Extrapolating from them reads that pocket as the field's trend and floods the
/// floor under the table with light (+16 % over the table and the floor under it before the
/// query learnt to skip the trend there; with the check removed +12.5 % here, +5.3 % with it).
/// The query oracle over that region holds it within 10 %.
#[test]
fn the_floor_under_a_table_takes_no_extrapolated_light() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("table").unwrap().scene;
    let mut settings = DdgiSettings::balanced();
    settings.volume.rays_per_probe = 128;
    let frames = render_frames(&ctx, &scene, (64, 48), Some(&settings), 150);
    let oracle = frame_query_oracle(&ctx, &scene, &frames, 256);
    eprintln!(
        "table: whole image signed {:+.4}, median {:.4}; regions {:?}",
        oracle.signed_error, oracle.median_error, oracle.regions
    );
    let (_, ddgi, truth) = oracle.regions.iter().find(|r| r.0 == "table").unwrap();
    let signed = ddgi / truth - 1.0;
    assert!(
        signed.abs() < 0.10,
        "the table and the floor under it: {signed:+.4}"
    );
}

/// `slit-corridor`: a lit hall and a dark corridor whose only opening is a slit narrower than
/// the probe spacing, as Sponza's upper corridors are. Read at the probe rays' hits, the probes
/// leave the corridor almost black (−94.8 % here); with the traced bounce the surfaces by the
/// slit pass on what they see through it (−56.3 %; docs/ddgi.md, "A traced bounce at the probe
/// rays' hits"), and with a blind bounce the slit's reveals, which no probe sees, pass on the
/// hall's light too ("Tracing on where the probes are blind"). The corridor must hold three
/// times the light with the traced bounce, a fifth more again with the blind bounce, and no
/// more than the truth; a blind bounce without the traced bounce (at the probe rays' own hits)
/// half as much again as the probes read at the hits.
#[test]
fn the_traced_and_the_blind_bounces_light_a_corridor_through_a_slit() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("slit-corridor").unwrap().scene;
    let variants = [(false, 0), (true, 0), (true, 1), (false, 1)].map(bounce_variant);
    let corridor = region_against_one_truth(&ctx, &scene, &variants, "corridor");
    let [(query, truth), (traced, _), (blind, _), (blind_alone, _)] = corridor[..] else {
        unreachable!()
    };
    let error = |light: f32| 100.0 * (light / truth - 1.0);
    eprintln!(
        "slit-corridor's corridor against the truth: probes read at the hits {:+.1} %, traced bounce {:+.1} %, and a blind bounce {:+.1} %; a blind bounce alone {:+.1} %",
        error(query),
        error(traced),
        error(blind),
        error(blind_alone)
    );
    assert!(
        traced > 3.0 * query,
        "the traced bounce brings the corridor {traced:.3e} against the query's {query:.3e}"
    );
    assert!(
        blind > 1.2 * traced,
        "the blind bounce brings the corridor {blind:.3e} against the traced bounce's {traced:.3e}"
    );
    assert!(
        blind_alone > 1.5 * query,
        "a blind bounce alone brings the corridor {blind_alone:.3e} against the query's {query:.3e}"
    );
    assert!(
        blind < truth,
        "the corridor reads {blind:.3e}, over the truth's {truth:.3e}"
    );
}

/// Blind bounces trace on from hits no probe sees, such as the faces of two-rooms' doorway:
/// they must not light the dark room past the truth, nor move it far from what the probes give
/// without them (issue 15: fixes may not bring leaks back). `quality`'s update on `balanced`'s
/// rays: the traced bounce, with and without a blind bounce.
#[test]
fn blind_bounces_bring_no_light_into_the_dark_room() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("two-rooms").unwrap().scene;
    let variants = [(true, 0), (true, 1)].map(bounce_variant);
    let dark_room = region_against_one_truth(&ctx, &scene, &variants, "dark-room");
    let [(without, truth), (blind, _)] = dark_room[..] else {
        unreachable!()
    };
    eprintln!(
        "two-rooms' dark room against the truth: traced bounce {:+.1} %, and a blind bounce {:+.1} %",
        100.0 * (without / truth - 1.0),
        100.0 * (blind / truth - 1.0)
    );
    assert!(
        blind <= 1.05 * truth.max(without),
        "with a blind bounce the dark room reads {blind:.3e}: the truth is {truth:.3e}, without it {without:.3e}"
    );
}
