// ddgi/probe_states: after the blends, each probe's state for the next frame (003 §6,
// Figure 7, Listing 5; ddgi_states lists the six). During the volume's first frames (while relocation runs) it notes whether any
// front face lies where surfaces read the probe: within one grid cell of it along every axis
// (one of the eight cells it is a corner of), widened by the self-shadow bias (the query
// looks up the cell of the biased point) and, for the grid's outermost probes, without limit
// outwards (the query clamps points beyond the grid to its outer cells: an empty room whose
// walls stood more than a cell past its outer probes went black, docs/ddgi.md). On the last
// of those frames a
// probe still seeing more than 25 % backfaces turns off (or, with shade_probes_in_geometry,
// stays vigilant), one near geometry turns newly vigilant, and the rest sleep. From then on,
// sleeping probes inside a wake box (an animated instance's bounds grown by a cell and the
// self-shadow bias) turn newly awake, and sleep again when it leaves; a newly probe, having
// converged in its frame, turns vigilant or awake. The newly probes are listed apart too, for
// the next frame's convergence rounds (ddgi_convergence). With
// `every_probe_updates` (probe states off) the states are the same and decide what the query
// reads, but every probe is listed to trace and blend.
#import ddgi_volume
#import ddgi_rays
#import ddgi_states
#import ddgi_active_list

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(3) var<storage, read> directions: array<vec4<f32>>;
@group(2) @binding(5) var<storage, read> probe_offsets: array<vec4<f32>>;
@group(2) @binding(6) var<storage, read> samples: array<GpuDdgiRaySample>;
@group(2) @binding(16) var<storage, read_write> probe_states: array<u32>;
// min, max corners, two vec4 a box
@group(2) @binding(17) var<storage, read> wake_boxes: array<vec4<f32>>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>, @builtin(local_invocation_index) li: u32) {
    let probe = id.x + id.y * groups.x * 64u;
    var updates = false;
    var newly = false;
    if probe < volume.probe_count {
        let word = next_state(probe);
        probe_states[probe] = word;
        updates = probe_traces(word, volume.every_probe_updates);
        newly = probe_is_newly(word);
    }
    list_if(LIST_UPDATING, probe, updates, li);
    list_if(LIST_NEWLY, probe, newly, li);
}

// The most blends the state word counts.
const MAX_BLENDS: u32 = (1u << (32u - PROBE_AGE_SHIFT)) - 1u;

// The probe's state word for the next frame.
fn next_state(probe: u32) -> u32 {
    let word = probe_states[probe];
    var state = probe_state(word);
    var near = (word & PROBE_NEAR_GEOMETRY) != 0u;
    var blends = probe_blends(word);
    if probe_traces(word, volume.every_probe_updates) {
        // It traced and blended this frame; a newly probe started over in its convergence
        // rounds, each of which counts as a frame.
        if probe_is_newly(word) {
            blends = 1u + volume.convergence_rounds;
        } else {
            blends = min(blends + 1u, MAX_BLENDS);
        }
    }
    // Converged in its frame (003 Listing 5): newly vigilant turns vigilant, newly awake awake.
    if state == PROBE_NEWLY_VIGILANT {
        state = PROBE_VIGILANT;
    } else if state == PROBE_NEWLY_AWAKE {
        state = PROBE_AWAKE;
    }
    // A probe that entered a tracking window is classified on its own frames.
    var fresh = probe_fresh(word);
    var phase = volume.state_phase;
    if fresh > 0u {
        phase = select(STATES_CLASSIFYING, STATES_CLASSIFY_LAST, fresh == 1u);
        fresh -= 1u;
    }
    if phase == STATES_CLASSIFYING || phase == STATES_CLASSIFY_LAST {
        let m = volume.rays_per_probe;
        // A cell and the self-shadow bias at the smallest spacing. The query's bias is per axis
        // (larger along coarse axes), but a probe past this reach holds at most about a fifth
        // of a biased point's trilinear weight: on Sibenik the per-axis reach woke 11 % more
        // probes for 8 % more GI time and changed its query by 0.4 % (docs/ddgi.md).
        let margin = 0.75 * volume.min_spacing * volume.self_shadow_bias;
        let coord = probe_grid_coord(probe);
        let unbounded = vec3<f32>(volume.max_ray_distance);
        let reach = volume.spacing + margin;
        let reach_below = select(reach, unbounded, coord == vec3<u32>(0u));
        let reach_above = select(reach, unbounded, coord == volume.counts - 1u);
        var backfaces = 0u;
        for (var r = 0u; r < m; r++) {
            let distance = samples[probe * m + r].distance;
            if distance < 0.0 {
                backfaces++;
            } else if distance < volume.max_ray_distance && all(directions[r].xyz * distance <= reach_above) && all(-directions[r].xyz * distance <= reach_below) {
                near = true;
            }
        }
        if phase == STATES_CLASSIFY_LAST {
            let in_geometry = f32(backfaces) > 0.25 * f32(m);
            if in_geometry && volume.shade_probes_in_geometry == 0u {
                state = PROBE_OFF;
            } else if in_geometry {
                state = PROBE_VIGILANT;
            } else if near {
                state = PROBE_NEWLY_VIGILANT;
            } else {
                state = PROBE_SLEEPING;
            }
        }
    } else if phase == STATES_CLASSIFIED && (state == PROBE_SLEEPING || state == PROBE_AWAKE) {
        let position = grid_position(probe) + probe_offsets[probe].xyz;
        var woken = false;
        for (var b = 0u; b < volume.wake_box_count; b++) {
            woken = woken || (all(position >= wake_boxes[2u * b].xyz) && all(position <= wake_boxes[2u * b + 1u].xyz));
        }
        if woken && state == PROBE_SLEEPING {
            // Whatever it held is stale (unless every probe kept updating): its first blend
            // starts it from scratch.
            if volume.every_probe_updates == 0u {
                blends = 0u;
            }
            state = PROBE_NEWLY_AWAKE;
        } else {
            state = select(PROBE_SLEEPING, PROBE_AWAKE, woken);
        }
    }
    return state | select(0u, PROBE_NEAR_GEOMETRY, near) | (fresh << PROBE_FRESH_SHIFT) | (blends << PROBE_AGE_SHIFT);
}
