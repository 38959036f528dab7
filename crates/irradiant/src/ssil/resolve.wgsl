// ssil/resolve: the filtered light into the frame's indirect light: the diffuse share of the
// gathered irradiance and the glossy radiance. In ssil+ddgi (`hybrid`), DDGI has already
// written its light there; the screen-space light replaces it in the share of the cosine lobe
// the screen covered (coverage C) and the probes keep the rest — off-screen and hidden sources,
// and what lies past the largest ring — so that nothing is counted twice.
#import ssil_common
#import gbuffer
#import brdf

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var ssil_filtered: texture_2d<f32>;
@group(2) @binding(2) var ssil_filtered_specular: texture_2d<f32>;
@group(2) @binding(3) var indirect: texture_storage_2d<rgba32float, read_write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    if gbuffer_depth_at(id.xy) < 0.0 {
        textureStore(indirect, id.xy, vec4<f32>(0.0));
        return;
    }
    let s = gbuffer_surface(id.xy);
    let light = textureLoad(ssil_filtered, id.xy, 0);
    var out = diffuse_weight(s) / PI * light.rgb + textureLoad(ssil_filtered_specular, id.xy, 0).rgb;
    if ssil.hybrid == 1u {
        let probes = textureLoad(indirect, id.xy);
        out += (1.0 - light.a) * probes.rgb / max(probes.a, 1e-6);
    }
    textureStore(indirect, id.xy, vec4<f32>(out, 1.0));
}
