//! The six probe states (003 §6, Figure 7, Listing 5) and the convergence pass: ddgi/probe_states
//! against a table of the paper's transitions, and how fast probes that appear converge with
//! and without the convergence rounds.

mod common;

use common::*;
use irradiant::ddgi::constants::*;
use irradiant::ddgi::{Ddgi, DdgiSettings};
use irradiant::frame::SceneChange;
use irradiant::gpu_types::GpuDdgiRaySample;
use irradiant_gpu::read_buffer_as;

/// What a probe's rays saw in the frame before its state is decided.
#[derive(Clone, Copy, Debug)]
enum Rays {
    /// A front face a tenth of a cell away in every direction.
    Near,
    /// Nothing within reach.
    Far,
    /// Back faces only: the probe is inside geometry.
    Inside,
}

/// Where the probe stands in the frame: classified on its own (fresh count 1 is the last
/// classification frame, 2 an earlier one), or with the volume classified long ago (0).
struct Row {
    state: u32,
    fresh: u32,
    rays: Rays,
    in_wake_box: bool,
    next: u32,
}

const fn row(state: u32, fresh: u32, rays: Rays, in_wake_box: bool, next: u32) -> Row {
    Row {
        state,
        fresh,
        rays,
        in_wake_box,
        next,
    }
}

/// 003 Figure 7 and Listing 5, one transition a row.
const TRANSITIONS: &[Row] = &[
    // The last classification frame: off inside geometry, newly vigilant near it, else asleep.
    row(PROBE_VIGILANT, 1, Rays::Inside, false, PROBE_OFF),
    row(PROBE_VIGILANT, 1, Rays::Near, false, PROBE_NEWLY_VIGILANT),
    row(PROBE_VIGILANT, 1, Rays::Far, false, PROBE_SLEEPING),
    row(
        PROBE_NEWLY_VIGILANT,
        1,
        Rays::Near,
        false,
        PROBE_NEWLY_VIGILANT,
    ),
    // Earlier classification frames decide nothing yet.
    row(PROBE_VIGILANT, 2, Rays::Far, false, PROBE_VIGILANT),
    row(PROBE_VIGILANT, 2, Rays::Inside, false, PROBE_VIGILANT),
    // Classified: a newly probe has converged in its frame.
    row(PROBE_NEWLY_VIGILANT, 0, Rays::Far, false, PROBE_VIGILANT),
    row(PROBE_VIGILANT, 0, Rays::Far, false, PROBE_VIGILANT),
    row(PROBE_OFF, 0, Rays::Far, false, PROBE_OFF),
    row(PROBE_SLEEPING, 0, Rays::Far, false, PROBE_SLEEPING),
    row(PROBE_AWAKE, 0, Rays::Far, false, PROBE_SLEEPING),
    row(PROBE_NEWLY_AWAKE, 0, Rays::Far, false, PROBE_SLEEPING),
    // Inside a wake box (the high-x end of the row of probes).
    row(PROBE_SLEEPING, 0, Rays::Far, true, PROBE_NEWLY_AWAKE),
    row(PROBE_NEWLY_AWAKE, 0, Rays::Far, true, PROBE_AWAKE),
    row(PROBE_AWAKE, 0, Rays::Far, true, PROBE_AWAKE),
    row(PROBE_OFF, 0, Rays::Far, true, PROBE_OFF),
];

