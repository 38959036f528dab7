// Scene access: the bindings of group 0, shared by every pass that traces rays
// (see GpuScene::bind_group_layout for their names).
#import types
#import sampling
#import surface

@group(0) @binding(0) var<storage, read> bvh_nodes: array<GpuBvhNode>;
// GpuTriangle, three 16-byte words each: read through triangle_at(), three vector loads.
@group(0) @binding(1) var<storage, read> triangles: array<vec4<u32>>;

// Triangle `i` from its three 16-byte words (GpuTriangle's layout): a vector load each, where
// a load of the struct leaves the split to the compiler.
fn triangle_at(i: u32) -> GpuTriangle {
    let a = triangles[3u * i];
    let b = triangles[3u * i + 1u];
    let c = triangles[3u * i + 2u];
    return GpuTriangle(bitcast<vec3<f32>>(a.xyz), a.w, bitcast<vec3<f32>>(b.xyz), b.w, bitcast<vec3<f32>>(c.xyz), c.w);
}
@group(0) @binding(2) var<storage, read> triangle_shading: array<GpuTriangleShading>;
@group(0) @binding(3) var<storage, read> instances: array<GpuInstance>;
@group(0) @binding(4) var<storage, read> materials: array<GpuMaterial>;
@group(0) @binding(5) var<storage, read> lights: array<GpuLight>;
// Each GpuEmitter is five 16-byte words, which emitter_at() reads as five vector loads.
@group(0) @binding(6) var<storage, read> emitters: array<vec4<u32>>;
@group(0) @binding(7) var<uniform> scene_info: GpuSceneInfo;
@group(0) @binding(8) var scene_textures: texture_2d_array<f32>;
@group(0) @binding(9) var scene_sampler: sampler;
// Bottom-level trees in the wide layout (BLAS_WIDE == 1); one unused node otherwise. Each
// GpuWideBvhNode is five 16-byte words, which bvh.wgsl's wide_node() reads as five vector loads.
@group(0) @binding(10) var<storage, read> wide_nodes: array<vec4<u32>>;
// The emitter grid (scene::emitter_grid): per cell an alias table over the emitters' clusters,
// then the clusters' members.
@group(0) @binding(11) var emitter_grid: texture_2d<u32>;

fn to_object_point(inst: GpuInstance, p: vec3<f32>) -> vec3<f32> {
    let q = vec4<f32>(p, 1.0);
    return vec3<f32>(dot(inst.world_to_object0, q), dot(inst.world_to_object1, q), dot(inst.world_to_object2, q));
}

fn to_object_vector(inst: GpuInstance, v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(inst.world_to_object0.xyz, v), dot(inst.world_to_object1.xyz, v), dot(inst.world_to_object2.xyz, v));
}

fn to_world_point(inst: GpuInstance, p: vec3<f32>) -> vec3<f32> {
    let q = vec4<f32>(p, 1.0);
    return vec3<f32>(dot(inst.object_to_world0, q), dot(inst.object_to_world1, q), dot(inst.object_to_world2, q));
}

fn to_world_vector(inst: GpuInstance, v: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(dot(inst.object_to_world0.xyz, v), dot(inst.object_to_world1.xyz, v), dot(inst.object_to_world2.xyz, v));
}

// Normals go through the inverse transpose: the transposed world-to-object matrix.
fn to_world_normal(inst: GpuInstance, n: vec3<f32>) -> vec3<f32> {
    return normalize(inst.world_to_object0.xyz * n.x + inst.world_to_object1.xyz * n.y + inst.world_to_object2.xyz * n.z);
}

fn interpolate_uv(s: GpuTriangleShading, bary: vec2<f32>) -> vec2<f32> {
    return s.uv0 * (1.0 - bary.x - bary.y) + s.uv1 * bary.x + s.uv2 * bary.y;
}

