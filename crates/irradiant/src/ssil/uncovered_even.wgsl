// ssil/temporal's `uncovered_light` for `ssil` alone, and for ssil+ddgi without the bent fill
// (`bent_fill` off): the probes' light at the pixel as it is, as if the directions the screen
// left uncovered brought the mean of every direction.
fn uncovered_light(s: Surface, probes: vec3<f32>, coverage: f32, covered: vec3<f32>) -> vec3<f32> {
    return probes;
}
