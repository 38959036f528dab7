// The raster host's G-buffer pass (examples/raster_host/host.rs): world normals, base colour,
// material and emission from the scene's triangles, under the host's camera; or with --native
// Irradiant's own layout (host::NativeGBuffer), with Irradiant's oct_encode prepended.
struct Camera { view_projection: mat4x4<f32>, eye: vec4<f32> }
@group(0) @binding(0) var<uniform> camera: Camera;

struct VertexIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) base_colour: vec3<f32>,
    @location(3) emission: vec3<f32>,
    @location(4) material: vec3<f32>,
}
struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) base_colour: vec3<f32>,
    @location(2) emission: vec3<f32>,
    @location(3) material: vec3<f32>,
    @location(4) world: vec3<f32>,
}
struct GBuffer {
    @location(0) normal: vec4<f32>,
    @location(1) base_colour: vec4<f32>,
    @location(2) material: vec4<f32>,
    @location(3) emission: vec4<f32>,
}

@vertex
fn vertex(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.clip = camera.view_projection * vec4<f32>(v.position, 1.0);
    out.normal = v.normal;
    out.base_colour = v.base_colour;
    out.emission = v.emission;
    out.material = v.material;
    out.world = v.position;
    return out;
}

@fragment
fn fragment(v: VertexOut, @builtin(front_facing) front: bool) -> GBuffer {
    var g: GBuffer;
    g.normal = vec4<f32>(normalize(v.normal), 0.0);
    g.base_colour = vec4<f32>(v.base_colour, 1.0);
    g.material = vec4<f32>(v.material, 0.0);
    // Emitters emit from their front (counter-clockwise) side.
    g.emission = vec4<f32>(select(vec3<f32>(0.0), v.emission, front), 1.0);
    return g;
}

// Irradiant's G-buffer layout (docs/embedding.md, "Drawing into Irradiant's G-buffer").
struct NativeGBuffer {
    @location(0) depth: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) albedo: vec4<f32>,
    @location(3) emission: vec4<f32>,
    @location(4) motion: vec4<f32>,
}

@fragment
fn fragment_native(v: VertexOut, @builtin(front_facing) front: bool) -> NativeGBuffer {
    let to_surface = v.world - camera.eye.xyz;
    var n = normalize(v.normal);
    // Turned towards the camera: Irradiant's surfaces are two-sided.
    n = select(n, -n, dot(n, to_surface) > 0.0);
    var g: NativeGBuffer;
    g.depth = vec4<f32>(length(to_surface), 0.0, 0.0, 0.0);
    g.normal = vec4<f32>(oct_encode(n), oct_encode(n));
    g.albedo = vec4<f32>(v.base_colour, v.material.x);
    g.emission = vec4<f32>(select(vec3<f32>(0.0), v.emission, front), v.material.y);
    // A still scene and camera: no motion.
    g.motion = vec4<f32>(0.0, 0.0, v.material.z, 0.0);
    return g;
}
