// ddgi/resolve: indirect diffuse light at each G-buffer pixel from the probe volume.
#import ddgi_query
#import frame_types
#import gbuffer_surface
#import brdf

@group(1) @binding(9) var<storage, read> gbuffer: array<GpuGBufferTexel>;
@group(1) @binding(10) var<storage, read_write> indirect: array<vec4<f32>>;
@group(1) @binding(11) var<uniform> frame: GpuFrameParams;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let index = id.y * frame.width + id.x;
    let g = gbuffer[index];
    if g.depth < 0.0 {
        indirect[index] = vec4<f32>(0.0);
        return;
    }
    let s = surface_from_gbuffer(g);
    let wo = normalize(frame.camera.position - s.position);
    indirect[index] = vec4<f32>(diffuse_weight(s) * ddgi_irradiance(s.position, s.normal, wo), 1.0);
}
