// GPU structs shared by every pass. Each has one Rust definition (src/scene/types.rs,
// src/frame/types.rs) and a test that checks the two agree (tests/gpu_structs.rs).
#import scene_constants

// Inner BVH node holding both children's boxes. A child with count 0 is an inner node
// (first = node index); count > 0 is a leaf of `count` primitives from `first`; first =
// 0xffffffff marks an absent child.
struct GpuBvhNode {
    a_min: vec3<f32>,
    a_first: u32,
    a_max: vec3<f32>,
    a_count: u32,
    b_min: vec3<f32>,
    b_first: u32,
    b_max: vec3<f32>,
    b_count: u32,
}

// A compressed 8-wide bottom-level node (irradiant_bvh::GpuWideBvhNode documents the bits).
struct GpuWideBvhNode {
    // min corner of the children's quantisation grid
    origin: vec3<f32>,
    // bytes: grid scale exponents of x, y, z; imask (bit k: slot k is an inner node)
    exponents_imask: u32,
    child_base: u32,
    primitive_base: u32,
    // a byte per slot: leaf (unary count << 5 | first offset), inner (0b001 << 5 | 24 + slot), empty 0
    child_meta: vec2<u32>,
    // a byte per slot: quantised child box planes
    q_min_x: vec2<u32>,
    q_max_x: vec2<u32>,
    q_min_y: vec2<u32>,
    q_max_y: vec2<u32>,
    q_min_z: vec2<u32>,
    q_max_z: vec2<u32>,
}

// Intersection data, in the mesh's object space, in BVH leaf order.
struct GpuTriangle {
    v0: vec3<f32>,
    material: u32,
    e1: vec3<f32>,
    // TRIANGLE_ALPHA_TESTED: the material has a mask and a texture
    flags: u32,
    e2: vec3<f32>,
    _pad: u32,
}

// Shading data, same order as GpuTriangle. Normals of length 0 mean "use the face normal".
struct GpuTriangleShading {
    n0: vec3<f32>,
    // an emissive triangle's place among its mesh's: emitters[instance.emitter_base + this]
    emitter_ordinal: u32,
    n1: vec3<f32>,
    _pad1: u32,
    n2: vec3<f32>,
    _pad2: u32,
    uv0: vec2<f32>,
    uv1: vec2<f32>,
    uv2: vec2<f32>,
    _pad3: vec2<f32>,
}

// An instance: rows of its 3×4 world-to-object and object-to-world matrices, and of last
// frame's object-to-world (for motion vectors).
struct GpuInstance {
    world_to_object0: vec4<f32>,
    world_to_object1: vec4<f32>,
    world_to_object2: vec4<f32>,
    object_to_world0: vec4<f32>,
    object_to_world1: vec4<f32>,
    object_to_world2: vec4<f32>,
    previous_object_to_world0: vec4<f32>,
    previous_object_to_world1: vec4<f32>,
    previous_object_to_world2: vec4<f32>,
    blas_root: u32,
    emitter_base: u32,
    _pad1: u32,
    _pad2: u32,
}

struct GpuMaterial {
    base_color: vec4<f32>,
    emission: vec3<f32>,
    // layer of the texture array, or -1
    texture: i32,
    metallic: f32,
    roughness: f32,
    specular: f32,
    // alpha below this is a hole; -1 for opaque materials
    alpha_cutoff: f32,
}

struct GpuLight {
    position: vec3<f32>,
    // LIGHT_POINT, LIGHT_SPOT or LIGHT_DIRECTIONAL
    kind: u32,
    // the direction light travels
    direction: vec3<f32>,
    cos_inner: f32,
    // colour × intensity; zero when switched off
    power: vec3<f32>,
    cos_outer: f32,
}

// An emissive triangle in world space at the last uploaded pose, with its cluster of the
// emitter grid and its area pdf within it (scene::types::GpuEmitter).
struct GpuEmitter {
    v0: vec3<f32>,
    triangle: u32,
    e1: vec3<f32>,
    instance: u32,
    e2: vec3<f32>,
    cluster: u32,
    normal: vec3<f32>,
    _pad: u32,
    radiance: vec3<f32>,
    pdf_area: f32,
}

struct GpuSceneInfo {
    sky: vec3<f32>,
    light_count: u32,
    emitter_count: u32,
    grid_clusters: u32,
    tlas_root: u32,
    instance_count: u32,
    // the emitter grid (scene::emitter_grid): its low corner, cells per unit length, cells a
    // side, and its texture's row width and first member row
    grid_min: vec3<f32>,
    grid_width: u32,
    grid_inverse_cell: vec3<f32>,
    grid_member_row: u32,
    grid_dims: vec3<u32>,
    _pad: u32,
}

struct GpuCamera {
    position: vec3<f32>,
    tan_half_fov_y: f32,
    right: vec3<f32>,
    aspect: f32,
    up: vec3<f32>,
    _pad0: f32,
    forward: vec3<f32>,
    _pad1: f32,
}
