//! The scene on the GPU: BVH nodes, triangles, instances, materials, lights, emitters and
//! textures, bound as group 0 of every ray-tracing pass (`shaders/scene.wgsl`).

use std::time::{Duration, Instant};

use glam::{Mat4, Vec3};
use irradiant_bvh::{
    BuildQuality, GpuBvhNode, GpuWideBvhNode, build_blas, build_tlas, build_wide_blas,
    transform_bounds,
};
use irradiant_gpu::{GpuContext, wgpu};
use irradiant_scene::{AlphaMode, LightKind, Pose, Scene};
use wgpu::util::DeviceExt;

use crate::RenderError;
use crate::gpu_types::*;
use crate::pipeline::{STORAGE_READ, UNIFORM, buffer_entry, sampler_entry, texture_entry};

/// How the scene is prepared for the GPU.
#[derive(Clone, Debug)]
pub struct GpuSceneSettings {
    /// Every texture is resampled to this square size in one texture array (lavapipe has no
    /// binding arrays). Larger keeps detail for the camera; GI barely needs it. 512 costs
    /// 1.4 MiB a texture with mips.
    pub texture_size: u32,
    /// BVH build effort: faster builds or faster rays. The bottom-level trees are built once
    /// per mesh (animation moves instances, not triangles), so the default spends the time:
    /// `Quality` takes 1.7–2× `Balanced`'s build time (Sibenik: 116–174 ms against 67–89 on
    /// the device machine's CPU) and traces its rays 2–9 % faster on an H200 (BENCHMARKS.md).
    pub bvh_quality: BuildQuality,
    /// Where each thread keeps its bottom-level traversal stack: private (per-thread) memory,
    /// or a slice of workgroup memory. Which is faster depends on the GPU: on an H200 the
    /// workgroup stack is 1.4–1.7× slower (BENCHMARKS.md), so private is the default.
    pub stack_in_workgroup: bool,
    /// The bottom-level trees' node layout. Wide (compressed 8-wide nodes) traverses
    /// incoherent rays faster on the GPUs measured (BENCHMARKS.md) and takes about half the
    /// node memory; binary is the simpler reference, and the one `stack_in_workgroup` applies to.
    pub blas_layout: BlasLayout,
}

/// How the bottom-level trees are laid out for traversal.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BlasLayout {
    /// Two children's boxes a 64-byte node ([`GpuBvhNode`]).
    Binary,
    /// Eight children's quantised boxes an 80-byte node ([`GpuWideBvhNode`], Ylitie et al. 2017).
    #[default]
    Wide,
}

impl Default for GpuSceneSettings {
    fn default() -> Self {
        Self {
            texture_size: 512,
            bvh_quality: BuildQuality::Quality,
            stack_in_workgroup: false,
            blas_layout: BlasLayout::Wide,
        }
    }
}

impl GpuSceneSettings {
    pub fn fast() -> Self {
        Self {
            texture_size: 256,
            bvh_quality: BuildQuality::Fast,
            ..Self::default()
        }
    }
    /// The default: 512² textures and `Quality` BVH builds (paid once a mesh).
    pub fn balanced() -> Self {
        Self::default()
    }
    pub fn quality() -> Self {
        Self {
            texture_size: 1024,
            ..Self::default()
        }
    }
}

/// Where each GPU triangle slot came from: (mesh, triangle of the mesh).
pub type TriangleSource = (u32, u32);

