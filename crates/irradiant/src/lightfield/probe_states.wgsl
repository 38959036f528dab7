// lightfield/probe_states: probes inside geometry switched off (beyond the paper, after DDGI's
// backface test, 003 §5). A probe swallowed by a solid sees only the inside of its surfaces:
// its radiance is black and its distances say "a surface right here", so every point near
// that solid would take its darkness. A probe whose surfaces face away from it for more than
// a quarter of its texels is off: the prefiltered query skips it (DDGI's probe states) and the
// trace passes over it to the next probe of the cage.
#import lightfield
#import ddgi_constants

@group(2) @binding(52) var<storage, read_write> target_probe_states: array<u32>;

const THREADS: u32 = 64u;
var<workgroup> back_faces: atomic<u32>;
var<workgroup> surfaces: atomic<u32>;

// A workgroup a probe.
@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let probe = group.x;
    let size = lightfield.resolution;
    var back = 0u;
    var seen = 0u;
    for (var i = lane; i < size * size; i += THREADS) {
        let texel = vec2<u32>(i % size, i / size);
        let g = textureLoad(lightfield_geometry, texel, probe, 0).r;
        if geometry_distance(g) < LF_NO_SURFACE {
            seen++;
            let dir = lf_direction((vec2<f32>(texel) + 0.5) / f32(size));
            back += u32(dot(geometry_normal(g), dir) > 0.0);
        }
    }
    atomicAdd(&back_faces, back);
    atomicAdd(&surfaces, seen);
    workgroupBarrier();
    if lane == 0u && probe < lightfield.probe_count {
        let inside = f32(atomicLoad(&back_faces)) > 0.25 * f32(max(atomicLoad(&surfaces), 1u));
        target_probe_states[probe] = select(PROBE_VIGILANT, PROBE_OFF, inside);
    }
}
