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
}
