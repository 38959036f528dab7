// Counter-based random numbers: PCG hashes (Jarzynski and Olano 2020), deterministic for a
// given pixel, frame and seed.

fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn rng_seed(a: u32, b: u32, c: u32) -> u32 {
    return pcg_hash(a ^ pcg_hash(b ^ pcg_hash(c)));
}

// A float in [0, 1) from 24 random bits.
fn rand(state: ptr<function, u32>) -> f32 {
    *state = pcg_hash(*state);
    return f32(*state >> 8u) * (1.0 / 16777216.0);
}

fn rand2(state: ptr<function, u32>) -> vec2<f32> {
    let x = rand(state);
    return vec2<f32>(x, rand(state));
}
