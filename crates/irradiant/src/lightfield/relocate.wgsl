// lightfield/relocate: probes moved out of geometry before the bake (beyond the paper, after
// DDGI's relocation, 003 §5). A probe swallowed by a solid sees the inside of its surfaces; it
// steps through the nearest of them that it may cross, by its distance plus a margin, toward
// the free space beyond. Offsets keep the probe in its cell and inside the box of the grid's
// outer layers (relocation_keeps_grid); a probe still inside after the last step is switched
// off (lightfield/probe_states).
#import lightfield

@group(2) @binding(55) var<storage, read_write> target_probe_offsets: array<vec4<f32>>;

const THREADS: u32 = 64u;
// The nearest back face's distance bits before any is found: the largest float.
const NO_BACK_FACE: u32 = 0x7f7fffffu;
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
        atomicStore(&nearest_bits, NO_BACK_FACE);
    }
    workgroupBarrier();
    let coord = grid_coord(probe, lightfield.counts);
    let current = target_probe_offsets[min(probe, lightfield.probe_count - 1u)].xyz;
    var back = 0u;
    var seen = 0u;
    var best = bitcast<f32>(NO_BACK_FACE);
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
                let step = dir * (distance + lightfield.max_thickness);
                if distance < best && relocation_keeps_grid(coord, lightfield.counts, lightfield.spacing, current + step) {
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
    // Outside, or inside with no back face it may cross (it stays, and turns off).
    if f32(atomicLoad(&back_faces)) <= 0.25 * f32(max(atomicLoad(&surfaces), 1u)) || atomicLoad(&nearest_bits) == NO_BACK_FACE {
        return;
    }
    let i = atomicLoad(&nearest_texel);
    let dir = lf_direction((vec2<f32>(f32(i % size), f32(i / size)) + 0.5) / f32(size));
    let step = bitcast<f32>(atomicLoad(&nearest_bits)) + lightfield.max_thickness;
    target_probe_offsets[probe] = vec4<f32>(current + dir * step, 0.0);
}