#[test]
fn probe_states_follow_the_papers_transitions() {
    let Some(ctx) = gpu() else { return };
    let n = TRANSITIONS.len() as u32;
    // One row of probes along x through the Cornell box, a probe a transition.
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    scene.probe_volumes[0].counts = [n, 1, 1];
    let mut settings = DdgiSettings::balanced();
    settings.volume.rays_per_probe = 32;
    settings.update.relocation = false;
    let mut session = session(&ctx, &scene, (16, 16), spec(Some(&settings)));
    // Past the volume's own classification.
    for _ in 0..8 {
        session.render().unwrap();
    }
    let ddgi = session.technique_as_mut::<Ddgi>().unwrap();
    let volume = ddgi.volume_mut();
    let spacing = volume.grid.spacing.x;
    let m = settings.volume.rays_per_probe as usize;
    let mut words = Vec::new();
    let mut samples = Vec::new();
    for r in TRANSITIONS {
        words.push(r.state | (r.fresh << PROBE_FRESH_SHIFT) | (7 << PROBE_AGE_SHIFT));
        let distance = match r.rays {
            Rays::Near => 0.1 * spacing,
            Rays::Far => 1e6,
            Rays::Inside => -0.1 * spacing,
        };
        samples.extend((0..m).map(|_| GpuDdgiRaySample {
            radiance: [0.0; 3],
            distance,
        }));
    }
    // A wake box over the last rows: upload grows it by a cell and the self-shadow bias (a
    // quarter cell here), so it starts 0.6 cells past the first row inside.
    let first_in_box = TRANSITIONS.iter().position(|r| r.in_wake_box).unwrap();
    assert!(TRANSITIONS[first_in_box..].iter().all(|r| r.in_wake_box));
    let x = volume.grid.probe_position(first_in_box as u32).x + 0.6 * spacing;
    volume.scene_changed(&SceneChange {
        dynamic_bounds: vec![(glam::Vec3::new(x, -1e3, -1e3), glam::Vec3::splat(1e3))],
        ..Default::default()
    });
    let r = &volume.resources;
    ctx.queue
        .write_buffer(&r.states, 0, bytemuck::cast_slice(&words));
    ctx.queue
        .write_buffer(&r.samples, 0, bytemuck::cast_slice(&samples));
    volume.prepare(&ctx);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    volume.record_probe_states(&mut encoder, None);
    ctx.queue.submit([encoder.finish()]);
    let after: Vec<u32> = read_buffer_as(&ctx, &volume.resources.states).unwrap();
    let lists: Vec<u32> = read_buffer_as(&ctx, &volume.resources.active_probes).unwrap();
    let mut wrong = Vec::new();
    for (i, r) in TRANSITIONS.iter().enumerate() {
        let state = after[i] & PROBE_STATE_MASK;
        if state != r.next {
            wrong.push(format!(
                "row {i}: state {} fresh {} rays {:?} wake box {}: got {state}, expected {}",
                r.state, r.fresh, r.rays, r.in_wake_box, r.next
            ));
        }
        // A probe woken from sleep starts from scratch; any other keeps its blends.
        let blends = after[i] >> PROBE_AGE_SHIFT;
        let woken = r.state == PROBE_SLEEPING && r.next == PROBE_NEWLY_AWAKE;
        if woken && blends != 0 {
            wrong.push(format!("row {i}: woken with {blends} blends, not 0"));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // The newly probes are listed apart for the convergence rounds, in grid order.
    let newly: Vec<u32> = (0..n)
        .filter(|&p| {
            matches!(
                TRANSITIONS[p as usize].next,
                PROBE_NEWLY_VIGILANT | PROBE_NEWLY_AWAKE
            )
        })
        .collect();
    let header = irradiant::ddgi::NEWLY_LIST as usize / 4;
    let start = irradiant::ddgi::ACTIVE_PROBES_HEADER as usize / 4 + n as usize;
    assert_eq!(
        lists[header] as usize,
        newly.len(),
        "the newly list's count"
    );
    assert_eq!(&lists[start..start + newly.len()], newly.as_slice());
}

/// Each probe's mean irradiance (luminance over its tile's interior texels).
fn probe_means(ctx: &irradiant::GpuContext, volume: &irradiant::ddgi::DdgiVolume) -> Vec<f64> {
    let atlases = volume.read_atlases(ctx).unwrap();
    let texels = volume.settings().volume.irradiance_texels;
    let width = atlases.irradiance_size.0;
    (0..volume.grid.probe_count)
        .map(|p| {
            let mut sum = 0.0;
            for y in 0..texels {
                for x in 0..texels {
                    let (u, v) = volume.atlas.texel(p, texels, x, y);
                    sum += pixel_luminance(&atlases.irradiance[(v * width + u) as usize]);
                }
            }
            sum / (texels * texels) as f64
        })
        .collect()
}

/// The first frame (counted from 1) from which every later one is within `share`.
fn frames_to_reach(errors: &[f64], share: f64) -> usize {
    errors.iter().rposition(|&e| e > share).map_or(1, |i| i + 2)
}

/// Over the probes `which` picks from the final states, the mean relative error of each
/// frame's probe irradiance against the mean of the last ten frames, frame by frame over
/// `frames` more frames, and how many frames it took to stay within 10 %.
fn convergence_of(
    ctx: &irradiant::GpuContext,
    session: &mut irradiant::Session,
    frames: usize,
    which: impl Fn(u32) -> bool,
) -> (Vec<f64>, usize) {
    let mut series = Vec::new();
    for _ in 0..frames {
        session.render().unwrap();
        let volume = session.technique_as::<Ddgi>().unwrap().volume();
        series.push(probe_means(ctx, volume));
    }
    let volume = session.technique_as::<Ddgi>().unwrap().volume();
    let states: Vec<u32> = read_buffer_as(ctx, &volume.resources.states).unwrap();
    let chosen: Vec<usize> = (0..states.len())
        .filter(|&p| which(states[p] & PROBE_STATE_MASK))
        .collect();
    assert!(!chosen.is_empty(), "no probe in the measured state");
    let converged: Vec<f64> = (0..states.len())
        .map(|p| series[frames - 10..].iter().map(|f| f[p]).sum::<f64>() / 10.0)
        .collect();
    let errors: Vec<f64> = series
        .iter()
        .map(|f| {
            chosen
                .iter()
                .map(|&p| (f[p] - converged[p]).abs() / converged[p].max(1e-6))
                .sum::<f64>()
                / chosen.len() as f64
        })
        .collect();
    let reach = frames_to_reach(&errors, 0.1);
    (errors, reach)
}

#[test]
fn the_convergence_pass_brings_new_probes_to_their_light_sooner() {
    let Some(ctx) = gpu() else { return };
    // The Cornell box with a dense grid (7×7×7) and 64 rays a probe; a block waits outside the
    // box, then moves into its middle, where probes sleep.
    let mut scene = cornell_with_block(glam::Vec3::new(0.0, -10.0, 0.0));
    scene.probe_volumes[0].counts = [7, 7, 7];
    let mut settings = DdgiSettings::balanced();
    settings.volume.rays_per_probe = 64;
    let mut reached = Vec::new();
    for rounds in [0, 3] {
        settings.update.convergence_rounds = rounds;
        // A volume's start: every probe near geometry is newly vigilant after classification.
        let mut session = session(&ctx, &scene, (16, 16), spec(Some(&settings)));
        let (start, start_frames) = convergence_of(&ctx, &mut session, 40, |s| s == PROBE_VIGILANT);
        // A woken probe: the block moves in after 40 frames.
        let block = *session.instance_ids().last().unwrap();
        let centre = scene.probe_volumes[0]
            .min
            .midpoint(scene.probe_volumes[0].max);
        session
            .set_instance_transform(block, glam::Mat4::from_translation(centre))
            .unwrap();
        let (woken, woken_frames) = convergence_of(&ctx, &mut session, 40, |s| s == PROBE_AWAKE);
        eprintln!("{rounds} rounds: volume start {start_frames} frames {start:.3?}");
        eprintln!("{rounds} rounds: woken {woken_frames} frames {woken:.3?}");
        reached.push((start_frames, woken_frames, start[5], woken[0]));
    }
    let (without, with) = (reached[0], reached[1]);
    // The frame after classification (the sixth) is the one the rounds converge at a
    // volume's start. A woken probe starts from scratch either way; its error then is mostly
    // its neighbours' (the block changed their light too), which the rounds do not touch.
    assert!(
        with.2 < 0.75 * without.2,
        "the rounds should cut the error of the frame after classification: {:.3} against {:.3}",
        with.2,
        without.2
    );
    assert!(
        with.0 <= without.0 && with.1 <= without.1 && with.3 < without.3 + 0.02,
        "the rounds should not make probes converge later: {with:?} against {without:?}"
    );
}
