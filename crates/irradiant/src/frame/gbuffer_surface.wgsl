// A G-buffer texel as the shared BRDF's Surface.
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
