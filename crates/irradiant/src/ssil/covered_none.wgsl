// ssil: no covered directions (`ssil` alone, or ssil+ddgi without `bent_fill`): the functions of
// covered_directions.wgsl, doing nothing and binding nothing.
const COVERS_DIRECTIONS: bool = false;

fn covered_within_lobe(covered: vec3<f32>, coverage: f32) -> vec3<f32> {
    return vec3<f32>(0.0);
}

fn store_covered(texel: vec2<i32>, covered: vec3<f32>) {}

fn source_covered(texel: vec2<i32>) -> vec3<f32> {
    return vec3<f32>(0.0);
}

fn coarse_covered(texel: vec2<i32>) -> vec3<f32> {
    return vec3<f32>(0.0);
}

fn history_covered(texel: vec2<i32>) -> vec3<f32> {
    return vec3<f32>(0.0);
}