// Base colour and coverage at a texture coordinate (level 0: the path tracer antialiases by
// accumulation, and probe rays are too sparse for ray cones to matter).
fn base_color_at(m: GpuMaterial, uv: vec2<f32>) -> vec4<f32> {
    if m.texture < 0 {
        return m.base_color;
    }
    return m.base_color * textureSampleLevel(scene_textures, scene_sampler, uv, m.texture, 0.0);
}

// Whether an alpha-tested triangle is a hole at these barycentrics.
fn is_alpha_hole(tri_index: u32, bary: vec2<f32>) -> bool {
    let m = materials[triangle_at(tri_index).material];
    let uv = interpolate_uv(triangle_shading[tri_index], bary);
    return base_color_at(m, uv).a < m.alpha_cutoff;
}

fn surface_at(origin: vec3<f32>, dir: vec3<f32>, t: f32, tri_index: u32, instance_index: u32, bary: vec2<f32>) -> Surface {
    let tri = triangle_at(tri_index);
    let shading = triangle_shading[tri_index];
    let inst = instances[instance_index];
    let m = materials[tri.material];
    var s: Surface;
    s.position = origin + dir * t;
    let face = to_world_normal(inst, cross(tri.e1, tri.e2));
    let front = dot(face, dir) < 0.0;
    s.geometric_normal = select(-face, face, front);
    let w = vec3<f32>(1.0 - bary.x - bary.y, bary.x, bary.y);
    let interpolated = shading.n0 * w.x + shading.n1 * w.y + shading.n2 * w.z;
    if dot(interpolated, interpolated) > 1e-12 {
        var n = to_world_normal(inst, interpolated);
        n = select(-n, n, dot(n, s.geometric_normal) >= 0.0);
        s.normal = n;
    } else {
        s.normal = s.geometric_normal;
    }
    let base = base_color_at(m, interpolate_uv(shading, bary));
    s.albedo = base.rgb;
    s.metallic = m.metallic;
    s.roughness = m.roughness;
    s.specular = m.specular;
    s.emission = select(vec3<f32>(0.0), m.emission, front);
    return s;
}

// A point on an emitter chosen for next-event estimation.
struct EmitterSample {
    position: vec3<f32>,
    normal: vec3<f32>,
    radiance: vec3<f32>,
    // pdf with respect to area
    pdf_area: f32,
    // the triangle and instance it lies on, to recognise it at the end of a shadow ray
    triangle: u32,
    instance: u32,
}

// The emitter grid's cell holding p, clamped to the grid (EmitterGrid::cell): the place an
// emitter is picked from and its pdf read at.
fn emitter_cell(p: vec3<f32>) -> u32 {
    let dims = vec3<i32>(scene_info.grid_dims);
    let c = clamp(vec3<i32>(floor((p - scene_info.grid_min) * scene_info.grid_inverse_cell)), vec3<i32>(0), dims - 1);
    return u32(c.x) + scene_info.grid_dims.x * (u32(c.y) + scene_info.grid_dims.y * u32(c.z));
}

// An emitter picked from a cell, with its cluster's probability there.
struct EmitterPick {
    index: u32,
    cluster_probability: f32,
}

