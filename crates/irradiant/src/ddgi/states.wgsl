// ddgi: probe states (003 §6, Figure 7). Every probe has one u32: its state (low 3 bits),
// whether a classification frame saw static geometry near it (PROBE_NEAR_GEOMETRY), a fresh
// count (PROBE_FRESH_*) and how many frames it has blended since it last started updating
// (from PROBE_AGE_SHIFT up).
//
// - VIGILANT: near static geometry; traces and updates every frame. Every probe starts so,
//   while the volume's first frames classify it.
// - OFF: stuck inside static geometry even after relocation; never traces, never shades.
// - SLEEPING: no static geometry within one grid cell, so no surface reads it; never traces,
//   never shades.
// - NEWLY VIGILANT: classified near geometry this frame (the end of a volume's or an entered
//   plane's classification); NEWLY AWAKE: sleeping, and an animated instance's box (grown by a
//   cell and the self-shadow bias) reached it this frame, so it starts from scratch. Either
//   traces its normal rays and, first, `convergence_rounds` more rounds of them (ddgi's
//   convergence pass, a running mean over the rounds), then turns VIGILANT or AWAKE.
// - AWAKE: traces and updates until the box leaves; then SLEEPING.
//
// A probe that enters a tracking window (ddgi/window_enter) starts vigilant with nothing
// blended and a fresh count: for that many frames it is relocated and classified on its own,
// as every probe is in a volume's first frames.

// PROBE_* (the state word's fields) and STATES_* (volume.state_phase) come from
// ddgi::constants.
#import ddgi_constants
#import dispatch

fn probe_state(word: u32) -> u32 {
    return word & PROBE_STATE_MASK;
}

// Whether the probe traces rays and blends this frame.
fn probe_updates(word: u32) -> bool {
    let state = probe_state(word);
    return state == PROBE_VIGILANT || state == PROBE_AWAKE || probe_is_newly(word);
}

// Whether the probe woke or was classified vigilant this frame: the convergence pass's rounds
// update it.
fn probe_is_newly(word: u32) -> bool {
    let state = probe_state(word);
    return state == PROBE_NEWLY_VIGILANT || state == PROBE_NEWLY_AWAKE;
}

// Whether the probe traces and blends this frame: the vigilant and awake ones, or every probe
// with probe states off (`every_probe_updates`, the volume's), while the query still reads
// only those that update by their state (probe_updates).
fn probe_traces(word: u32, every_probe_updates: u32) -> bool {
    return probe_updates(word) || every_probe_updates != 0u;
}

// Frames left in which a probe that entered a tracking window is relocated and classified on
// its own; 0 for every other probe.
fn probe_fresh(word: u32) -> u32 {
    return (word >> PROBE_FRESH_SHIFT) & PROBE_FRESH_MASK;
}

// Frames blended since the probe last started updating.
fn probe_blends(word: u32) -> u32 {
    return word >> PROBE_AGE_SHIFT;
}

// The probes that update, listed by ddgi/probe_states at the end of each frame for the next
// (DdgiResources::active_probes): two lists, each a header — its count, the indirect dispatch
// of ddgi/shade (a workgroup a ray block of PROBES_PER_GROUP listed probes), that of the blends
// (a workgroup a listed probe), that of ddgi/trace (shade's, or with FETCH_RAYS a workgroup a
// run of fetch_run of the listed probes' rays) — and its probes in grid order within each
// 64 of the states pass. List 0 holds every probe that updates; list 1 the newly vigilant and
// newly awake among them, which the convergence rounds update (ddgi_convergence); list l's
// probes start at l × probe_count. Workgroups then start only for probes that update: on
// Sibenik 43 % of the probes sleep or are off. ddgi_active reads them; this is
// ddgi/probe_states' view, which builds them.
struct DdgiProbeListWrite {
    count: atomic<u32>,
    rays_x: atomic<u32>,
    rays_y: atomic<u32>,
    rays_z: atomic<u32>,
    blends_x: atomic<u32>,
    blends_y: atomic<u32>,
    blends_z: atomic<u32>,
    trace_x: atomic<u32>,
    trace_y: atomic<u32>,
    trace_z: atomic<u32>,
    padding0: u32,
    padding1: u32,
}

struct DdgiActiveProbesWrite {
    lists: array<DdgiProbeListWrite, 2>,
    probes: array<u32>,
}

// The same lists, read.
struct DdgiProbeList {
    count: u32,
    rays_x: u32,
    rays_y: u32,
    rays_z: u32,
    blends_x: u32,
    blends_y: u32,
    blends_z: u32,
    trace_x: u32,
    trace_y: u32,
    trace_z: u32,
    padding0: u32,
    padding1: u32,
}

struct DdgiActiveProbes {
    lists: array<DdgiProbeList, 2>,
    probes: array<u32>,
}

// The list of every probe that updates, and of the newly vigilant and newly awake ones.
const LIST_UPDATING: u32 = 0u;
const LIST_NEWLY: u32 = 1u;

// The convergence pass's round (DdgiResources::convergence): ddgi/converge_step counts the
// rounds, 1 to `convergence_rounds`, and sets it back to 0 for the normal update.
struct DdgiConvergence {
    round: u32,
    padding0: u32,
    padding1: u32,
    padding2: u32,
}
