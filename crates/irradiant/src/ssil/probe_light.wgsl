// ssil/probe_light (ssil+ddgi): the light the first bounce gathers, with the probes' light in
// it: what leaves each surface of the start level — its direct light plus the diffuse light
// DDGI's probes put there (frame `indirect`, already albedo-weighted; averaged over the
// texel's block of full-resolution pixels), and the surface's diffuse share in alpha
// (frame/pyramid). The screen then carries every bounce the probes
// hold, where it can see the sender, and the probes light the rest (ssil/temporal) — neither
// counted twice. ssil/bounce averages it up the levels.
#import ssil_common
#import gbuffer

@group(2) @binding(0) var<uniform> ssil: GpuSsilParams;
@group(2) @binding(1) var pyramid_radiance: texture_2d<f32>;
@group(2) @binding(2) var indirect: texture_2d<f32>;
@group(2) @binding(3) var target_radiance: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = level_size(ssil.start_level);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let block = 1u << ssil.start_level;
    let last = vec2<u32>(frame.width, frame.height) - 1u;
    var probes = vec3<f32>(0.0);
    var count = 0.0;
    for (var y = 0u; y < block; y++) {
        for (var x = 0u; x < block; x++) {
            let p = min(id.xy * block + vec2<u32>(x, y), last);
            let gi = textureLoad(indirect, p, 0);
            if gbuffer_depth_at(p) >= 0.0 && gi.a > 0.0 {
                probes += gi.rgb / gi.a;
                count += 1.0;
            }
        }
    }
    let own = textureLoad(pyramid_radiance, id.xy, ssil.start_level);
    let sent = own.rgb + probes / max(count, 1.0);
    textureStore(target_radiance, vec2<i32>(id.xy), vec4<f32>(sent, own.a));
}
