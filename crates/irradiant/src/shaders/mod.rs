//! The shader library: shared WGSL modules importable by name with `#import`, and the
//! constants Rust and WGSL share, generated from their one Rust definition.

use std::sync::{Arc, OnceLock};

use irradiant_gpu::{ComputePass, GpuContext, PassDesc, PassError, ShaderLibrary};

mod dispatch_constants {
    irradiant_gpu::wgsl_constants! {
        /// Workgroups in a row of the indirect dispatches the shaders write (DDGI's shadow
        /// queue and active probes, the path tracer's wavefront), folded as
        /// `Workgroups::linear` folds direct ones.
        WORKGROUP_FOLD: u32 = irradiant_gpu::WORKGROUP_FOLD;
    }
}

/// Workgroups a dispatch of rays whose lanes fetch (bvh_fetch.wgsl) holds at most, by default
/// (`speed.fetch_workgroups`, [`crate::raycast::RayCaster::new`]): a workgroup's run of rays
/// grows, in steps of 64, as the rays outnumber 64 × this. Runs keep the GPU full: on an H200
/// (2026-11-28, BENCHMARKS.md) runs of 256 rays made Sponza's 262 144 probe rays 23 % slower
/// (1 024 workgroups), while 2 million bench rays in 8 100 workgroups took 17–37 % less time
/// than a ray a thread; in 4 050 or 2 025 workgroups diffuse rays gained nothing more.
pub const FETCH_WORKGROUPS: u32 = 8192;

/// Rays a workgroup takes where its lanes fetch, for `rays` rays in all and a dispatch of at
/// most `workgroups` (dispatch.wgsl's `fetch_run`): 64 while they fit, then as many more 64s as
/// it takes.
fn fetch_run(rays: u64, workgroups: u32) -> u64 {
    64 * rays.div_ceil(64 * u64::from(workgroups.max(1))).max(1)
}

/// Whether lanes that fetch pay for `rays` rays in a dispatch of at most `workgroups`: only
/// where a run passes 64 rays, so that a lane has more than one ray to fetch. A run of 64 the
/// fetching loop walks slower than a ray a thread (8 % on Sponza's probe rays, H200).
pub(crate) fn fetch_pays(rays: u64, workgroups: u32) -> bool {
    rays > 64 * u64::from(workgroups.max(1))
}

/// The dispatch of `rays` rays whose lanes fetch, a run of [`fetch_run`] a workgroup (folded as
/// the shaders fold the indirect ones they write).
pub(crate) fn fetch_dispatch(rays: u64, workgroups: u32) -> irradiant_gpu::Workgroups {
    irradiant_gpu::Workgroups::linear(rays.div_ceil(fetch_run(rays, workgroups)))
}

/// Every shared WGSL module by its `#import` name, built once.
pub fn library() -> &'static ShaderLibrary {
    static LIBRARY: OnceLock<ShaderLibrary> = OnceLock::new();
    LIBRARY.get_or_init(|| {
        ShaderLibrary::default()
            .with("scene_constants", crate::scene::constants::wgsl())
            .with("frame_constants", crate::frame::constants::wgsl())
            .with("ddgi_constants", crate::ddgi::constants::wgsl())
            .with("ssil_constants", crate::ssil::constants::wgsl())
            .with("pathtrace_constants", crate::pathtrace::constants::wgsl())
            .with("probe_constants", crate::probes::constants::wgsl())
            .with("dispatch_constants", dispatch_constants::wgsl())
            .with("dispatch", include_str!("dispatch.wgsl"))
            .with("types", include_str!("types.wgsl"))
            .with("random", include_str!("random.wgsl"))
            .with("sampling", include_str!("sampling.wgsl"))
            .with("scene", include_str!("scene.wgsl"))
            .with("bvh", include_str!("bvh.wgsl"))
            .with("bvh_fetch", include_str!("bvh_fetch.wgsl"))
            .with("brdf", include_str!("brdf.wgsl"))
            .with("lights", include_str!("lights.wgsl"))
            .with("resampling", include_str!("resampling.wgsl"))
            .with("camera", include_str!("camera.wgsl"))
            .with("path", include_str!("../pathtrace/path.wgsl"))
            .with("pathtrace_params", include_str!("../pathtrace/params.wgsl"))
            .with("surface", include_str!("surface.wgsl"))
            .with("octahedral", crate::probes::octahedral::OCTAHEDRAL_WGSL)
            .with("probe_grid", include_str!("../probes/grid.wgsl"))
            .with("probe_atlas", include_str!("../probes/atlas.wgsl"))
            .with("frame_types", include_str!("../frame/frame_types.wgsl"))
            .with(
                "gbuffer_layout",
                include_str!("../frame/gbuffer_layout.wgsl"),
            )
            .with("gbuffer", include_str!("../frame/gbuffer_read.wgsl"))
            .with("gbuffer_write", include_str!("../frame/gbuffer_write.wgsl"))
            .with("history", include_str!("../frame/history.wgsl"))
            .with("direct_mean", include_str!("../frame/direct_mean.wgsl"))
            .with("ddgi_volume", include_str!("../ddgi/volume.wgsl"))
            .with("ddgi_query", include_str!("../ddgi/query.wgsl"))
            .with("ddgi_hit_light", include_str!("../ddgi/hit_light.wgsl"))
            .with("ddgi_gather", include_str!("../ddgi/gather_common.wgsl"))
            .with("ddgi_probes", include_str!("../ddgi/probes.wgsl"))
            .with("ddgi_rays", include_str!("../ddgi/rays.wgsl"))
            .with("ddgi_states", include_str!("../ddgi/states.wgsl"))
            .with("ddgi_convergence", include_str!("../ddgi/convergence.wgsl"))
            .with("ddgi_active", include_str!("../ddgi/active.wgsl"))
            .with("ddgi_active_list", include_str!("../ddgi/active_list.wgsl"))
            .with("ssil_common", include_str!("../ssil/common.wgsl"))
            .with("lightfield_constants", crate::lightfield::constants::wgsl())
            .with("host_constants", crate::host::constants::wgsl())
            .with("lightfield", include_str!("../lightfield/lightfield.wgsl"))
    })
}

/// A compute pass from the library's modules: composed, validated, reflected, compiled.
pub fn pass(ctx: &GpuContext, desc: &PassDesc) -> Result<Arc<ComputePass>, PassError> {
    ComputePass::new(ctx, library(), desc)
}