// Picks an emitter for a point in `cell` with one uniform draw: a cluster through the cell's
// alias table, then a member of it in proportion to power through the cluster's, by what is
// left of the draw (uniform again within the branch the keep test took). Two texel reads.
// One draw, not two: every pass's later random numbers stay where they were before the grid,
// and a second draw here made DDGI's 64-ray probes read the Cornell box three times too
// bright on lavapipe (a correlation between streams that was not found).
fn pick_emitter(cell: u32, u: f32) -> EmitterPick {
    let clusters = scene_info.grid_clusters;
    let scaled = u * f32(clusters);
    let entry = min(u32(scaled), clusters - 1u);
    let t = textureLoad(emitter_grid, vec2<u32>(entry, cell), 0);
    let left = scaled - f32(entry);
    let keep_chance = bitcast<f32>(t.x);
    let keep = left < keep_chance;
    let cluster = select(t.y, entry, keep);
    // One division: the branch's share of the draw over the branch's width.
    let u_member = clamp(select(left - keep_chance, left, keep) / max(select(1.0 - keep_chance, keep_chance, keep), 1e-7), 0.0, 0.99999994);
    // Cluster k holds the members ⌊k·n/K⌋ to ⌊(k+1)·n/K⌋, and ⌊k·n/K⌋ = k·⌊n/K⌋ + ⌊k·r/K⌋
    // (r = n mod K): the one division by a variable is the same for every pick, and the last
    // quotient, of numbers below K² ≤ 4096, is exact in floats with half a step's margin.
    let n = scene_info.emitter_count;
    let whole = n / clusters;
    let rest = n - whole * clusters;
    let step = 1.0 / f32(clusters);
    let first = cluster_start(cluster, whole, rest, step);
    let count = cluster_start(cluster + 1u, whole, rest, step) - first;
    let scaled_member = u_member * f32(count);
    let slot = first + min(u32(scaled_member), count - 1u);
    // The texture's rows are a power of two wide (emitter_grid::texture_size).
    let width = scene_info.grid_width;
    let m = textureLoad(emitter_grid, vec2<u32>(slot & (width - 1u), scene_info.grid_member_row + (slot >> countTrailingZeros(width))), 0);
    let index = select(m.y, m.x, scaled_member - floor(scaled_member) < bitcast<f32>(m.z));
    return EmitterPick(index, bitcast<f32>(select(t.w, t.z, keep)));
}

// Cluster k's first member, ⌊k·n/K⌋, from n = whole·K + rest and step = 1/K (pick_emitter).
fn cluster_start(k: u32, whole: u32, rest: u32, step: f32) -> u32 {
    return k * whole + u32((f32(k * rest) + 0.5) * step);
}

// The area pdf with which pick_emitter and a uniform point on the triangle pick a point of
// emitter `index` for `cell`.
fn emitter_area_pdf(cell: u32, index: u32) -> f32 {
    let cluster = emitters[5u * index + 2u].w;
    let pdf_area = bitcast<f32>(emitters[5u * index + 4u].w);
    return bitcast<f32>(textureLoad(emitter_grid, vec2<u32>(cluster, cell), 0).z) * pdf_area;
}

// The entry of the emitters buffer of a hit's triangle (an emissive one).
fn hit_emitter(instance: u32, triangle: u32) -> u32 {
    return instances[instance].emitter_base + triangle_shading[triangle].emitter_ordinal;
}

// Emitter `index` from its five 16-byte words (GpuEmitter's layout): a vector load each, where
// a load of the struct leaves the split to the compiler (as wide_node() does for the nodes).
fn emitter_at(index: u32) -> GpuEmitter {
    let a = emitters[5u * index];
    let b = emitters[5u * index + 1u];
    let c = emitters[5u * index + 2u];
    let d = emitters[5u * index + 3u];
    let e = emitters[5u * index + 4u];
    return GpuEmitter(bitcast<vec3<f32>>(a.xyz), a.w, bitcast<vec3<f32>>(b.xyz), b.w, bitcast<vec3<f32>>(c.xyz), c.w, bitcast<vec3<f32>>(d.xyz), d.w, bitcast<vec3<f32>>(e.xyz), bitcast<f32>(e.w));
}

// The point of emitter `index` at barycentrics b (along its triangle's e1 and e2), with its
// area pdf given its cluster: how a reservoir's sample is found again in later frames.
fn emitter_point(index: u32, b: vec2<f32>) -> EmitterSample {
    let e = emitter_at(index);
    var s: EmitterSample;
    s.position = e.v0 + e.e1 * b.x + e.e2 * b.y;
    s.normal = e.normal;
    s.radiance = e.radiance;
    s.pdf_area = e.pdf_area;
    s.triangle = e.triangle;
    s.instance = e.instance;
    return s;
}
