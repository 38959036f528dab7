// G-buffer texels to and from the shared BRDF's Surface.
#import frame_types
#import surface

fn surface_from_gbuffer(g: GpuGBufferTexel) -> Surface {
    var s: Surface;
    s.position = g.position;
    s.geometric_normal = g.geometric_normal;
    s.normal = g.normal;
    s.albedo = g.albedo;
    s.metallic = g.metallic;
    s.roughness = g.roughness;
    s.specular = g.specular;
    s.emission = g.emission;
    return s;
}

// A texel for a surface `depth` along the camera ray (motion is left at zero).
fn gbuffer_from_surface(s: Surface, depth: f32) -> GpuGBufferTexel {
    var g: GpuGBufferTexel;
    g.position = s.position;
    g.depth = depth;
    g.normal = s.normal;
    g.geometric_normal = s.geometric_normal;
    g.albedo = s.albedo;
    g.roughness = s.roughness;
    g.metallic = s.metallic;
    g.specular = s.specular;
    g.emission = s.emission;
    return g;
}
