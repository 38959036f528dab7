// ddgi/relocate: one iteration of the probe-position optimiser of 003 §5 (Listing 4), run for
// the volume's first frames. A probe that sees more than 25 % backfaces is inside geometry and
// moves through the closest backface (towards the volume's middle when others tie with it,
// and is marked tied when they surround it); a probe very close to a front face moves towards
// the farthest front face; a probe of the grid's outer layers first moves a hair inwards.
// Offsets keep the probe in its cell and inside the box of the grid's outer layers
// (relocation_keeps_grid).
#import ddgi_volume
#import ddgi_rays
#import ddgi_states

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(2) @binding(6) var<storage, read> samples: array<GpuDdgiRaySample>;
@group(2) @binding(13) var<storage, read_write> probe_offsets: array<vec4<f32>>;
@group(2) @binding(15) var<storage, read> probe_states: array<u32>;

// How far a ray went to the backface it hit; 0 for a front face or a miss. ddgi/shade stores a
// backface hit as minus its distance, shortened by the backface-hit rule when that is on.
fn backface_distance(distance: f32) -> f32 {
    return max(-distance, 0.0) / select(1.0, BACKFACE_DEPTH_SCALE, (volume.weights & WEIGHT_BACKFACE_HITS) != 0u);
}

fn within(probe: u32, offset: vec3<f32>) -> bool {
    return relocation_keeps_grid(probe_grid_coord(probe), volume.counts, volume.spacing, offset);
}

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let probe = id.x + id.y * groups.x * 64u;
    if probe >= volume.probe_count || volume.relocating == 0u {
        return;
    }
    // After a tracking window's step, only the probes that entered move.
    if volume.relocating == RELOCATING_FRESH && probe_fresh(probe_states[probe]) == 0u {
        return;
    }
    let m = volume.rays_per_probe;
    let current = probe_offsets[probe].xyz;
    // First, a probe of the outer layers moves a hair inwards (OUTER_PROBE_INSET): in a wall's
    // plane its rays miss the wall, so this iteration's are no guide, and the next ones see
    // the wall's face.
    let coord = probe_grid_coord(probe);
    let inset = OUTER_PROBE_INSET * volume.spacing * outer_layer_inwards(coord, volume.counts);
    if all(current == vec3<f32>(0.0)) && any(inset != vec3<f32>(0.0)) {
        probe_offsets[probe] = vec4<f32>(inset, probe_offsets[probe].w);
        return;
    }
    var backfaces = 0u;
    var closest_back = vec4<f32>(0.0, 0.0, 0.0, 1e30);
    var closest_front = vec4<f32>(0.0, 0.0, 0.0, 1e30);
    var farthest_front = vec4<f32>(0.0, 0.0, 0.0, -1.0);
    for (var r = 0u; r < m; r++) {
        let d = directions[r].xyz;
        let distance = samples[probe * m + r].distance;
        if distance < 0.0 {
            backfaces++;
            let t = backface_distance(distance);
            // The closest backface the probe may cross: one whose far side lies outside the
            // volume does not count (a box's bottom on the floor), so the probe leaves through
            // a side if one is near enough. 1.01 times its distance is the shortest crossing
            // the loop below tries.
            if t < closest_back.w && within(probe, current + d * t * 1.01) {
                closest_back = vec4<f32>(d, t);
            }
        } else {
            // A miss counts as a front face at the ray's full length.
            if distance < closest_front.w {
                closest_front = vec4<f32>(d, distance);
            }
            if distance > farthest_front.w {
                farthest_front = vec4<f32>(d, distance);
            }
        }
    }
    var next = current;
    // Once tied, a probe stays tied until the relocation starts over (its later iterations
    // start outside the geometry).
    var tied = probe_offsets[probe].w;
    // Outside a room of one-sided walls a probe sees their backs and the void, no face at all
    // (its closest front face is a miss): it is outside the scene's geometry, and a backface
    // leads in.
    let sees_no_face = closest_front.w >= volume.max_ray_distance;
    let inside = f32(backfaces) > 0.25 * f32(m) || (sees_no_face && backfaces > 0u);
    if inside && closest_back.w < 1e30 {
        // A tie (relocation_exits_tie): the closest exit would be a lottery of the ray set, so
        // the probe leaves towards the volume's middle among the exits nearly as close as the
        // closest. Where they surround it (relocation_exits_surround; a column's axis),
        // whichever it takes lights some of its eight cells and misleads the others: it is
        // marked tied, and the query counts it at `tied_probe_weight`.
        let inwards = relocation_inwards(coord, volume.counts, volume.spacing, current);
        var inmost = closest_back;
        var tie = false;
        for (var r = 0u; r < m; r++) {
            let d = directions[r].xyz;
            let t = backface_distance(samples[probe * m + r].distance);
            if t > 0.0 && t <= closest_back.w * (1.0 + RELOCATION_EXIT_TIE) && within(probe, current + d * t * 1.01) {
                if relocation_exits_tie(d, t, closest_back.xyz, closest_back.w) {
                    tie = true;
                    if relocation_exits_surround(d, closest_back.xyz) {
                        tied = 1.0;
                    }
                }
                if dot(d, inwards) > dot(inmost.xyz, inwards) {
                    inmost = vec4<f32>(d, t);
                }
            }
        }
        if tie || tied > 0.5 {
            closest_back = inmost;
        }
    }
    if inside {
        // Inside something: cross the closest backface, as far beyond it as the limit allows
        // (up to twice its distance). With none that may be crossed it stays, and turns off.
        for (var i = 0u; i < 100u && closest_back.w < 1e30; i++) {
            let candidate = current + closest_back.xyz * closest_back.w * (2.0 - f32(i) * 0.01);
            if within(probe, candidate) {
                next = candidate;
                break;
            }
        }
    } else if closest_front.w < RELOCATION_SURFACE_STEP * volume.min_spacing && dot(closest_front.xyz, farthest_front.xyz) <= 0.5 {
        // Touching a surface (its visibility tests would be all self-shadow): step towards open
        // space, no further than a surface step. A probe merely near a wall stays: the
        // query extrapolates at most half a cell past the outermost probes, so they belong
        // close to the walls.
        let candidate = current + farthest_front.xyz * min(RELOCATION_SURFACE_STEP * volume.min_spacing, farthest_front.w);
        if within(probe, candidate) {
            next = candidate;
        }
    }
    probe_offsets[probe] = vec4<f32>(next, tied);
}
