//! Constants of the host G-buffer's conventions that host/gbuffer.rs and host/import.wgsl
//! share, defined once (the shader library serves them as the module `host_constants`).

irradiant_gpu::wgsl_constants! {
    /// Depth: the distance along the ray from the eye (Irradiant's own G-buffer).
    DEPTH_RAY_DISTANCE: u32 = 0;
    /// Depth: positive view-space z, the distance along the view direction.
    DEPTH_VIEW_Z: u32 = 1;
    /// Depth: a hardware depth buffer, 0 at the near plane and 1 at the far one.
    DEPTH_HARDWARE: u32 = 2;
    /// Depth: a reversed hardware depth buffer, 1 at the near plane and 0 at the far one.
    DEPTH_HARDWARE_REVERSED: u32 = 3;
    /// Depth: reversed with the far plane at infinity (depth = near ÷ view z).
    DEPTH_HARDWARE_REVERSED_INFINITE: u32 = 4;
    /// Normal: world space, xyz in −1…1 (a float or snorm texture).
    NORMAL_WORLD_SIGNED: u32 = 0;
    /// Normal: world space stored as (n + 1) ÷ 2 (a unorm texture).
    NORMAL_WORLD_UNORM: u32 = 1;
    /// Normal: view space (x right, y up, z towards the viewer), xyz in −1…1.
    NORMAL_VIEW_SIGNED: u32 = 2;
    /// Normal: view space stored as (n + 1) ÷ 2.
    NORMAL_VIEW_UNORM: u32 = 3;
    /// Normal: world space, octahedral in xy (Irradiant's own).
    NORMAL_OCTAHEDRAL: u32 = 4;
    /// Motion: none handed; the camera's motion is assumed (a static scene).
    MOTION_NONE: u32 = 0;
    /// Motion: where the surface was last frame minus where it is, in pixels (Irradiant's own).
    MOTION_PIXELS_TO_PREVIOUS: u32 = 1;
    /// Motion: the same in UV (0…1 across the image, y down).
    MOTION_UV_TO_PREVIOUS: u32 = 2;
    /// Motion: where the surface is minus where it was, in UV (y down).
    MOTION_UV_FROM_PREVIOUS: u32 = 3;
    /// A material channel that is not in the texture.
    CHANNEL_NONE: u32 = 4;
}
