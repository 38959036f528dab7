//! The CPU half of putting a scene on the GPU: one bottom-level BVH per mesh (obvhs), the
//! triangles in BVH leaf order, and each mesh's emissive triangles. No GPU calls here.

use std::time::{Duration, Instant};

use glam::Vec3;
use irradiant_bvh::{Blas, GpuBvhNode, GpuWideBvhNode, WideBlas, build_blas, build_wide_blas};
use irradiant_scene::{AlphaMode, Mesh, Scene};
use rayon::prelude::*;

use super::constants::TRIANGLE_ALPHA_TESTED;
use super::types::{GpuTriangle, GpuTriangleShading};
use super::{BlasLayout, GpuSceneSettings, TriangleSource};
use crate::RenderError;

/// Every mesh's tree and triangles, ready to upload.
pub(super) struct SceneBuild {
    pub nodes: Vec<GpuBvhNode>,
    pub wide_nodes: Vec<GpuWideBvhNode>,
    pub triangles: Vec<GpuTriangle>,
    pub shading: Vec<GpuTriangleShading>,
    pub triangle_sources: Vec<TriangleSource>,
    /// Object-space corners of each triangle slot, for emitter areas.
    pub slot_triangles: Vec<[Vec3; 3]>,
    /// Per mesh: root node and object-space bounds.
    pub blas_roots: Vec<(u32, (Vec3, Vec3))>,
    /// Per mesh: emissive triangle slots with their emitted radiance.
    pub mesh_emitters: Vec<Vec<(u32, glam::Vec3)>>,
    pub max_depth: u32,
    /// The bottom-level trees' SAH cost, averaged over their triangles.
    pub sah_cost: f32,
    /// First node of the top level, after every mesh's nodes.
    pub tlas_base: u32,
    pub duration: Duration,
}

/// One mesh's triangles and bottom-level tree (none for an empty mesh).
struct MeshTree {
    tris: Vec<[Vec3; 3]>,
    tree: Option<Tree>,
}

enum Tree {
    Binary(Blas),
    Wide(WideBlas),
}

impl MeshTree {
    fn build(mesh: &Mesh, settings: &GpuSceneSettings) -> Self {
        let tris: Vec<[Vec3; 3]> = (0..mesh.triangle_count())
            .map(|t| mesh.triangle(t))
            .collect();
        let tree = (!tris.is_empty()).then(|| match settings.blas_layout {
            BlasLayout::Binary => Tree::Binary(build_blas(&tris, settings.bvh_quality)),
            BlasLayout::Wide => Tree::Wide(build_wide_blas(&tris, settings.bvh_quality)),
        });
        Self { tris, tree }
    }
}

impl SceneBuild {
    pub fn new(scene: &Scene, settings: &GpuSceneSettings) -> Result<Self, RenderError> {
        // The top-level tree needs a leaf; a host's session keeps one instance at least too.
        if scene.instances.is_empty() {
            return Err(RenderError::Scene(
                "the scene places no instance of any mesh: place one (a manifest's [mesh] or [[place]], or Scene::instances)".into(),
            ));
        }
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
        let (mut sah_weighted, mut sah_triangles) = (0.0f64, 0usize);
        let alpha_tested: Vec<bool> = scene
            .materials
            .iter()
            .map(|m| matches!(m.alpha_mode, AlphaMode::Mask { .. }))
            .collect();
        // Every mesh's tree at once (each build is parallel inside too), then laid end to end.
        let trees: Vec<MeshTree> = scene
            .meshes
            .par_iter()
            .map(|mesh| MeshTree::build(mesh, settings))
            .collect();
        for (mesh_index, (mesh, tree)) in scene.meshes.iter().zip(trees).enumerate() {
            let MeshTree { tris, tree } = tree;
            let Some(tree) = tree else {
                blas_roots.push((0, (Vec3::ZERO, Vec3::ZERO)));
                mesh_emitters.push(Vec::new());
                continue;
            };
            let slot_base = triangles.len() as u32;
            // (root node, object-space bounds, depth, leaf triangle order) of the mesh's tree.
            let (root, bounds, depth, triangle_order, sah_cost) = match tree {
                Tree::Binary(mut blas) => {
                    let root = nodes.len() as u32;
                    blas.offset(root, slot_base);
                    nodes.extend_from_slice(&blas.nodes);
                    (
                        root,
                        blas.bounds,
                        blas.depth,
                        blas.triangle_order,
                        blas.sah_cost,
                    )
                }
                Tree::Wide(mut blas) => {
                    let root = wide_nodes.len() as u32;
                    blas.offset(root, slot_base);
                    wide_nodes.extend_from_slice(&blas.nodes);
                    (
                        root,
                        blas.bounds,
                        blas.depth,
                        blas.triangle_order,
                        blas.sah_cost,
                    )
                }
            };
            sah_weighted += f64::from(sah_cost) * tris.len() as f64;
            sah_triangles += tris.len();
            max_depth = max_depth.max(depth);
            blas_roots.push((root, bounds));
            let mut emissive = Vec::new();
            for &t in &triangle_order {
                let [a, b, c] = tris[t as usize];
                let material = mesh.triangle_materials[t as usize];
                let emission = scene.materials[material as usize].emission;
                let mut shading_of = triangle_shading(mesh, t as usize);
                if emission.max_element() > 0.0 {
                    shading_of.emitter_ordinal = emissive.len() as u32;
                    emissive.push((triangles.len() as u32, emission));
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
                shading.push(shading_of);
                triangle_sources.push((mesh_index as u32, t));
                slot_triangles.push([a, b, c]);
            }
            mesh_emitters.push(emissive);
        }
        // The builders bound every tree's depth, so traversal stacks sized to the deepest
        // never overflow.
        debug_assert!(max_depth <= irradiant_bvh::MAX_BLAS_DEPTH);
        let tlas_base = nodes.len() as u32;
        // Room for the top level: a binary tree over n leaves has fewer than n inner nodes.
        nodes.extend(std::iter::repeat_n(
            <GpuBvhNode as bytemuck::Zeroable>::zeroed(),
            (scene.instances.len() + settings.instance_headroom as usize).max(1),
        ));
        if wide_nodes.is_empty() {
            wide_nodes.push(<GpuWideBvhNode as bytemuck::Zeroable>::zeroed());
        }
        Ok(Self {
            nodes,
            wide_nodes,
            triangles,
            shading,
            triangle_sources,
            slot_triangles,
            blas_roots,
            mesh_emitters,
            max_depth,
            sah_cost: (sah_weighted / sah_triangles.max(1) as f64) as f32,
            tlas_base,
            duration: start.elapsed(),
        })
    }
}

pub(super) fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
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
        emitter_ordinal: 0,
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
