// lightfield/relocate: probes moved out of geometry before the bake (beyond the paper, after
// DDGI's relocation, 003 §5). A probe swallowed by a solid sees the inside of its surfaces; it
// steps through the nearest of them that it may cross, by its distance plus a margin, toward
// the free space beyond — towards the grid's middle, marked tied, where such back faces all
// round tie (a column's axis). Offsets keep the probe in its cell and inside the box of the grid's
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
// Whether the exits tie (relocation_exits_tie), and then the crossable back face nearly as
// close as the nearest that points most towards the grid's middle: its alignment (+ 2, so that
// its bits order as the value does) and its texel.
var<workgroup> tied: atomic<u32>;
var<workgroup> inmost_bits: atomic<u32>;
var<workgroup> inmost_texel: atomic<u32>;

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
            let dir = texel_direction(i, size);
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
    // A tie, as DDGI's relocation finds one (ddgi/relocate): the probe leaves towards the
    // grid's middle, and is marked (w = 1) for the query's `tied_probe_weight`.
    let nearest = bitcast<f32>(atomicLoad(&nearest_bits));
    let nearest_dir = texel_direction(atomicLoad(&nearest_texel), size);
    let inwards = relocation_inwards(coord, lightfield.counts, lightfield.spacing, current);
    var tie = 0u;
    var inmost = -1.0;
    var inmost_at = 0u;
    for (var i = lane; i < size * size && nearest < bitcast<f32>(NO_BACK_FACE); i += THREADS) {
        let g = textureLoad(lightfield_geometry, vec2<u32>(i % size, i / size), probe, 0).r;
        let distance = geometry_distance(g);
        let dir = texel_direction(i, size);
        if distance <= nearest * (1.0 + RELOCATION_EXIT_TIE) && dot(geometry_normal(g), dir) > 0.0 && relocation_keeps_grid(coord, lightfield.counts, lightfield.spacing, current + dir * (distance + lightfield.max_thickness)) {
            tie |= u32(relocation_exits_tie(dir, distance, nearest_dir, nearest));
            if dot(dir, inwards) > inmost {
                inmost = dot(dir, inwards);
                inmost_at = i;
            }
        }
    }
    atomicOr(&tied, tie);
    atomicMax(&inmost_bits, bitcast<u32>(inmost + 2.0));
    workgroupBarrier();
    if bitcast<u32>(inmost + 2.0) == atomicLoad(&inmost_bits) {
        atomicStore(&inmost_texel, inmost_at);
    }
    workgroupBarrier();
    if lane != 0u || probe >= lightfield.probe_count {
        return;
    }
    // Outside, or inside with no back face it may cross (it stays, and turns off).
    let was_tied = target_probe_offsets[probe].w;
    if f32(atomicLoad(&back_faces)) <= 0.25 * f32(max(atomicLoad(&surfaces), 1u)) || atomicLoad(&nearest_bits) == NO_BACK_FACE {
        return;
    }
    var exit = atomicLoad(&nearest_texel);
    if atomicLoad(&tied) != 0u {
        exit = atomicLoad(&inmost_texel);
    }
    let distance = geometry_distance(textureLoad(lightfield_geometry, vec2<u32>(exit % size, exit / size), probe, 0).r);
    let step = distance + lightfield.max_thickness;
    target_probe_offsets[probe] = vec4<f32>(current + texel_direction(exit, size) * step, max(was_tied, f32(atomicLoad(&tied))));
}

// The direction of a map texel, by its index.
fn texel_direction(i: u32, size: u32) -> vec3<f32> {
    return lf_direction((vec2<f32>(f32(i % size), f32(i / size)) + 0.5) / f32(size));
}
