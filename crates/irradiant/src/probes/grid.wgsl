// probe_grid: addressing of a regular probe grid (CPU twin: probes::ProbeGrid), x fastest.
#import probe_constants

fn grid_coord(probe: u32, counts: vec3<u32>) -> vec3<u32> {
    return vec3<u32>(probe % counts.x, (probe / counts.x) % counts.y, probe / (counts.x * counts.y));
}

fn grid_index(coord: vec3<u32>, counts: vec3<u32>) -> u32 {
    return coord.x + counts.x * (coord.y + counts.y * coord.z);
}

// Whether a relocation offset keeps the probe at `coord` in its cell and inside the box of the
// grid's outer layers. Past them lie the walls the grid was fitted to, or the far side of a
// surface resting on one: a probe in a box standing on the floor crossed its bottom, the
// closest backface, into the void under the floor (docs/ddgi.md, "A probe pushed out of the
// volume"). A surface step of slack lets a probe in a column that reaches the ceiling leave it
// with a tilt. An axis of one layer has no extent to keep to.
fn relocation_keeps_grid(coord: vec3<u32>, counts: vec3<u32>, spacing: vec3<f32>, offset: vec3<f32>) -> bool {
    let p = vec3<f32>(coord) * spacing + offset;
    let slack = RELOCATION_SURFACE_STEP * spacing;
    let extent = spacing * vec3<f32>(counts - 1u);
    let flat_axis = counts == vec3<u32>(1u);
    let inside = (p >= -slack & p <= extent + slack) | flat_axis;
    return all(abs(offset) < RELOCATION_LIMIT * spacing) && all(inside);
}

// Whether a backface at distance t in direction d ties with the closest (direction `closest`,
// distance `closest_t`) as a way out: nearly as close, and more than 60° away from it.
fn relocation_exits_tie(d: vec3<f32>, t: f32, closest: vec3<f32>, closest_t: f32) -> bool {
    return t <= closest_t * (1.0 + RELOCATION_EXIT_TIE) && dot(d, closest) < 0.5;
}

// Whether a tied exit d lies across the closest (60° to 120° from it): exits in a ring or a
// square round the probe (a column's axis), where whichever it takes misleads some of its
// cells. Two opposite exits (a wall's middle plane) are not: either side is open, and the
// probe serves the side it takes in full.
fn relocation_exits_surround(d: vec3<f32>, closest: vec3<f32>) -> bool {
    return abs(dot(d, closest)) < 0.5;
}

// Per axis, which way is inwards from the grid's outer layers: +1 on the first layer, −1 on the
// last, 0 between them and along a flat axis.
fn outer_layer_inwards(coord: vec3<u32>, counts: vec3<u32>) -> vec3<f32> {
    let spread = counts > vec3<u32>(1u);
    return vec3<f32>((coord == vec3<u32>(0u)) & spread) - vec3<f32>((coord == counts - 1u) & spread);
}

// The direction from a probe (grid coordinates `coord`, moved by `offset`) towards the middle
// of its grid, where DDGI's probe whose exits tie leaves: there it serves the cells that have
// no other probe. (A probe at the very middle still gets a direction.)
fn relocation_inwards(coord: vec3<u32>, counts: vec3<u32>, spacing: vec3<f32>, offset: vec3<f32>) -> vec3<f32> {
    let middle = 0.5 * spacing * vec3<f32>(counts - 1u);
    return normalize(middle - vec3<f32>(coord) * spacing - offset + vec3<f32>(1e-4, 2e-4, 3e-4));
}
