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

// PROBE_* (the state word's fields) and STATES_* (volume.state_phase) come from
// ddgi::constants.
#import ddgi_constants

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
