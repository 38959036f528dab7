// probe_grid: addressing of a regular probe grid (CPU twin: probes::ProbeGrid), x fastest.

fn grid_coord(probe: u32, counts: vec3<u32>) -> vec3<u32> {
    return vec3<u32>(probe % counts.x, (probe / counts.x) % counts.y, probe / (counts.x * counts.y));
}

fn grid_index(coord: vec3<u32>, counts: vec3<u32>) -> u32 {
    return coord.x + counts.x * (coord.y + counts.y * coord.z);
}
