// lightfield/relocate: probes moved out of geometry before the bake (beyond the paper, after
// DDGI's relocation, 003 §5). A probe swallowed by a solid sees the inside of its surfaces; it
// steps through the nearest of them, by its distance plus a margin, toward the free space
// beyond. Offsets stay within 0.45 of the spacing on each axis, so that the probe keeps its
// cell; a probe still inside after the last step is switched off (lightfield/probe_states).
#import lightfield

@group(2) @binding(55) var<storage, read_write> target_probe_offsets: array<vec4<f32>>;

const THREADS: u32 = 64u;
var<workgroup> back_faces: atomic<u32>;
var<workgroup> surfaces: atomic<u32>;
// The nearest back face: its distance's bits (positive floats order as their bits do), and
// its texel.
var<workgroup> nearest_bits: atomic<u32>;
var<workgroup> nearest_texel: atomic<u32>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let probe = group.x;
    let size = lightfield.resolution;
    if lane == 0u {
        atomicStore(&nearest_bits, 0x7f7fffffu);
    }
    workgroupBarrier();
    var back = 0u;
    var seen = 0u;
    var best = 3.0e38;
    var best_texel = 0u;
    for (var i = lane; i < size * size; i += THREADS) {
        let texel = vec2<u32>(i % size, i / size);
        let g = textureLoad(lightfield_geometry, texel, probe, 0).r;
        let distance = geometry_distance(g);
        if distance < LF_NO_SURFACE {
            seen++;
            let dir = lf_direction((vec2<f32>(texel) + 0.5) / f32(size));
            if dot(geometry_normal(g), dir) > 0.0 {
                back++;
                if distance < best {
                    best = distance;
                    best_texel = i;
                }
            }
        }
    }
    atomicAdd(&back_faces, back);
    atomicAdd(&surfaces, seen);
    atomicMin(&nearest_bits, bitcast<u32>(best));
    workgroupBarrier();
    if bitcast<u32>(best) == atomicLoad(&nearest_bits) {
        atomicStore(&nearest_texel, best_texel);
    }
    workgroupBarrier();
    if lane != 0u || probe >= lightfield.probe_count {
        return;
    }
    if f32(atomicLoad(&back_faces)) <= 0.25 * f32(max(atomicLoad(&surfaces), 1u)) {
        return;
    }
    let i = atomicLoad(&nearest_texel);
    let dir = lf_direction((vec2<f32>(f32(i % size), f32(i / size)) + 0.5) / f32(size));
    let step = bitcast<f32>(atomicLoad(&nearest_bits)) + lightfield.max_thickness;
    let limit = 0.45 * lightfield.spacing;
    let moved = clamp(target_probe_offsets[probe].xyz + dir * step, -limit, limit);
    target_probe_offsets[probe] = vec4<f32>(moved, 0.0);
}