pub struct GpuScene {
    pub layout: wgpu::BindGroupLayout,
    pub bind_group: wgpu::BindGroup,
    nodes: wgpu::Buffer,
    instances: wgpu::Buffer,
    lights: wgpu::Buffer,
    emitters: wgpu::Buffer,
    info: wgpu::Buffer,
    /// Per mesh: root node and object-space bounds.
    blas_roots: Vec<(u32, (Vec3, Vec3))>,
    tlas_base: u32,
    /// Per mesh: emissive triangle slots with their emission luminance.
    mesh_emitters: Vec<Vec<(u32, f32)>>,
    /// Object-space triangles of each slot, for emitter areas.
    slot_triangles: Vec<[Vec3; 3]>,
    instance_meshes: Vec<u32>,
    /// Radiance of rays that leave the scene.
    pub sky: Vec3,
    /// The instance buffer is in top-level leaf order: entry k holds scene instance
    /// `instance_order[k]` (hits report k).
    pub instance_order: Vec<u32>,
    /// Last uploaded transforms, in scene order (motion vectors).
    previous_transforms: Vec<Mat4>,
    /// Per scene instance: whether an animation moves it.
    animated: Vec<bool>,
    /// Per scene instance: world-space bounds at the last uploaded pose.
    instance_bounds: Vec<(Vec3, Vec3)>,
    /// Depth of the top-level traversal stack: enough for any tree over the instances that
    /// PLOC builds in practice (it is rebuilt each frame, so its depth varies).
    tlas_stack: u32,
    stack_in_workgroup: bool,
    blas_layout: BlasLayout,
    pub triangle_sources: Vec<TriangleSource>,
    pub stats: GpuSceneStats,
}

#[derive(Clone, Debug, Default)]
pub struct GpuSceneStats {
    pub triangles: usize,
    pub bvh_nodes: usize,
    pub bvh_build: Duration,
    pub max_blas_depth: u32,
    pub texture_layers: u32,
    pub gpu_bytes: u64,
}

/// Deepest tree traversal supports: deeper means a degenerate mesh.
const MAX_STACK: u32 = 128;

