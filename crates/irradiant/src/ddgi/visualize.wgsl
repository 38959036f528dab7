// ddgi/visualize: draws every probe as a small sphere showing the irradiance it stores in the
// direction of the sphere's normal (--show-probes), over the composed radiance.
#import ddgi_query
#import gbuffer

@group(2) @binding(12) var radiance: texture_storage_2d<rgba32float, write>;

const INVALID_PROBE: u32 = 0xffffffffu;

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if !in_frame(id.xy) {
        return;
    }
    let origin = frame.camera.position;
    let dir = pixel_ray_dir(id.xy);
    let depth = gbuffer_depth_at(id.xy);
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
        let encoded = sample_irradiance_encoded(atlas_tile_cell(found, volume.probes_per_row), tile_uv(n));
        textureStore(radiance, vec2<i32>(id.xy), vec4<f32>(pow(max(encoded, vec3<f32>(0.0)), vec3<f32>(volume.irradiance_gamma)), 1.0));
    }
}
