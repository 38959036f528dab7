//! Shared WGSL modules, importable by name with `#import`.

use irradiant_gpu::ShaderLibrary;

pub fn library() -> ShaderLibrary {
    ShaderLibrary::default()
        .with("types", include_str!("types.wgsl"))
        .with("random", include_str!("random.wgsl"))
        .with("sampling", include_str!("sampling.wgsl"))
        .with("scene", include_str!("scene.wgsl"))
        .with("bvh", include_str!("bvh.wgsl"))
        .with("brdf", include_str!("brdf.wgsl"))
        .with("lights", include_str!("lights.wgsl"))
        .with("camera", include_str!("camera.wgsl"))
        .with("surface", include_str!("surface.wgsl"))
        .with("octahedral", include_str!("octahedral.wgsl"))
        .with("frame_types", include_str!("../frame/frame_types.wgsl"))
        .with(
            "gbuffer_surface",
            include_str!("../frame/gbuffer_surface.wgsl"),
        )
        .with("ddgi_volume", include_str!("../ddgi/volume.wgsl"))
        .with("ddgi_query", include_str!("../ddgi/query.wgsl"))
        .with("ddgi_probes", include_str!("../ddgi/probes.wgsl"))
        .with("ddgi_rays", include_str!("../ddgi/rays.wgsl"))
        .with("ddgi_states", include_str!("../ddgi/states.wgsl"))
}
