// The raster host's lighting (examples/raster_host/host.rs): emission + direct + Irradiant's
// indirect light, the sky where the depth buffer is clear.
@group(0) @binding(0) var emission: texture_2d<f32>;
@group(0) @binding(1) var direct: texture_2d<f32>;
@group(0) @binding(2) var indirect: texture_2d<f32>;
@group(0) @binding(3) var depth: texture_2d<f32>;
@group(0) @binding(4) var<uniform> sky: vec4<f32>;

@vertex
fn vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fragment(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let at = vec2<i32>(p.xy);
    // Reversed Z: 0 is the far plane, where no surface was drawn.
    if textureLoad(depth, at, 0).r <= 0.0 {
        return vec4<f32>(sky.rgb, 1.0);
    }
    let lit = textureLoad(emission, at, 0).rgb + textureLoad(direct, at, 0).rgb + textureLoad(indirect, at, 0).rgb;
    return vec4<f32>(lit, 1.0);
}
