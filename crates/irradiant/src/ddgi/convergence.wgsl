// ddgi: the convergence pass (003 §6.3, Listing 5). In the frame a probe is newly awake or
// newly vigilant, `convergence_rounds` rounds of ray directions, trace, shade and blends run
// before the normal update over the list of newly probes (ddgi_active's this_list), each with
// the ray set turned by another angle and other random numbers. The first round
// blends at hysteresis 0, as the paper's pass does: whatever the probe held (a woken probe's
// stale light, the mean of a classification's first, darker frames) is dropped, and the rounds
// and the normal update form a running mean of this frame's light. Each round's atlas copy
// lets the next round's rays read the light the last one gathered, so a plane of probes that
// enters together also gathers the bounces between its own probes within the frame.
#import ddgi_states

// A uniform where it is read: the ray passes are at the adapter's storage-buffer limit.
@group(2) @binding(22) var<uniform> convergence: DdgiConvergence;

// The samples the probe's value holds before this blend: its blended frames; for a newly
// probe only the rounds blended before this one (all of this frame's, in the normal update).
fn samples_held(word: u32) -> u32 {
    if probe_is_newly(word) {
        return select(volume.convergence_rounds, convergence.round - 1u, convergence.round > 0u);
    }
    return probe_blends(word);
}

// The frame number the random numbers of this dispatch's rays start from: another stream in
// every convergence round.
fn ray_frame() -> u32 {
    return volume.frame ^ (convergence.round << 24u);
}

// The ray set turned about its axis by the golden angle once per convergence round: the
// rounds' spherical Fibonacci sets interleave instead of repeating.
fn round_turn(d: vec3<f32>) -> vec3<f32> {
    let angle = 2.39996323 * f32(convergence.round);
    let c = cos(angle);
    let s = sin(angle);
    return vec3<f32>(c * d.x - s * d.y, s * d.x + c * d.y, d.z);
}
