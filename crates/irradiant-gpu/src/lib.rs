//! Irradiant's GPU layer on wgpu: adapter and device, WGSL composition, passes declared once
//! in their WGSL and bound by name, sizes checked before allocation, GPU-struct layout checks,
//! timestamp profiling and readback. Techniques build on this; nothing here knows about scenes
//! or global illumination.

#![warn(missing_docs)]

mod budget;
mod context;
mod fullscreen;
mod layout;
mod pass;
mod profiler;
mod readback;
mod shader;

pub use budget::{Allocation, AllocationKind, Budget, bytes, texture_2d, texture_2d_array};
pub use context::{AdapterChoice, GpuContext, GpuError, GpuInfo, lavapipe_icd};
pub use fullscreen::{FULLSCREEN_VERTEX_WGSL, fullscreen_pipeline, unfiltered_texture_entry};
pub use layout::{Expected, StructLayoutError, check_struct_layouts};
pub use pass::{
    BindingDecl, BoundPass, ComputePass, MAX_WORKGROUPS_PER_DIMENSION, PassDesc, PassError,
    Resource, ResourceTable, WORKGROUP_FOLD, Workgroups,
};
pub use profiler::{PassTiming, Profiler};
pub use readback::{read_buffer, read_buffer_as, read_texture, read_texture_level};
pub use shader::{
    Composed, ShaderError, ShaderLibrary, WgslValue, compose, compose_module, wgsl_const,
};

pub use bytemuck;
pub use wgpu;
