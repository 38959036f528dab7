//! The raster host's renderer: its device (asked for what Irradiant needs), geometry,
//! G-buffer pass, Irradiant through `HostGi` in the same encoder, and its lighting pass into an
//! HDR image. `main.rs` drives it headless, `window.rs` into a window.

use std::error::Error;
use std::sync::Arc;

use glam::{Mat4, Vec4};
use irradiant::host::{DepthConvention, HostGBuffer, HostGi, MaterialChannels, NormalEncoding};
use irradiant::{GpuContext, Preset, SessionSettings, TechniqueSpec};
use wgpu::util::DeviceExt;

use crate::Options;

/// The host's projection: reversed Z (1 at the near plane, 0 at the far one).
const NEAR: f32 = 0.05;
const FAR: f32 = 1000.0;

/// One vertex of the host's geometry: every instance's triangles in world space, each with its
/// material (a host keeps these in its own formats; this one is the simplest).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    base_colour: [f32; 3],
    emission: [f32; 3],
    /// Roughness, metallic, specular scale.
    material: [f32; 3],
}

const RASTER_WGSL: &str = include_str!("raster.wgsl");

const COMPOSE_WGSL: &str = include_str!("compose.wgsl");

/// The host's G-buffer targets.
struct GBufferTargets {
    depth: wgpu::Texture,
    normal: wgpu::Texture,
    base_colour: wgpu::Texture,
    material: wgpu::Texture,
    emission: wgpu::Texture,
}

const FORMATS: [wgpu::TextureFormat; 4] = [
    wgpu::TextureFormat::Rgba16Float, // world normal, signed
    wgpu::TextureFormat::Rgba16Float, // base colour, linear
    wgpu::TextureFormat::Rgba8Unorm,  // roughness, metallic, specular scale (0…1)
    wgpu::TextureFormat::Rgba16Float, // emission
];

impl GBufferTargets {
    fn new(device: &wgpu::Device, (width, height): (u32, u32)) -> Self {
        let target = |label, format| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                // TEXTURE_BINDING: Irradiant reads them.
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
        };
        Self {
            depth: target("host/depth", wgpu::TextureFormat::Depth32Float),
            normal: target("host/normal", FORMATS[0]),
            base_colour: target("host/base_colour", FORMATS[1]),
            material: target("host/material", FORMATS[2]),
            emission: target("host/emission", FORMATS[3]),
        }
    }

    /// The G-buffer as Irradiant is told to read it.
    fn for_irradiant(&self) -> HostGBuffer<'_> {
        HostGBuffer {
            depth: &self.depth,
            depth_convention: DepthConvention::HardwareReversed {
                near: NEAR,
                far: FAR,
            },
            normal: &self.normal,
            normal_encoding: NormalEncoding::WorldSigned,
            base_colour: &self.base_colour,
            material: Some(&self.material),
            material_channels: MaterialChannels {
                roughness: Some(0),
                metallic: Some(1),
                specular: Some(2),
            },
            emission: Some(&self.emission),
            motion: None,
        }
    }
}

/// Every instance's triangles in world space, with their materials.
fn vertices(scene: &irradiant_scene::Scene) -> Vec<Vertex> {
    let mut out = Vec::new();
    for instance in &scene.instances {
        let mesh = &scene.meshes[instance.mesh as usize];
        let normal_matrix = instance.transform.inverse().transpose();
        for (t, corners) in mesh.indices.chunks_exact(3).enumerate() {
            let m = &scene.materials[mesh.triangle_materials[t] as usize];
            let p: [glam::Vec3; 3] = std::array::from_fn(|k| {
                instance
                    .transform
                    .transform_point3(mesh.positions[corners[k] as usize])
            });
            let flat = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
            for (k, &i) in corners.iter().enumerate() {
                let normal = mesh.normals.get(i as usize).map_or(flat, |n| {
                    normal_matrix.transform_vector3(*n).normalize_or_zero()
                });
                out.push(Vertex {
                    position: p[k].to_array(),
                    normal: normal.to_array(),
                    base_colour: m.base_color.truncate().to_array(),
                    emission: m.emission.to_array(),
                    material: [m.roughness, m.metallic, m.specular],
                });
            }
        }
    }
    out
}

/// The host's camera: Irradiant's view (position, target, vertical field of view) with a
/// reversed-Z projection at the image's aspect.
fn view_projection(camera: &irradiant_scene::Camera, (w, h): (u32, u32)) -> Mat4 {
    // A right-handed look-at: x right, y up, the view along −z.
    let f = (camera.target - camera.position).normalize();
    let s = f.cross(camera.up).normalize();
    let u = s.cross(f);
    let eye = camera.position;
    let view = Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
    );
    // Perspective with depth 1 at the near plane and 0 at the far one.
    let focal = 1.0 / (camera.fov_y_degrees.to_radians() * 0.5).tan();
    let aspect = w as f32 / h as f32;
    let projection = Mat4::from_cols(
        Vec4::new(focal / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, focal, 0.0, 0.0),
        Vec4::new(0.0, 0.0, NEAR / (FAR - NEAR), -1.0),
        Vec4::new(0.0, 0.0, FAR * NEAR / (FAR - NEAR), 0.0),
    );
    projection * view
}

