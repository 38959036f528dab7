// ddgi/visualize: draws every probe as a small sphere over the composed radiance. With
// COLOUR_BY_STATE = 0 a sphere shows the irradiance it stores in the direction of its normal
// (--show-probes); with 1 it is coloured by its state (003 §6: vigilant green, awake orange,
// sleeping blue, off red, newly vigilant pale green, newly awake yellow; a tied probe
// magenta) and a thin line joins its grid point to where relocation (003 §5) moved it
// (ddgi/visualize_states, the viewer's probe view).
#import ddgi_query
#import gbuffer

@group(2) @binding(12) var radiance: texture_storage_2d<rgba32float, write>;

const INVALID_PROBE: u32 = 0xffffffffu;

fn state_colour(probe: u32) -> vec3<f32> {
    if probe_is_tied(probe) {
        return vec3<f32>(0.9, 0.1, 0.9);
    }
    switch probe_state(probe_states[probe]) {
        case PROBE_VIGILANT: { return vec3<f32>(0.1, 0.85, 0.2); }
        case PROBE_AWAKE: { return vec3<f32>(1.0, 0.55, 0.05); }
        case PROBE_SLEEPING: { return vec3<f32>(0.15, 0.35, 1.0); }
        case PROBE_NEWLY_VIGILANT: { return vec3<f32>(0.7, 1.0, 0.7); }
        case PROBE_NEWLY_AWAKE: { return vec3<f32>(1.0, 0.95, 0.2); }
        default: { return vec3<f32>(0.95, 0.1, 0.1); }
    }
}

// The distance between the pixel's ray (origin o, unit direction d) and the segment a→b, and
// the ray's parameter at the closest point.
fn ray_segment(o: vec3<f32>, d: vec3<f32>, a: vec3<f32>, b: vec3<f32>) -> vec2<f32> {
    let u = b - a;
    let w = o - a;
    let uu = dot(u, u);
    let du = dot(d, u);
    let dw = dot(d, w);
    let denom = uu - du * du;
    let s = select(clamp((dot(u, w) - du * dw) / denom, 0.0, 1.0), 0.0, denom < 1e-8);
    let t = max(du * s - dw, 0.0);
    return vec2<f32>(length(w + d * t - u * s), t);
}

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
    var on_line = false;
    let radius = 0.1 * volume.min_spacing;
    for (var p = 0u; p < volume.probe_count; p++) {
        let centre = probe_position(p);
        let oc = origin - centre;
        let b = dot(oc, dir);
        let c = dot(oc, oc) - radius * radius;
        let disc = b * b - c;
        if disc > 0.0 {
            let t = -b - sqrt(disc);
            if t > 0.0 && t < nearest {
                nearest = t;
                found = p;
                on_line = false;
            }
        }
        if COLOUR_BY_STATE != 0u {
            let home = grid_position_at(probe_grid_coord(p));
            let line = ray_segment(origin, dir, home, centre);
            if line.x < 0.15 * radius && line.y > 0.0 && line.y < nearest {
                nearest = line.y;
                found = p;
                on_line = true;
            }
        }
    }
    if found == INVALID_PROBE {
        return;
    }
    let n = normalize(origin + dir * nearest - probe_position(found));
    var colour: vec3<f32>;
    if COLOUR_BY_STATE != 0u {
        // Lit from the eye, so that a sphere reads as round.
        colour = select(state_colour(found) * (0.35 + 0.65 * max(-dot(n, dir), 0.0)), vec3<f32>(1.0), on_line);
    } else {
        let encoded = sample_irradiance_encoded(atlas_tile_cell(found, volume.probes_per_row), tile_uv(n));
        colour = pow(max(encoded, vec3<f32>(0.0)), vec3<f32>(volume.irradiance_gamma));
    }
    textureStore(radiance, vec2<i32>(id.xy), vec4<f32>(colour, 1.0));
}