impl GpuScene {
    pub fn new(
        ctx: &GpuContext,
        scene: &Scene,
        settings: &GpuSceneSettings,
    ) -> Result<Self, RenderError> {
        let device = &ctx.device;
        let start = Instant::now();
        let mut nodes: Vec<GpuBvhNode> = Vec::new();
        let mut wide_nodes: Vec<GpuWideBvhNode> = Vec::new();
        let mut triangles: Vec<GpuTriangle> = Vec::new();
        let mut shading: Vec<GpuTriangleShading> = Vec::new();
        let mut triangle_sources = Vec::new();
        let mut slot_triangles = Vec::new();
        let mut blas_roots = Vec::new();
        let mut mesh_emitters = Vec::new();
        let mut max_depth = 0;
        let alpha_tested: Vec<bool> = scene
            .materials
            .iter()
            .map(|m| matches!(m.alpha_mode, AlphaMode::Mask { .. }))
            .collect();
        for (mesh_index, mesh) in scene.meshes.iter().enumerate() {
            let tris: Vec<[Vec3; 3]> = (0..mesh.triangle_count())
                .map(|t| mesh.triangle(t))
                .collect();
            if tris.is_empty() {
                blas_roots.push((0, (Vec3::ZERO, Vec3::ZERO)));
                mesh_emitters.push(Vec::new());
                continue;
            }
            let slot_base = triangles.len() as u32;
            // (root node, object-space bounds, depth, leaf triangle order) of the mesh's tree.
            let (root, bounds, depth, triangle_order) = match settings.blas_layout {
                BlasLayout::Binary => {
                    let mut blas = build_blas(&tris, settings.bvh_quality);
                    let root = nodes.len() as u32;
                    blas.offset(root, slot_base);
                    nodes.extend_from_slice(&blas.nodes);
                    (root, blas.bounds, blas.depth, blas.triangle_order)
                }
                BlasLayout::Wide => {
                    let mut blas = build_wide_blas(&tris, settings.bvh_quality);
                    let root = wide_nodes.len() as u32;
                    blas.offset(root, slot_base);
                    wide_nodes.extend_from_slice(&blas.nodes);
                    (root, blas.bounds, blas.depth, blas.triangle_order)
                }
            };
            max_depth = max_depth.max(depth);
            blas_roots.push((root, bounds));
            let mut emissive = Vec::new();
            for &t in &triangle_order {
                let [a, b, c] = tris[t as usize];
                let material = mesh.triangle_materials[t as usize];
                let emission = scene.materials[material as usize].emission;
                if emission.max_element() > 0.0 {
                    emissive.push((triangles.len() as u32, luminance(emission)));
                }
                triangles.push(GpuTriangle {
                    v0: a.into(),
                    material,
                    e1: (b - a).into(),
                    flags: if alpha_tested[material as usize] {
                        TRIANGLE_ALPHA_TESTED
                    } else {
                        0
                    },
                    e2: (c - a).into(),
                    _pad: 0,
                });
                shading.push(triangle_shading(mesh, t as usize));
                triangle_sources.push((mesh_index as u32, t));
                slot_triangles.push([a, b, c]);
            }
            mesh_emitters.push(emissive);
        }
        if max_depth > MAX_STACK {
            return Err(RenderError::Scene(format!(
                "a mesh's BVH is {max_depth} levels deep, more than traversal supports ({MAX_STACK}); the mesh is degenerate (e.g. thousands of triangles on one point)"
            )));
        }
        let tlas_base = nodes.len() as u32;
        // Room for the top level: a binary tree over n leaves has fewer than n inner nodes.
        nodes.extend(std::iter::repeat_n(
            <GpuBvhNode as bytemuck::Zeroable>::zeroed(),
            scene.instances.len().max(1),
        ));
        let bvh_build = start.elapsed();

        let materials: Vec<GpuMaterial> = scene
            .materials
            .iter()
            .map(|m| GpuMaterial {
                base_color: m.base_color.into(),
                emission: m.emission.into(),
                texture: m.base_color_texture.map_or(-1, |t| t as i32),
                metallic: m.metallic,
                roughness: m.roughness,
                specular: m.specular,
                alpha_cutoff: match m.alpha_mode {
                    AlphaMode::Mask { cutoff } => cutoff,
                    AlphaMode::Opaque => -1.0,
                },
            })
            .collect();

        let storage = wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC;
        let max_binding = ctx.info.max_storage_buffer_binding_size;
        let buffer = |label: &str, contents: &[u8]| -> Result<wgpu::Buffer, RenderError> {
            if contents.len() as u64 > max_binding {
                return Err(RenderError::Scene(format!(
                    "{label} needs {} MiB, more than this adapter binds ({} MiB); use a smaller scene or another adapter",
                    contents.len() >> 20,
                    max_binding >> 20
                )));
            }
            Ok(
                device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some(label),
                    contents,
                    usage: storage,
                }),
            )
        };
        let nodes_buffer = buffer("scene/bvh_nodes", bytemuck::cast_slice(&nodes))?;
        if wide_nodes.is_empty() {
            wide_nodes.push(<GpuWideBvhNode as bytemuck::Zeroable>::zeroed());
        }
        let wide_nodes_buffer = buffer("scene/wide_bvh_nodes", bytemuck::cast_slice(&wide_nodes))?;
        let triangles_buffer = buffer("scene/triangles", bytemuck::cast_slice(&triangles))?;
        let shading_buffer = buffer("scene/triangle_shading", bytemuck::cast_slice(&shading))?;
        let instances = buffer(
            "scene/instances",
            &vec![0u8; size_of::<GpuInstance>() * scene.instances.len().max(1)],
        )?;
        let materials_buffer = buffer("scene/materials", bytemuck::cast_slice(&materials))?;
        let lights = buffer(
            "scene/lights",
            &vec![0u8; size_of::<GpuLight>() * scene.lights.len().max(1)],
        )?;
        let emitter_capacity: usize = scene
            .instances
            .iter()
            .map(|i| mesh_emitters[i.mesh as usize].len())
            .sum();
        let emitters = buffer(
            "scene/emitters",
            &vec![0u8; size_of::<GpuEmitter>() * emitter_capacity.max(1)],
        )?;
        let info = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("scene/info"),
            size: size_of::<GpuSceneInfo>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let (texture_view, texture_layers, texture_bytes) =
            upload_textures(ctx, scene, settings.texture_size)?;
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("scene/sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });

        let layout = scene_bind_group_layout(device);
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("scene/bind_group"),
            layout: &layout,
            entries: &[
                entry(0, &nodes_buffer),
                entry(1, &triangles_buffer),
                entry(2, &shading_buffer),
                entry(3, &instances),
                entry(4, &materials_buffer),
                entry(5, &lights),
                entry(6, &emitters),
                entry(7, &info),
                wgpu::BindGroupEntry {
                    binding: 8,
                    resource: wgpu::BindingResource::TextureView(&texture_view),
                },
                wgpu::BindGroupEntry {
                    binding: 9,
                    resource: wgpu::BindingResource::Sampler(&sampler),
                },
                entry(10, &wide_nodes_buffer),
            ],
        });
        let gpu_bytes = [
            &nodes_buffer,
            &wide_nodes_buffer,
            &triangles_buffer,
            &shading_buffer,
            &instances,
            &materials_buffer,
            &lights,
            &emitters,
        ]
        .iter()
        .map(|b| b.size())
        .sum::<u64>()
            + texture_bytes;
        let mut gpu_scene = Self {
            layout,
            bind_group,
            nodes: nodes_buffer,
            instances,
            lights,
            emitters,
            info,
            blas_roots,
            tlas_base,
            mesh_emitters,
            slot_triangles,
            instance_meshes: scene.instances.iter().map(|i| i.mesh).collect(),
            sky: scene.sky,
            instance_order: Vec::new(),
            previous_transforms: Vec::new(),
            animated: scene
                .instances
                .iter()
                .map(|instance| {
                    scene.animations.iter().any(|a| {
                        matches!(&a.target, irradiant_scene::AnimationTarget::Instance(name) if *name == instance.name)
                    })
                })
                .collect(),
            instance_bounds: Vec::new(),
            stack_in_workgroup: settings.stack_in_workgroup,
            blas_layout: settings.blas_layout,
            tlas_stack: (2 * (scene.instances.len().max(2) as f32).log2().ceil() as u32 + 4)
                .min(scene.instances.len() as u32 + 2),
            stats: GpuSceneStats {
                triangles: triangles.len(),
                bvh_nodes: nodes.len() + wide_nodes.len(),
                bvh_build,
                max_blas_depth: max_depth,
                texture_layers,
                gpu_bytes,
            },
            triangle_sources,
        };
        gpu_scene.update(ctx, &scene.pose_at(0.0));
        ctx.check("uploading the scene")?;
        Ok(gpu_scene)
    }

    /// Constants every shader that traces rays needs: traversal stacks as deep as the trees.
    pub fn shader_constants(&self) -> Vec<(&'static str, String)> {
        vec![
            (
                "BLAS_STACK_SIZE",
                format!("{}u", self.stats.max_blas_depth.max(2)),
            ),
            ("TLAS_STACK_SIZE", format!("{}u", self.tlas_stack)),
            (
                "STACK_IN_WORKGROUP",
                format!(
                    "{}u",
                    (self.stack_in_workgroup && self.blas_layout == BlasLayout::Binary) as u32
                ),
            ),
            (
                "BLAS_WIDE",
                format!("{}u", (self.blas_layout == BlasLayout::Wide) as u32),
            ),
        ]
    }

    /// Uploads what animation changes: instance transforms, the top-level BVH, lights and the
    /// emitter table. Cheap (no bottom-level work).
    pub fn update(&mut self, ctx: &GpuContext, pose: &Pose) {
        let queue = &ctx.queue;
        let mut instances = Vec::with_capacity(pose.instance_transforms.len());
        let mut boxes = Vec::with_capacity(pose.instance_transforms.len());
        for (i, transform) in pose.instance_transforms.iter().enumerate() {
            let (root, bounds) = self.blas_roots[self.instance_meshes[i] as usize];
            let previous = self.previous_transforms.get(i).unwrap_or(transform);
            instances.push(gpu_instance(transform, previous, root));
            boxes.push(transform_bounds(bounds, transform));
        }
        let tlas = build_tlas(&boxes);
        if tlas.depth > self.tlas_stack {
            tracing::warn!(
                "top-level BVH depth {} exceeds its traversal stack ({}): some instances may be missed this frame",
                tlas.depth,
                self.tlas_stack
            );
        }
        // The top level's leaves index instances in TLAS order: reorder instances to match.
        let ordered: Vec<GpuInstance> = tlas
            .instance_order
            .iter()
            .map(|&i| instances[i as usize])
            .collect();
        let mut tlas_nodes = tlas.nodes.clone();
        for n in &mut tlas_nodes {
            for (first, count) in [(&mut n.a_first, n.a_count), (&mut n.b_first, n.b_count)] {
                if count == 0 && *first != irradiant_bvh::ABSENT {
                    *first += self.tlas_base;
                }
            }
        }
        queue.write_buffer(&self.instances, 0, bytemuck::cast_slice(&ordered));
        queue.write_buffer(
            &self.nodes,
            self.tlas_base as u64 * size_of::<GpuBvhNode>() as u64,
            bytemuck::cast_slice(&tlas_nodes),
        );

        let lights: Vec<GpuLight> = pose.lights.iter().map(gpu_light).collect();
        if !lights.is_empty() {
            queue.write_buffer(&self.lights, 0, bytemuck::cast_slice(&lights));
        }

        // Emitters, chosen in proportion to luminance × world area.
        let mut emitters = Vec::new();
        let mut powers = Vec::new();
        for (ordered_index, &source) in tlas.instance_order.iter().enumerate() {
            let transform = &pose.instance_transforms[source as usize];
            for &(slot, lum) in &self.mesh_emitters[self.instance_meshes[source as usize] as usize]
            {
                let [a, b, c] =
                    self.slot_triangles[slot as usize].map(|p| transform.transform_point3(p));
                let area = 0.5 * (b - a).cross(c - a).length();
                emitters.push(GpuEmitter {
                    triangle: slot,
                    instance: ordered_index as u32,
                    cdf: 0.0,
                    _pad: 0,
                });
                powers.push(lum * area);
            }
        }
        let total: f32 = powers.iter().sum();
        let mut running = 0.0;
        for (e, p) in emitters.iter_mut().zip(&powers) {
            running += p;
            e.cdf = running / total;
        }
        if let Some(last) = emitters.last_mut() {
            last.cdf = 1.0;
        }
        if !emitters.is_empty() {
            queue.write_buffer(&self.emitters, 0, bytemuck::cast_slice(&emitters));
        }
        let info = GpuSceneInfo {
            sky: self.sky.into(),
            light_count: lights.len() as u32,
            emitter_count: emitters.len() as u32,
            emissive_power: total,
            tlas_root: self.tlas_base,
            instance_count: ordered.len() as u32,
        };
        queue.write_buffer(&self.info, 0, bytemuck::bytes_of(&info));
        self.instance_order = tlas.instance_order;
        self.previous_transforms = pose.instance_transforms.clone();
        self.instance_bounds = boxes;
    }

    /// World-space bounds of every instance an animation moves, at the current pose: where
    /// geometry may appear that the static scene does not have (DDGI wakes probes there).
    pub fn dynamic_bounds(&self) -> Vec<(Vec3, Vec3)> {
        self.instance_bounds
            .iter()
            .zip(&self.animated)
            .filter(|(_, animated)| **animated)
            .map(|(bounds, _)| *bounds)
            .collect()
    }
}

fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

fn entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

fn triangle_shading(mesh: &irradiant_scene::Mesh, t: usize) -> GpuTriangleShading {
    let idx = &mesh.indices[3 * t..3 * t + 3];
    let n = |k: usize| {
        mesh.normals
            .get(idx[k] as usize)
            .copied()
            .unwrap_or(Vec3::ZERO)
            .to_array()
    };
    let uv = |k: usize| {
        mesh.uvs
            .get(idx[k] as usize)
            .copied()
            .unwrap_or_default()
            .to_array()
    };
    GpuTriangleShading {
        n0: n(0),
        _pad0: 0,
        n1: n(1),
        _pad1: 0,
        n2: n(2),
        _pad2: 0,
        uv0: uv(0),
        uv1: uv(1),
        uv2: uv(2),
        _pad3: [0.0; 2],
    }
}

fn gpu_instance(transform: &Mat4, previous: &Mat4, blas_root: u32) -> GpuInstance {
    let inverse = transform.inverse();
    let rows = |m: &Mat4| {
        [
            m.row(0).to_array(),
            m.row(1).to_array(),
            m.row(2).to_array(),
        ]
    };
    let [w0, w1, w2] = rows(&inverse);
    let [o0, o1, o2] = rows(transform);
    let [p0, p1, p2] = rows(previous);
    GpuInstance {
        world_to_object0: w0,
        world_to_object1: w1,
        world_to_object2: w2,
        object_to_world0: o0,
        object_to_world1: o1,
        object_to_world2: o2,
        previous_object_to_world0: p0,
        previous_object_to_world1: p1,
        previous_object_to_world2: p2,
        blas_root,
        _pad0: 0,
        _pad1: 0,
        _pad2: 0,
    }
}

