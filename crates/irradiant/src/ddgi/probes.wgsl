// ddgi: probe positions after relocation (003 §5): the grid position plus a per-probe offset
// of less than half the spacing, found during the volume's first frames (xyz; w is 1 for a tied
// probe); and probe states.
#import ddgi_volume
#import ddgi_states

@group(2) @binding(5) var<storage, read> probe_offsets: array<vec4<f32>>;
@group(2) @binding(15) var<storage, read> probe_states: array<u32>;

fn probe_position(probe: u32) -> vec3<f32> {
    return probe_position_at(probe_grid_coord(probe), probe);
}

// probe_position where the caller knows the probe's grid coordinates (the query's cage), which
// spares the integer divisions of turning the index back into them.
fn probe_position_at(coord: vec3<u32>, probe: u32) -> vec3<f32> {
    return grid_position_at(coord) + probe_offsets[probe].xyz;
}

// Whether the probe's stored light is live: sleeping and switched-off probes are skipped by
// the query (003 §6), and so is one that has blended nothing since it entered a tracking
// window (its tile still holds the light of the probe that left).
fn probe_shades(probe: u32) -> bool {
    let word = probe_states[probe];
    let unblended_entry = probe_fresh(word) > 0u && probe_blends(word) == 0u;
    return probe_updates(word) && !unblended_entry;
}

// Whether relocation found the probe inside geometry with no single way out (ddgi/relocate):
// the query counts it at `tied_probe_weight`.
fn probe_is_tied(probe: u32) -> bool {
    return probe_offsets[probe].w > 0.5;
}
