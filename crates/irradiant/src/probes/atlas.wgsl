// probe_atlas: octahedral probe tiles in an atlas (CPU twins: probes::atlas, probes::octahedral).
// A tile has `texels` interior texels a side and a 1-texel border, which repeats the texels
// across the octahedral map's fold so that bilinear lookups are seamless.
#import octahedral

// A probe's tile's column and row in an atlas. Integer division is slow on GPUs: the query
// finds it once a probe for both of the probe's atlases.
fn atlas_tile_cell(probe: u32, probes_per_row: u32) -> vec2<u32> {
    return vec2<u32>(probe % probes_per_row, probe / probes_per_row);
}

// Top-left texel of a probe's tile (side `tile` texels, border included) in an atlas.
fn atlas_tile_origin(probe: u32, tile: u32, probes_per_row: u32) -> vec2<u32> {
    return atlas_tile_cell(probe, probes_per_row) * tile;
}

// The world direction that interior texel (i, j) of a tile of `texels` interior texels stands for.
fn texel_direction(texel: vec2<u32>, texels: u32) -> vec3<f32> {
    let uv = (vec2<f32>(texel) + 0.5) / f32(texels) * 2.0 - 1.0;
    return oct_decode(uv);
}

// The tile texel (border included, so interior texels are 1…texels) whose value border
// texel (x, y) repeats, mirrored as the octahedral map folds.
fn border_source(x: u32, y: u32, texels: u32) -> vec2<u32> {
    let last = texels + 1u;
    let corner_x = select(1u, texels, x == 0u);
    let corner_y = select(1u, texels, y == 0u);
    if (x == 0u || x == last) && (y == 0u || y == last) {
        return vec2<u32>(corner_x, corner_y);
    }
    if y == 0u || y == last {
        return vec2<u32>(last - x, select(texels, 1u, y == 0u));
    }
    return vec2<u32>(select(texels, 1u, x == 0u), last - y);
}

// Direction d's place in any tile, 0…1 a side: the same for every probe, so a query that reads
// all eight cage probes at one normal finds it once.
fn tile_uv(d: vec3<f32>) -> vec2<f32> {
    return oct_encode(d) * 0.5 + 0.5;
}

// Position in the tile at `cell` (atlas_tile_cell) of the place `uv` (tile_uv), in atlas
// texels: texel centres at whole numbers, so floor() is the top-left texel of the bilinear
// footprint.
fn atlas_tile_coord_at(cell: vec2<u32>, texels: u32, uv: vec2<f32>) -> vec2<f32> {
    let origin = vec2<f32>(cell * (texels + 2u)) + 1.0;
    return origin + uv * f32(texels) - 0.5;
}

// The same for direction d.
fn atlas_tile_coord(cell: vec2<u32>, texels: u32, d: vec3<f32>) -> vec2<f32> {
    return atlas_tile_coord_at(cell, texels, tile_uv(d));
}
