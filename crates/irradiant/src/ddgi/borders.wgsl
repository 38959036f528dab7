// ddgi/borders: copies each tile's edge texels into its 1-texel border, mirrored as the
// octahedral map folds, so that bilinear filtering is seamless across the map's edges.
#import ddgi_volume

@group(1) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(1) @binding(7) var<storage, read_write> irradiance_atlas: array<vec2<u32>>;
@group(1) @binding(8) var<storage, read_write> distance_atlas: array<vec2<f32>>;

// The interior texel whose value border texel (x, y) of a tile with `texels` interior texels
// repeats (CPU twin: ddgi::octahedral::border_source).
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

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let index = id.x + id.y * groups.x * 64u;
    let irradiance_tile = volume.irradiance_texels + 2u;
    let distance_tile = volume.distance_texels + 2u;
    let per_probe = irradiance_tile * irradiance_tile + distance_tile * distance_tile;
    let probe = index / per_probe;
    if probe >= volume.probe_count {
        return;
    }
    var k = index % per_probe;
    let is_irradiance = k < irradiance_tile * irradiance_tile;
    if !is_irradiance {
        k -= irradiance_tile * irradiance_tile;
    }
    let tile = select(distance_tile, irradiance_tile, is_irradiance);
    let x = k % tile;
    let y = k / tile;
    if x != 0u && y != 0u && x != tile - 1u && y != tile - 1u {
        return;
    }
    let source = border_source(x, y, tile - 2u);
    let origin = tile_origin(probe, tile);
    let width = atlas_width(tile);
    let target_index = (origin.y + y) * width + origin.x + x;
    let source_index = (origin.y + source.y) * width + origin.x + source.x;
    if is_irradiance {
        irradiance_atlas[target_index] = irradiance_atlas[source_index];
    } else {
        distance_atlas[target_index] = distance_atlas[source_index];
    }
}
