//! Irradiant's GPU layer on wgpu: adapter and device, WGSL composition, GPU-struct layout
//! checks, timestamp profiling and readback. Techniques build on this; nothing here knows
//! about scenes or global illumination.

mod context;
mod layout;
mod profiler;
mod readback;
mod shader;

pub use context::{AdapterChoice, GpuContext, GpuError, GpuInfo};
pub use layout::{Expected, StructLayoutError, check_struct_layouts};
pub use profiler::{PassTiming, Profiler};
pub use readback::{read_buffer, read_buffer_as};
pub use shader::{ShaderError, ShaderLibrary, compose};

pub use bytemuck;
pub use wgpu;
