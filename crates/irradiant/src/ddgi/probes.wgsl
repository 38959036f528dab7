// ddgi: probe positions after relocation (003 §5): the grid position plus a per-probe offset
// of less than half the spacing, found during the volume's first frames.
#import ddgi_volume

@group(1) @binding(5) var<storage, read> probe_offsets: array<vec4<f32>>;

fn probe_position(probe: u32) -> vec3<f32> {
    return grid_position(probe) + probe_offsets[probe].xyz;
}
