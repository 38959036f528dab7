// ddgi/visualize: draws every probe as a small sphere showing the irradiance it stores in the
// direction of the sphere's normal (--show-probes).
#import ddgi_query
#import frame_types
#import camera

@group(1) @binding(9) var<storage, read> gbuffer: array<GpuGBufferTexel>;
@group(1) @binding(11) var<uniform> frame: GpuFrameParams;
@group(1) @binding(12) var<storage, read_write> radiance: array<vec4<f32>>;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= frame.width || id.y >= frame.height {
        return;
    }
    let index = id.y * frame.width + id.x;
    let size = vec2<f32>(f32(frame.width), f32(frame.height));
    let origin = frame.camera.position;
    let dir = camera_ray_dir(frame.camera, vec2<f32>(id.xy) + 0.5, size);
    let depth = gbuffer[index].depth;
    var nearest = select(1e30, depth, depth >= 0.0);
    var found = INVALID_PROBE;
    let radius = 0.1 * volume.min_spacing;
    for (var p = 0u; p < volume.probe_count; p++) {
        let oc = origin - probe_position(p);
        let b = dot(oc, dir);
        let c = dot(oc, oc) - radius * radius;
        let disc = b * b - c;
        if disc > 0.0 {
            let t = -b - sqrt(disc);
            if t > 0.0 && t < nearest {
                nearest = t;
                found = p;
            }
        }
    }
    if found != INVALID_PROBE {
        let n = normalize(origin + dir * nearest - probe_position(found));
        let encoded = sample_irradiance_encoded(found, n);
        radiance[index] = vec4<f32>(pow(max(encoded, vec3<f32>(0.0)), vec3<f32>(volume.irradiance_gamma)), 1.0);
    }
}

const INVALID_PROBE: u32 = 0xffffffffu;
