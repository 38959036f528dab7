// The G-buffer's channels and how each packs a surface: one place for the layout, shared by
// the pass that writes it (frame/gbuffer) and the module that reads it (gbuffer). A host engine
// that brings its own G-buffer fills these textures.
//
// gbuffer_depth    r32float     distance along the primary ray; negative where it left the scene
// gbuffer_normal   rgba16float  xy: shading normal, zw: geometric normal, both octahedral
// gbuffer_albedo   rgba16float  rgb: base albedo, a: perceptual roughness
// gbuffer_emission rgba16float  rgb: emitted radiance towards the camera, a: metallic
// gbuffer_motion   rgba32float  xy: where the surface was last frame minus where it is now, in
//                               pixels (unjittered); z: specular scale; w: unused
//
// The position is not stored: it is the camera ray's origin plus depth along the ray through
// the pixel's (jittered) sample point.
#import octahedral
#import surface

struct GBufferTexels {
    depth: f32,
    normal: vec4<f32>,
    albedo: vec4<f32>,
    emission: vec4<f32>,
    motion: vec4<f32>,
}

fn gbuffer_pack(s: Surface, depth: f32, motion: vec2<f32>) -> GBufferTexels {
    var t: GBufferTexels;
    t.depth = depth;
    t.normal = vec4<f32>(oct_encode(s.normal), oct_encode(s.geometric_normal));
    t.albedo = vec4<f32>(s.albedo, s.roughness);
    t.emission = vec4<f32>(s.emission, s.metallic);
    t.motion = vec4<f32>(motion, s.specular, 0.0);
    return t;
}

fn gbuffer_unpack(t: GBufferTexels, position: vec3<f32>) -> Surface {
    var s: Surface;
    s.position = position;
    s.normal = oct_decode(t.normal.xy);
    s.geometric_normal = oct_decode(t.normal.zw);
    s.albedo = t.albedo.rgb;
    s.roughness = t.albedo.a;
    s.emission = t.emission.rgb;
    s.metallic = t.emission.a;
    s.specular = t.motion.z;
    return s;
}