/// Everything the host keeps between frames.
pub struct Host {
    pub ctx: Arc<GpuContext>,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub scene: irradiant_scene::Scene,
    pub size: (u32, u32),
    pub gi: HostGi,
    /// The lit image, linear (Rgba32Float).
    pub hdr: wgpu::Texture,
    vertex_buffer: wgpu::Buffer,
    vertex_count: u32,
    targets: GBufferTargets,
    raster: wgpu::RenderPipeline,
    raster_group: wgpu::BindGroup,
    compose: wgpu::RenderPipeline,
    compose_group: wgpu::BindGroup,
    depth_view: wgpu::TextureView,
    /// The G-buffer pass's colour targets: the host's, or with --native Irradiant's own.
    gbuffer_views: Vec<wgpu::TextureView>,
    native: bool,
    hdr_view: wgpu::TextureView,
}

impl Host {
    /// The device on `instance`'s first adapter, the scene, Irradiant and the host's passes.
    pub fn new(options: &Options, instance: wgpu::Instance) -> Result<Self, Box<dyn Error>> {
        let scene = irradiant_scene::load(&options.scene)?.scene;
        let size = options.size;
        // The host's device, asked for what Irradiant needs.
        let adapter = pollster::block_on(instance.request_adapter(&Default::default()))?;
        let (features, limits) = GpuContext::requirements(&adapter)?;
        let (device, queue) =
            pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
                label: Some("host"),
                required_features: features,
                required_limits: limits,
                ..Default::default()
            }))?;
        let ctx = Arc::new(GpuContext::from_host(
            instance,
            adapter,
            device.clone(),
            queue.clone(),
        )?);
        let mut gi = HostGi::new(
            ctx.clone(),
            scene.clone(),
            SessionSettings {
                size,
                technique: TechniqueSpec::new(&options.technique, Preset::Balanced),
                ..Default::default()
            },
        )?;
        // This host has no shadow maps: it takes Irradiant's ray-traced direct light too.
        gi.set_direct_light(true);

        // The host's own geometry, G-buffer and passes.
        let vertices = vertices(&scene);
        let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("host/vertices"),
            contents: bytemuck::cast_slice(&vertices),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let camera = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("host/camera"),
            // The shader's Camera: the view-projection matrix, then the eye.
            contents: bytemuck::cast_slice(
                &[
                    view_projection(&scene.camera, size)
                        .to_cols_array()
                        .as_slice(),
                    &scene.camera.position.extend(1.0).to_array(),
                ]
                .concat(),
            ),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let targets = GBufferTargets::new(&device, size);
        let raster_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("host/raster"),
            // Irradiant's octahedral encoding, for the native G-buffer's normals.
            source: wgpu::ShaderSource::Wgsl(
                format!("{}\n{RASTER_WGSL}", irradiant::host::OCTAHEDRAL_WGSL).into(),
            ),
        });
        // --native: the fragment shader writes Irradiant's layout into its textures.
        let native = if options.native {
            Some(gi.native_gbuffer()?)
        } else {
            None
        };
        let (fragment, formats) = match &native {
            Some(native) => ("fragment_native", native.formats.to_vec()),
            None => ("fragment", FORMATS.to_vec()),
        };
        let raster = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("host/raster"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &raster_module,
                entry_point: Some("vertex"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: std::mem::size_of::<Vertex>() as u64,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3, 3 => Float32x3, 4 => Float32x3],
                })],
            },
            fragment: Some(wgpu::FragmentState {
                module: &raster_module,
                entry_point: Some(fragment),
                compilation_options: Default::default(),
                targets: &formats.iter().map(|&f| Some(f.into())).collect::<Vec<_>>(),
            }),
            // Two-sided, as Irradiant's surfaces are.
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: wgpu::TextureFormat::Depth32Float,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Greater),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
        let raster_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("host/raster"),
            layout: &raster.get_bind_group_layout(0),
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: camera.as_entire_binding(),
            }],
        });
        let hdr = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("host/hdr"),
            size: wgpu::Extent3d {
                width: size.0,
                height: size.1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Float,
            // TEXTURE_BINDING: the window presents it.
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let compose_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("host/compose"),
            source: wgpu::ShaderSource::Wgsl(COMPOSE_WGSL.into()),
        });
        let compose = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("host/compose"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &compose_module,
                entry_point: Some("vertex"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            fragment: Some(wgpu::FragmentState {
                module: &compose_module,
                entry_point: Some("fragment"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::TextureFormat::Rgba32Float.into())],
            }),
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
        let sky = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("host/sky"),
            contents: bytemuck::bytes_of(&scene.sky.extend(1.0).to_array()),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let view = |t: &wgpu::Texture| t.create_view(&Default::default());
        let depth_view = targets.depth.create_view(&wgpu::TextureViewDescriptor {
            aspect: wgpu::TextureAspect::DepthOnly,
            ..Default::default()
        });
        // The emission and whether a pixel sees a surface (depth above 0 in both layouts).
        let (emission_view, surface_view) = match &native {
            Some(native) => (native.emission.clone(), native.depth.clone()),
            None => (view(&targets.emission), depth_view.clone()),
        };
        let compose_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("host/compose"),
            layout: &compose.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&emission_view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(gi.direct()),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(gi.indirect()),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::TextureView(&surface_view),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: sky.as_entire_binding(),
                },
            ],
        });
        let gbuffer_views = if let Some(n) = &native {
            [n.depth, n.normal, n.albedo, n.emission, n.motion]
                .map(|v| v.clone())
                .to_vec()
        } else {
            [
                &targets.normal,
                &targets.base_colour,
                &targets.material,
                &targets.emission,
            ]
            .map(view)
            .to_vec()
        };
        let hdr_view = view(&hdr);
        Ok(Self {
            ctx,
            device,
            queue,
            scene,
            size,
            gi,
            hdr,
            vertex_count: vertices.len() as u32,
            vertex_buffer,
            targets,
            raster,
            raster_group,
            compose,
            compose_group,
            depth_view,
            gbuffer_views,
            native: options.native,
            hdr_view,
        })
    }

    /// Records one frame into `encoder`: the host's G-buffer pass, Irradiant's passes (timed
    /// where `timed`: read them with `gi.session_mut().read_timings()` after submitting), and
    /// the host's lighting into [`Host::hdr`].
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        timed: bool,
    ) -> Result<(), Box<dyn Error>> {
        {
            // The host's G-buffer pass.
            let attachments: Vec<_> = (self.gbuffer_views.iter().enumerate())
                .map(|(i, v)| {
                    // Irradiant's depth is cleared to "no surface", -1.
                    let clear = if self.native && i == 0 {
                        wgpu::Color {
                            r: -1.0,
                            ..wgpu::Color::TRANSPARENT
                        }
                    } else {
                        wgpu::Color::TRANSPARENT
                    };
                    Some(wgpu::RenderPassColorAttachment {
                        view: v,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(clear),
                            store: wgpu::StoreOp::Store,
                        },
                    })
                })
                .collect();
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("host/gbuffer"),
                color_attachments: &attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth_view,
                    // Reversed Z: cleared to the far plane, 0.
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&self.raster);
            pass.set_bind_group(0, &self.raster_group, &[]);
            pass.set_vertex_buffer(0, self.vertex_buffer.slice(..));
            pass.draw(0..self.vertex_count, 0..1);
        }
        // Irradiant: its passes into the same encoder, after the G-buffer.
        let (camera, gbuffer) = (&self.scene.camera, self.targets.for_irradiant());
        match (self.native, timed) {
            (false, false) => self.gi.record(encoder, camera, &gbuffer)?,
            (false, true) => self.gi.record_timed(encoder, camera, &gbuffer)?,
            (true, false) => self.gi.record_native(encoder, camera)?,
            (true, true) => self.gi.record_native_timed(encoder, camera)?,
        }
        // The host's lighting: emission + direct + indirect.
        fullscreen_pass(
            encoder,
            "host/compose",
            &self.hdr_view,
            &self.compose,
            &self.compose_group,
        );
        Ok(())
    }

    /// The last frame's lit image, read back (linear).
    pub fn image(&self) -> Result<irradiant::frame::Image, Box<dyn Error>> {
        let texels: Vec<[f32; 4]> =
            bytemuck::pod_collect_to_vec(&irradiant_gpu::read_texture(&self.ctx, &self.hdr, 16)?);
        Ok(irradiant::frame::Image {
            width: self.size.0,
            height: self.size.1,
            pixels: texels.iter().map(|t| [t[0], t[1], t[2]]).collect(),
        })
    }
}

/// A full-screen triangle drawn with `pipeline` and `group` into `target` (cleared first): the
/// host's lighting pass, and the window's present pass.
pub fn fullscreen_pass(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    pipeline: &wgpu::RenderPipeline,
    group: &wgpu::BindGroup,
) {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, group, &[]);
    pass.draw(0..3, 0..1);
}
