//! Compute pipelines from composed WGSL, with errors as values.

use irradiant_gpu::{GpuContext, compose, wgpu};

use crate::RenderError;

/// One compute stage: its label (`technique/stage`) names the pipeline, its passes and its
/// timings.
pub struct ComputeStage {
    pub label: &'static str,
    pub pipeline: wgpu::ComputePipeline,
}

impl ComputeStage {
    pub fn new(
        ctx: &GpuContext,
        label: &'static str,
        source: &str,
        constants: &[(&str, String)],
        layouts: &[&wgpu::BindGroupLayout],
    ) -> Result<Self, RenderError> {
        let wgsl = compose(label, source, &crate::shaders::library(), constants)?;
        let pipeline = ctx.scoped(label, |device| {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(wgsl.into()),
            });
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: &layouts.iter().map(|l| Some(*l)).collect::<Vec<_>>(),
                immediate_size: 0,
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: Some(&layout),
                module: &module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            })
        })?;
        Ok(Self { label, pipeline })
    }

    /// A stage that traces rays: the scene's bind group layout is group 0 and its shader
    /// constants (traversal stack depths) are defined.
    pub fn tracing(
        ctx: &GpuContext,
        scene: &crate::GpuScene,
        label: &'static str,
        source: &str,
        constants: &[(&str, String)],
        group: &wgpu::BindGroupLayout,
    ) -> Result<Self, RenderError> {
        Self::tracing_with_groups(ctx, scene, label, source, constants, &[group])
    }

    /// [`Self::tracing`] with several bind groups after the scene's (groups 1, 2, …).
    pub fn tracing_with_groups(
        ctx: &GpuContext,
        scene: &crate::GpuScene,
        label: &'static str,
        source: &str,
        constants: &[(&str, String)],
        groups: &[&wgpu::BindGroupLayout],
    ) -> Result<Self, RenderError> {
        let mut all = scene.shader_constants();
        all.extend(constants.iter().cloned());
        let mut layouts = vec![&scene.layout];
        layouts.extend_from_slice(groups);
        Self::new(ctx, label, source, &all, &layouts)
    }

    /// Records one dispatch in its own compute pass (so that it gets its own timestamps).
    pub fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut irradiant_gpu::Profiler>,
        bind_groups: &[&wgpu::BindGroup],
        workgroups: [u32; 3],
    ) {
        let mut pass = self.begin(encoder, profiler, bind_groups);
        pass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
    }

    /// Like [`Self::dispatch`], with the workgroup counts read on the GPU: three u32 at
    /// `offset` in `args`, written by an earlier pass.
    pub fn dispatch_indirect(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut irradiant_gpu::Profiler>,
        bind_groups: &[&wgpu::BindGroup],
        args: &wgpu::Buffer,
        offset: u64,
    ) {
        let mut pass = self.begin(encoder, profiler, bind_groups);
        pass.dispatch_workgroups_indirect(args, offset);
    }

    fn begin<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        profiler: Option<&mut irradiant_gpu::Profiler>,
        bind_groups: &[&wgpu::BindGroup],
    ) -> wgpu::ComputePass<'e> {
        let timestamp_writes = profiler.and_then(|p| p.pass(self.label));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.label),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        for (i, group) in bind_groups.iter().enumerate() {
            pass.set_bind_group(i as u32, *group, &[]);
        }
        pass
    }
}

/// A bind group layout entry for a compute-stage buffer.
pub fn buffer_entry(binding: u32, ty: wgpu::BufferBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A bind group layout entry for a sampled compute-stage texture.
pub fn texture_entry(
    binding: u32,
    view_dimension: wgpu::TextureViewDimension,
    filterable: bool,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable },
            view_dimension,
            multisampled: false,
        },
        count: None,
    }
}

/// A bind group layout entry for a compute-stage sampler.
pub fn sampler_entry(binding: u32, kind: wgpu::SamplerBindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Sampler(kind),
        count: None,
    }
}

pub const UNIFORM: wgpu::BufferBindingType = wgpu::BufferBindingType::Uniform;
pub const STORAGE_READ: wgpu::BufferBindingType =
    wgpu::BufferBindingType::Storage { read_only: true };
pub const STORAGE_WRITE: wgpu::BufferBindingType =
    wgpu::BufferBindingType::Storage { read_only: false };

pub fn bind_buffers(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    buffers: &[&wgpu::Buffer],
) -> wgpu::BindGroup {
    let entries: Vec<_> = buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: b.as_entire_binding(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

pub fn uniform_buffer(device: &wgpu::Device, label: &str, size: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

pub fn storage_buffer(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(16),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

/// A bind group layout of compute-stage buffers: (binding, kind) pairs, each with its name in
/// the WGSL beside it at the call site.
pub fn buffer_layout(
    device: &wgpu::Device,
    label: &str,
    entries: &[(u32, wgpu::BufferBindingType)],
) -> wgpu::BindGroupLayout {
    let entries: Vec<_> = entries
        .iter()
        .map(|&(binding, ty)| buffer_entry(binding, ty))
        .collect();
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &entries,
    })
}

/// A bind group of buffers at explicit bindings.
pub fn bind_at(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    entries: &[(u32, &wgpu::Buffer)],
) -> wgpu::BindGroup {
    let entries: Vec<_> = entries
        .iter()
        .map(|&(binding, b)| wgpu::BindGroupEntry {
            binding,
            resource: b.as_entire_binding(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// Workgroup counts for `groups` workgroups, folded into two dimensions past the 65535 limit.
pub fn fold_groups(groups: u32) -> [u32; 3] {
    let x = groups.clamp(1, 32768);
    [x, groups.div_ceil(x).max(1), 1]
}