fn gpu_light(light: &irradiant_scene::Light) -> GpuLight {
    let (kind, cos_inner, cos_outer) = match light.kind {
        LightKind::Point => (LIGHT_POINT, 1.0, 1.0),
        LightKind::Directional => (LIGHT_DIRECTIONAL, 1.0, 1.0),
        LightKind::Spot {
            inner_angle,
            outer_angle,
        } => (LIGHT_SPOT, inner_angle.cos(), outer_angle.cos()),
    };
    GpuLight {
        position: light.position.into(),
        kind,
        direction: light.direction.normalize_or(-Vec3::Y).into(),
        cos_inner,
        power: light.power().into(),
        cos_outer,
    }
}

/// Group 0 of every ray-tracing pass, by name: what `shaders/scene.wgsl` declares.
pub fn scene_bind_group_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let storage = |binding| buffer_entry(binding, STORAGE_READ);
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("scene/layout"),
        entries: &[
            storage(0),                                                  // bvh_nodes
            storage(1),                                                  // triangles
            storage(2),                                                  // triangle_shading
            storage(3),                                                  // instances
            storage(4),                                                  // materials
            storage(5),                                                  // lights
            storage(6),                                                  // emitters
            buffer_entry(7, UNIFORM),                                    // scene_info
            texture_entry(8, wgpu::TextureViewDimension::D2Array, true), // scene_textures
            sampler_entry(9, wgpu::SamplerBindingType::Filtering),       // scene_sampler
            storage(10),                                                 // wide_nodes
        ],
    })
}

