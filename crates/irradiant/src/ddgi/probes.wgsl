// ddgi: probe positions after relocation (003 §5): the grid position plus a per-probe offset
// of less than half the spacing, found during the volume's first frames; and probe states.
#import ddgi_volume
#import ddgi_states

@group(2) @binding(5) var<storage, read> probe_offsets: array<vec4<f32>>;
@group(2) @binding(15) var<storage, read> probe_states: array<u32>;

fn probe_position(probe: u32) -> vec3<f32> {
    return grid_position(probe) + probe_offsets[probe].xyz;
}

// Whether the probe's stored light is live: sleeping and switched-off probes are skipped by
// the query (003 §6).
fn probe_shades(probe: u32) -> bool {
    return probe_updates(probe_states[probe]);
}
