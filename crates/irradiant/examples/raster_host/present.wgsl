// The raster host's window (examples/raster_host/window.rs): its lit HDR image through the
// same ACES fit as the PNG it writes, into an sRGB view of the window (the hardware encodes).
@group(0) @binding(0) var hdr: texture_2d<f32>;

@vertex
fn vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fragment(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    let x = max(textureLoad(hdr, vec2<i32>(p.xy), 0).rgb, vec3<f32>(0.0));
    return vec4<f32>(saturate((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)), 1.0);
}
