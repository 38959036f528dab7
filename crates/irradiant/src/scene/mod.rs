//! The scene on the GPU: BVH nodes, triangles, instances, materials, lights, emitters and
//! textures, offered by name to every ray-tracing pass (`shaders/scene.wgsl` declares them).

mod build;
pub mod constants;
mod emitter_alias;
pub mod emitter_grid;
mod textures;
pub mod types;

use std::time::Duration;

use glam::{Mat4, Vec3};
use irradiant_bvh::{BuildQuality, GpuBvhNode, build_tlas, transform_bounds};
use irradiant_gpu::{Allocation, GpuContext, ResourceTable, wgpu};
use irradiant_scene::{AlphaMode, LightKind, Pose, Scene};
use wgpu::util::DeviceExt;

use crate::RenderError;
use build::{SceneBuild, luminance};
use constants::{LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT};
use types::*;

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
    /// Instances a host may add at run time ([`crate::Session::add_instance`]) beyond the
    /// scene's own before the scene's buffers are built anew (which rebuilds the frame and the
    /// technique, losing the probes' history). Each costs about 300 bytes, plus room for its
    /// mesh's emissive triangles were it the most emissive mesh; none for a scene that only
    /// ever holds what it loaded.
    pub instance_headroom: u32,
    /// How emitters are picked for next-event estimation and resampling: through the emitter
    /// grid (by power, facing and distance to the point's cell: `scene::emitter_grid`), or by
    /// power alone, the grid of one cell. The grid's picks find the near emitters that light
    /// a point (the path tracer's noise on `many-lights`: docs/pathtrace.md); it is built again
    /// on the CPU whenever an emitter moves or the top level reorders the instances (about
    /// 15 ms of one core for 1 000 emitters, spread over every core), where power alone
    /// builds one cell's table.
    pub emitter_grid: bool,
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
            instance_headroom: 0,
            emitter_grid: true,
        }
    }
}

impl GpuSceneSettings {
    /// 256² textures and `Fast` BVH builds: quicker to load, slower rays.
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
    /// 1024² textures, otherwise the default.
    pub fn quality() -> Self {
        Self {
            texture_size: 1024,
            ..Self::default()
        }
    }
}

/// Where each GPU triangle slot came from: (mesh, triangle of the mesh).
pub type TriangleSource = (u32, u32);

/// The scene on the GPU: its buffers, textures and BVH, bound by name by every ray-tracing
/// pass ([`GpuScene::resources`]); [`GpuScene::update`] uploads each new pose.
pub struct GpuScene {
    nodes: wgpu::Buffer,
    wide_nodes: wgpu::Buffer,
    triangles: wgpu::Buffer,
    triangle_shading: wgpu::Buffer,
    materials: wgpu::Buffer,
    textures: wgpu::TextureView,
    sampler: wgpu::Sampler,
    instances: wgpu::Buffer,
    lights: wgpu::Buffer,
    /// Punctual lights `lights` holds: the scene's, for good.
    light_count: usize,
    emitters: wgpu::Buffer,
    /// The emitter grid's texture (`scene::emitter_grid`), and its row width and cell budget.
    emitter_grid: wgpu::Texture,
    emitter_grid_view: wgpu::TextureView,
    emitter_grid_size: (u32, u32),
    /// The emitters the grid was last built for: it is built again only when they move.
    grid_built_for: Vec<GpuEmitter>,
    grid_shape: emitter_grid::GridShape,
    info: wgpu::Buffer,
    /// Per mesh: root node and object-space bounds.
    blas_roots: Vec<(u32, (Vec3, Vec3))>,
    tlas_base: u32,
    /// Per mesh: emissive triangle slots with their emitted radiance.
    mesh_emitters: Vec<Vec<(u32, Vec3)>>,
    /// Object-space triangles of each slot, for emitter areas.
    slot_triangles: Vec<[Vec3; 3]>,
    instance_meshes: Vec<u32>,
    /// Instances and emissive triangles the buffers hold room for.
    instance_capacity: usize,
    emitter_capacity: usize,
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
    /// Per GPU triangle slot (what a hit reports): the mesh triangle it came from.
    pub triangle_sources: Vec<TriangleSource>,
    /// Sizes and build time, for logs and benchmarks.
    pub stats: GpuSceneStats,
}

