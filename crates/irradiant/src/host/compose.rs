//! The indirect light added into a host's HDR target on request (`HostGi::compose_into`): a
//! full-screen triangle with additive blending, so that any renderable format works and the
//! host's lighting stays as it drew it. One pipeline per target format, made on first use.

use std::collections::HashMap;

use irradiant_gpu::{GpuContext, wgpu};

use crate::RenderError;

/// The fragment stage (the full-screen triangle is irradiant_gpu's).
const ADD_WGSL: &str = r#"
@group(0) @binding(0) var indirect: texture_2d<f32>;

@fragment
fn fragment(@builtin(position) p: vec4<f32>) -> @location(0) vec4<f32> {
    // Alpha 0: the blend adds the light and leaves the target's alpha as it is.
    return vec4<f32>(textureLoad(indirect, vec2<i32>(p.xy), 0).rgb, 0.0);
}
"#;

/// host/compose's pipelines, one a target format, and the last target's view and bind group
/// (a host composes into the same target frame after frame: nothing is made again then).
#[derive(Default)]
pub struct Composer {
    pipelines: HashMap<wgpu::TextureFormat, (wgpu::RenderPipeline, wgpu::BindGroupLayout)>,
    bound: Option<Bound>,
}

/// What one composition binds: the indirect light read, the target drawn into.
struct Bound {
    indirect: wgpu::TextureView,
    target: wgpu::Texture,
    target_view: wgpu::TextureView,
    group: wgpu::BindGroup,
}

impl Composer {
    /// Records `indirect` added into `target` (a view of a texture of the frame's size with
    /// RENDER_ATTACHMENT usage, of a blendable float or unorm format).
    pub fn record(
        &mut self,
        ctx: &GpuContext,
        encoder: &mut wgpu::CommandEncoder,
        indirect: &wgpu::TextureView,
        target: &wgpu::Texture,
        size: (u32, u32),
    ) -> Result<(), RenderError> {
        let format = target.format();
        let refuse = |problem: String| {
            RenderError::Settings(format!("HostGi::compose_into: the target {problem}"))
        };
        if (target.width(), target.height()) != size {
            return Err(refuse(format!(
                "is {}×{} where the frame is {}×{}: hand a target of the frame's size",
                target.width(),
                target.height(),
                size.0,
                size.1
            )));
        }
        if !target
            .usage()
            .contains(wgpu::TextureUsages::RENDER_ATTACHMENT)
        {
            return Err(refuse(
                "was created without RENDER_ATTACHMENT usage: add it where the host creates it"
                    .into(),
            ));
        }
        let blendable = format
            .guaranteed_format_features(ctx.device.features())
            .flags
            .contains(wgpu::TextureFormatFeatureFlags::BLENDABLE)
            || ctx
                .adapter
                .get_texture_format_features(format)
                .flags
                .contains(wgpu::TextureFormatFeatureFlags::BLENDABLE);
        if !blendable || format.is_depth_stencil_format() {
            return Err(refuse(format!(
                "has format {format:?}, which cannot be blended into: compose into an HDR colour target (Rgba16Float)"
            )));
        }
        let (pipeline, layout) = self
            .pipelines
            .entry(format)
            .or_insert_with(|| pipeline(ctx, format));
        let current = self
            .bound
            .as_ref()
            .is_some_and(|b| b.indirect == *indirect && b.target == *target);
        if !current {
            let group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("host/compose"),
                layout,
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(indirect),
                }],
            });
            self.bound = Some(Bound {
                indirect: indirect.clone(),
                target: target.clone(),
                target_view: target.create_view(&Default::default()),
                group,
            });
        }
        let bound = self.bound.as_ref().expect("made above");
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("host/compose"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &bound.target_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bound.group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}

fn pipeline(
    ctx: &GpuContext,
    format: wgpu::TextureFormat,
) -> (wgpu::RenderPipeline, wgpu::BindGroupLayout) {
    let layout = ctx
        .device
        .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("host/compose"),
            entries: &[irradiant_gpu::unfiltered_texture_entry(0)],
        });
    let add = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    };
    let target = wgpu::ColorTargetState {
        format,
        blend: Some(wgpu::BlendState {
            color: add,
            alpha: add,
        }),
        write_mask: wgpu::ColorWrites::ALL,
    };
    let pipeline =
        irradiant_gpu::fullscreen_pipeline(&ctx.device, "host/compose", ADD_WGSL, &layout, target);
    (pipeline, layout)
}