/// Resamples every texture to one square size with a full mip chain, into one array.
fn upload_textures(
    ctx: &GpuContext,
    scene: &Scene,
    size: u32,
) -> Result<(wgpu::TextureView, u32, u64), RenderError> {
    let limits = ctx.device.limits();
    let size = if scene.textures.is_empty() {
        1
    } else {
        size.clamp(1, limits.max_texture_dimension_2d)
    };
    let layers = scene.textures.len().max(1) as u32;
    if layers > limits.max_texture_array_layers {
        return Err(RenderError::Scene(format!(
            "the scene has {layers} textures; this adapter's texture arrays hold {}",
            limits.max_texture_array_layers
        )));
    }
    let mip_levels = 32 - size.leading_zeros();
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("scene/textures"),
        size: wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: layers,
        },
        mip_level_count: mip_levels,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8UnormSrgb,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    });
    let mut bytes = 0u64;
    for layer in 0..layers {
        let mut level_image = match scene.textures.get(layer as usize) {
            Some(t) => {
                let img = image::RgbaImage::from_raw(t.width, t.height, t.rgba8.clone())
                    .ok_or_else(|| {
                        RenderError::Scene(format!(
                            "texture '{}' has the wrong number of bytes",
                            t.name
                        ))
                    })?;
                image::imageops::resize(&img, size, size, image::imageops::FilterType::Triangle)
            }
            None => image::RgbaImage::from_pixel(1, 1, image::Rgba([255; 4])),
        };
        for level in 0..mip_levels {
            let s = (size >> level).max(1);
            if level > 0 {
                level_image = image::imageops::resize(
                    &level_image,
                    s,
                    s,
                    image::imageops::FilterType::Triangle,
                );
            }
            ctx.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: level,
                    origin: wgpu::Origin3d {
                        x: 0,
                        y: 0,
                        z: layer,
                    },
                    aspect: wgpu::TextureAspect::All,
                },
                level_image.as_raw(),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(4 * s),
                    rows_per_image: Some(s),
                },
                wgpu::Extent3d {
                    width: s,
                    height: s,
                    depth_or_array_layers: 1,
                },
            );
            bytes += 4 * s as u64 * s as u64;
        }
    }
    let view = texture.create_view(&wgpu::TextureViewDescriptor {
        label: Some("scene/textures_view"),
        dimension: Some(wgpu::TextureViewDimension::D2Array),
        ..Default::default()
    });
    Ok((view, layers, bytes))
}
