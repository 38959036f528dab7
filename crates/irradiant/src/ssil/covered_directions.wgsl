// ssil: the covered directions' cosine-weighted sum ∫covered ω cos θ dω / π beside the light, for
// ssil+ddgi's bent fill (`bent_fill`): written by ssil/gather, combined by ssil/upsample and
// filtered by ssil/temporal as the light is. Compiled after those passes' own WGSL
// (SsilPipelines); covered_none.wgsl stands in without the bent fill, so that nothing is
// summed, stored or bound. Each pass binds these names to its own textures.
const COVERS_DIRECTIONS: bool = true;

@group(2) @binding(80) var target_direction: texture_storage_2d<rgba16float, write>;
@group(2) @binding(81) var source_direction: texture_2d<f32>;
@group(2) @binding(82) var coarse_direction: texture_2d<f32>;
@group(2) @binding(83) var history_direction: texture_2d<f32>;

// The covered sum scaled as the coverage is where it is capped at the whole lobe (1): the
// levels' rings and the coarser levels' light overlap in corners, and the directions must
// not outgrow the share they stand for.
fn covered_within_lobe(covered: vec3<f32>, coverage: f32) -> vec3<f32> {
    return covered * (min(coverage, 1.0) / max(coverage, 1e-6));
}

fn store_covered(texel: vec2<i32>, covered: vec3<f32>) {
    textureStore(target_direction, texel, vec4<f32>(covered, 0.0));
}

fn source_covered(texel: vec2<i32>) -> vec3<f32> {
    return textureLoad(source_direction, texel, 0).xyz;
}

fn coarse_covered(texel: vec2<i32>) -> vec3<f32> {
    return textureLoad(coarse_direction, texel, 0).xyz;
}

fn history_covered(texel: vec2<i32>) -> vec3<f32> {
    return textureLoad(history_direction, texel, 0).xyz;
}
