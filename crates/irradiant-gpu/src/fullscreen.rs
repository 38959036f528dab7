//! A full-screen triangle drawn into one colour target: the viewer's blit and a host's
//! composition share its vertex stage and pipeline shape, and write only the fragment stage.

use wgpu::Device;

/// The vertex stage (`vertex`): one triangle covering the target, no vertex buffer. Prepended
/// to the fragment source by [`fullscreen_pipeline`].
pub const FULLSCREEN_VERTEX_WGSL: &str = r#"
@vertex
fn vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}
"#;

/// A render pipeline labelled `label` that draws the full-screen triangle (`draw(0..3, 0..1)`)
/// with `fragment_wgsl`'s `fragment` entry point, its one bind group laid out as `layout`,
/// into `target`.
pub fn fullscreen_pipeline(
    device: &Device,
    label: &str,
    fragment_wgsl: &str,
    layout: &wgpu::BindGroupLayout,
    target: wgpu::ColorTargetState,
) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(
            format!("{FULLSCREEN_VERTEX_WGSL}\n{fragment_wgsl}").into(),
        ),
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vertex"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fragment"),
            compilation_options: Default::default(),
            targets: &[Some(target)],
        }),
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        multiview_mask: None,
        cache: None,
    })
}

/// A fragment-stage texture binding, read with `textureLoad` (never filtered, so any float
/// format, 32-bit ones included, may be bound).
pub fn unfiltered_texture_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
        count: None,
    }
}
