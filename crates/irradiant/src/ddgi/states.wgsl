// ddgi: probe states (003 §6). Every probe has one u32: its state (low 2 bits), whether a
// classification frame saw static geometry near it (bit 2), and how many frames it has blended
// since it last started updating (bits 8 and up).
//
// - VIGILANT: near static geometry; traces and updates every frame. Every probe starts so.
// - OFF: stuck inside static geometry even after relocation; never traces, never shades.
// - SLEEPING: no static geometry within one grid cell, so no surface reads it; never traces,
//   never shades.
// - AWAKE: sleeping, but an animated instance's box (grown by a cell and the self-shadow bias)
//   reaches it: traces and updates, starting from scratch, until the box leaves.

const PROBE_VIGILANT: u32 = 0u;
const PROBE_OFF: u32 = 1u;
const PROBE_SLEEPING: u32 = 2u;
const PROBE_AWAKE: u32 = 3u;
const PROBE_STATE_MASK: u32 = 3u;
const PROBE_NEAR_GEOMETRY: u32 = 4u;
const PROBE_AGE_SHIFT: u32 = 8u;

// volume.state_phase
const STATES_OFF: u32 = 0u;
const STATES_CLASSIFYING: u32 = 1u;
const STATES_CLASSIFY_LAST: u32 = 2u;
const STATES_CLASSIFIED: u32 = 3u;

fn probe_state(word: u32) -> u32 {
    return word & PROBE_STATE_MASK;
}

// Whether the probe traces rays and blends this frame.
fn probe_updates(word: u32) -> bool {
    let state = probe_state(word);
    return state == PROBE_VIGILANT || state == PROBE_AWAKE;
}

// Frames blended since the probe last started updating.
fn probe_blends(word: u32) -> u32 {
    return word >> PROBE_AGE_SHIFT;
}