/// What putting the scene on the GPU made, and what it took.
#[derive(Clone, Debug, Default)]
pub struct GpuSceneStats {
    /// Triangle slots, over every mesh.
    pub triangles: usize,
    /// BVH nodes, binary and wide together (the top level's room included).
    pub bvh_nodes: usize,
    /// Wall time of building every bottom-level tree and laying out the triangles.
    pub bvh_build: Duration,
    /// Depth of the deepest bottom-level tree (sizes the traversal stack).
    pub max_blas_depth: u32,
    /// The bottom-level trees' SAH cost (`irradiant_bvh::sah_cost`), averaged over their
    /// triangles: the expected node visits and triangle tests of a ray through a tree.
    pub sah_cost: f32,
    /// Layers of the texture array (one a texture, at least one).
    pub texture_layers: u32,
    /// Bytes of every scene buffer and the texture array.
    pub gpu_bytes: u64,
}

impl GpuScene {
    /// Builds the BVHs, checks every allocation against the adapter, then uploads the scene
    /// posed at time 0.
    pub fn new(
        ctx: &GpuContext,
        scene: &Scene,
        settings: &GpuSceneSettings,
    ) -> Result<Self, RenderError> {
        let device = &ctx.device;
        let built = SceneBuild::new(scene, settings)?;
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
        let headroom = settings.instance_headroom as usize;
        let most_emissive_mesh = built.mesh_emitters.iter().map(Vec::len).max().unwrap_or(0);
        let emitter_capacity: usize = scene
            .instances
            .iter()
            .map(|i| built.mesh_emitters[i.mesh as usize].len())
            .sum::<usize>()
            + headroom * most_emissive_mesh;
        let instance_capacity = scene.instances.len() + headroom;
        let instance_bytes = size_of::<GpuInstance>() * instance_capacity.max(1);
        let light_bytes = size_of::<GpuLight>() * scene.lights.len().max(1);
        let emitter_bytes = size_of::<GpuEmitter>() * emitter_capacity.max(1);
        let setting = "the scene (fewer or smaller meshes)";
        let sizes = [
            ("scene/bvh_nodes", size_of_val(built.nodes.as_slice())),
            (
                "scene/wide_bvh_nodes",
                size_of_val(built.wide_nodes.as_slice()),
            ),
            ("scene/triangles", size_of_val(built.triangles.as_slice())),
            (
                "scene/triangle_shading",
                size_of_val(built.shading.as_slice()),
            ),
            ("scene/instances", instance_bytes),
            ("scene/materials", size_of_val(materials.as_slice())),
            ("scene/lights", light_bytes),
            ("scene/emitters", emitter_bytes),
        ];
        let mut plan: Vec<Allocation> = sizes
            .iter()
            .map(|&(label, bytes)| Allocation::storage(label, bytes as u64, setting))
            .collect();
        plan.push(textures::plan(ctx, scene, settings.texture_size));
        let (grid_width, grid_height, grid_cells) = emitter_grid::texture_size(
            emitter_capacity,
            ctx.device.limits().max_texture_dimension_2d,
            settings.emitter_grid,
        );
        plan.push(Allocation::texture(
            "scene/emitter_grid",
            (grid_width, grid_height),
            16,
            1,
            "the scene's emissive triangles (fewer)",
        ));
        ctx.check_allocations(&plan).map_err(RenderError::Gpu)?;

        let storage = wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC;
        let buffer = |label: &str, contents: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: storage,
            })
        };
        let nodes = buffer("scene/bvh_nodes", bytemuck::cast_slice(&built.nodes));
        let wide_nodes = buffer(
            "scene/wide_bvh_nodes",
            bytemuck::cast_slice(&built.wide_nodes),
        );
        let triangles = buffer("scene/triangles", bytemuck::cast_slice(&built.triangles));
        let triangle_shading = buffer(
            "scene/triangle_shading",
            bytemuck::cast_slice(&built.shading),
        );
        let instances = buffer("scene/instances", &vec![0u8; instance_bytes]);
        let materials_buffer = buffer("scene/materials", bytemuck::cast_slice(&materials));
        let lights = buffer("scene/lights", &vec![0u8; light_bytes]);
        let emitters = buffer("scene/emitters", &vec![0u8; emitter_bytes]);
        let emitter_grid = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("scene/emitter_grid"),
            size: wgpu::Extent3d {
                width: grid_width,
                height: grid_height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba32Uint,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let emitter_grid_view = emitter_grid.create_view(&Default::default());
        let info = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("scene/info"),
            size: size_of::<GpuSceneInfo>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let (texture_view, texture_layers, texture_bytes) =
            textures::upload_textures(ctx, scene, settings.texture_size)?;
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("scene/sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        let gpu_bytes = sizes.iter().map(|s| s.1 as u64).sum::<u64>()
            + texture_bytes
            + grid_width as u64 * grid_height as u64 * 16;
        let mut gpu_scene = Self {
            nodes,
            wide_nodes,
            triangles,
            triangle_shading,
            materials: materials_buffer,
            textures: texture_view,
            sampler,
            instances,
            lights,
            light_count: scene.lights.len(),
            emitters,
            emitter_grid,
            emitter_grid_view,
            emitter_grid_size: (grid_width, grid_cells),
            grid_built_for: Vec::new(),
            grid_shape: Default::default(),
            info,
            blas_roots: built.blas_roots,
            tlas_base: built.tlas_base,
            mesh_emitters: built.mesh_emitters,
            slot_triangles: built.slot_triangles,
            instance_meshes: scene.instances.iter().map(|i| i.mesh).collect(),
            instance_capacity,
            emitter_capacity,
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
            tlas_stack: irradiant_bvh::tlas_depth_bound(instance_capacity),
            stats: GpuSceneStats {
                triangles: built.triangles.len(),
                bvh_nodes: built.nodes.len() + built.wide_nodes.len(),
                bvh_build: built.duration,
                max_blas_depth: built.max_depth,
                sah_cost: built.sah_cost,
                texture_layers,
                gpu_bytes,
            },
            triangle_sources: built.triangle_sources,
        };
        gpu_scene.update(ctx, &scene.pose_at(0.0));
        ctx.check("uploading the scene")?;
        Ok(gpu_scene)
    }

    /// The scene's resources by the names `shaders/scene.wgsl` declares.
    pub fn resources(&self) -> ResourceTable<'_> {
        ResourceTable::new()
            .buffer("bvh_nodes", &self.nodes)
            .buffer("wide_nodes", &self.wide_nodes)
            .buffer("triangles", &self.triangles)
            .buffer("triangle_shading", &self.triangle_shading)
            .buffer("instances", &self.instances)
            .buffer("materials", &self.materials)
            .buffer("lights", &self.lights)
            .buffer("emitters", &self.emitters)
            .buffer("scene_info", &self.info)
            .texture("emitter_grid", &self.emitter_grid_view)
            .texture("scene_textures", &self.textures)
            .sampler("scene_sampler", &self.sampler)
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
            // One instance for good (no room left for a host's): the traversal needs no top level.
            (
                "ONE_INSTANCE",
                format!("{}u", (self.instance_capacity <= 1) as u32),
            ),
            (
                "SCENE_HAS_EMITTERS",
                format!("{}u", self.has_emitters() as u32),
            ),
            // The traversal's work counters: only raycast/trace's counting variant sets 1.
            ("COUNT_WORK", "0u".into()),
        ]
    }

    /// Whether ray kernels can walk a workgroup's rays with lanes that fetch the next ray as
    /// theirs ends (shaders/bvh_fetch.wgsl): the scene is one wide tree for good.
    pub fn fetches_rays(&self) -> bool {
        self.blas_layout == BlasLayout::Wide && self.instance_capacity <= 1
    }

    /// The scene's punctual lights (animation moves them but never adds one).
    pub(crate) fn light_count(&self) -> usize {
        self.light_count
    }

    /// Whether the scene can hold an emissive triangle: an instance's mesh has one, or room
    /// was left for a host to add one (shaders compiled without emitters skip them; animation
    /// moves emitters but never makes one).
    pub(crate) fn has_emitters(&self) -> bool {
        self.emitter_capacity > 0
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
        // Built no deeper than its traversal stack: a full stack never drops an instance.
        let tlas = build_tlas(&boxes, self.tlas_stack);
        debug_assert!(tlas.depth <= self.tlas_stack);
        // The top level's leaves index instances in TLAS order: reorder instances to match.
        // Each takes its mesh's emissive triangles' entries of the emitters buffer in turn.
        let mut emitter_base = 0u32;
        let ordered: Vec<GpuInstance> = tlas
            .instance_order
            .iter()
            .map(|&i| {
                let mut instance = instances[i as usize];
                instance.emitter_base = emitter_base;
                let mesh = self.instance_meshes[i as usize] as usize;
                emitter_base += self.mesh_emitters[mesh].len() as u32;
                instance
            })
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

        // Emitters in world space, in the instances' order, picked through the emitter grid.
        let mut emitters = Vec::new();
        let mut powers = Vec::new();
        for (ordered_index, &source) in tlas.instance_order.iter().enumerate() {
            let transform = &pose.instance_transforms[source as usize];
            let normal_matrix = transform.inverse().transpose();
            for &(slot, radiance) in
                &self.mesh_emitters[self.instance_meshes[source as usize] as usize]
            {
                let object = self.slot_triangles[slot as usize];
                let [a, b, c] = object.map(|p| transform.transform_point3(p));
                let area = 0.5 * (b - a).cross(c - a).length();
                let face = (object[1] - object[0]).cross(object[2] - object[0]);
                emitters.push(GpuEmitter {
                    v0: a.into(),
                    triangle: slot,
                    e1: (b - a).into(),
                    instance: ordered_index as u32,
                    e2: (c - a).into(),
                    cluster: 0,
                    normal: normal_matrix
                        .transform_vector3(face)
                        .normalize_or_zero()
                        .into(),
                    _pad: 0,
                    radiance: radiance.into(),
                    pdf_area: 0.0,
                });
                powers.push(luminance(radiance) * area);
            }
        }
        if !emitters.is_empty() && emitters != self.grid_built_for {
            self.build_emitter_grid(ctx, &boxes, emitters, &powers);
        }
        let shape = self.grid_shape;
        let info = GpuSceneInfo {
            sky: self.sky.into(),
            light_count: lights.len() as u32,
            emitter_count: emitter_base,
            grid_clusters: shape.clusters,
            tlas_root: self.tlas_base,
            instance_count: ordered.len() as u32,
            grid_min: shape.min.into(),
            grid_width: self.emitter_grid_size.0,
            grid_inverse_cell: shape.inverse_cell.into(),
            grid_member_row: shape.member_row,
            grid_dims: shape.dims.into(),
            _pad: 0,
        };
        queue.write_buffer(&self.info, 0, bytemuck::bytes_of(&info));
        self.instance_order = tlas.instance_order;
        self.previous_transforms = pose.instance_transforms.clone();
        self.instance_bounds = boxes;
    }

    /// Builds the emitter grid over the instances' `boxes` for `emitters` (without their
    /// cluster and pdf, which it sets) and uploads both.
    fn build_emitter_grid(
        &mut self,
        ctx: &GpuContext,
        boxes: &[(Vec3, Vec3)],
        mut emitters: Vec<GpuEmitter>,
        powers: &[f32],
    ) {
        let bounds = boxes.iter().fold(
            (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)),
            |(lo, hi), &(a, b)| (lo.min(a), hi.max(b)),
        );
        let unset = emitters.clone();
        let grid = emitter_grid::EmitterGrid::build(
            &mut emitters,
            powers,
            bounds,
            self.emitter_grid_size,
            emitter_grid::MEMBER_EVALUATIONS,
        );
        ctx.queue
            .write_buffer(&self.emitters, 0, bytemuck::cast_slice(&emitters));
        let rows = grid.texels.len() as u32 / grid.width;
        ctx.queue.write_texture(
            self.emitter_grid.as_image_copy(),
            bytemuck::cast_slice(&grid.texels),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(grid.width * 16),
                rows_per_image: Some(rows),
            },
            wgpu::Extent3d {
                width: grid.width,
                height: rows,
                depth_or_array_layers: 1,
            },
        );
        self.grid_shape = grid.shape;
        self.grid_built_for = unset;
    }

    /// Counts instance `index` as moving from now on (a host moves it by hand): its bounds join
    /// [`GpuScene::dynamic_bounds`], where DDGI wakes sleeping probes.
    pub fn set_moving(&mut self, index: usize) {
        if let Some(moving) = self.animated.get_mut(index) {
            *moving = true;
        }
    }

    /// Whether the buffers have room for one more instance of `mesh` (its transform, its
    /// top-level node, its emissive triangles).
    pub fn has_room_for(&self, mesh: u32) -> bool {
        let emitters = |m: u32| self.mesh_emitters.get(m as usize).map_or(0, Vec::len);
        let used: usize = self.instance_meshes.iter().map(|&m| emitters(m)).sum();
        self.instance_meshes.len() < self.instance_capacity
            && used + emitters(mesh) <= self.emitter_capacity
    }

    /// Adds an instance of `mesh` after the last (its transform comes with the next pose),
    /// counted as moving; the caller checked [`GpuScene::has_room_for`].
    pub fn add_instance(&mut self, mesh: u32) {
        debug_assert!(self.has_room_for(mesh));
        self.instance_meshes.push(mesh);
        self.animated.push(true);
    }

    /// Removes instance `index` (later ones move down one); its world bounds at the last pose
    /// are returned, where the light it blocked or reflected changes.
    pub fn remove_instance(&mut self, index: usize) -> Option<(Vec3, Vec3)> {
        self.instance_meshes.remove(index);
        self.animated.remove(index);
        if index < self.previous_transforms.len() {
            self.previous_transforms.remove(index);
        }
        (index < self.instance_bounds.len()).then(|| self.instance_bounds.remove(index))
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
        emitter_base: 0,
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
