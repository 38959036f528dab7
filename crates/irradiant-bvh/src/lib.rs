//! Two-level bounding volume hierarchy for Irradiant's compute-shader ray tracing.
//!
//! Bottom level: one BVH per mesh, built once, SAH quality through obvhs (PLOC build,
//! reinsertion optimisation and leaf collapse by SAH cost, optional spatial pre-splits).
//! Top level: one BVH over the world-space boxes of the instances, rebuilt whenever an
//! instance moves (a handful of boxes: microseconds), so objects move without touching
//! their bottom-level trees.
//!
//! The top level, and the bottom level in its binary layout, use [`GpuBvhNode`], which stores
//! the boxes of *both* children in the parent: a traversal step tests two boxes with one
//! 64-byte load. The bottom level's wide layout ([`GpuWideBvhNode`], the default) is obvhs'
//! compressed 8-wide BVH: eight quantised boxes in 80 bytes.

use std::time::Duration;

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3, Vec3A};
use obvhs::{BvhBuildParams, aabb::Aabb, bvh2::Bvh2, triangle::Triangle};

mod cpu_trace;
mod depth;
mod wide;
pub use cpu_trace::{
    CpuHit, SLAB_FAR_SCALE, brute_force_closest_hit, intersect_triangle, traverse_packed,
};
pub use wide::{GpuWideBvhNode, WideBlas, build_wide_blas};

/// One inner node of a BVH2, holding the bounds of its two children.
///
/// Child encoding (`*_first`, `*_count`):
/// - `count == 0`: the child is an inner node; `first` is its index in the node array.
/// - `count > 0`: the child is a leaf of `count` primitives starting at `first` (triangles in
///   the global triangle array for a bottom level, instances for the top level).
/// - An absent child (the root of a one-leaf tree has one) has `first == ABSENT`, count 0
///   and a point box at 1e30, beyond any ray's reach. (An inverted box would not do: the slab
///   test's per-axis min/max swap turns it back into a valid box.)
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuBvhNode {
    pub a_min: [f32; 3],
    pub a_first: u32,
    pub a_max: [f32; 3],
    pub a_count: u32,
    pub b_min: [f32; 3],
    pub b_first: u32,
    pub b_max: [f32; 3],
    pub b_count: u32,
}
const _: () = assert!(std::mem::size_of::<GpuBvhNode>() == 64);

/// How much time to spend building for how fast the tree traces.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BuildQuality {
    /// PLOC with little optimisation: quickest build, slower rays (~10–20% on big scenes).
    Fast,
    /// PLOC, reinsertion and SAH leaf collapse: about embree's build time, good trees.
    #[default]
    Balanced,
    /// Adds spatial pre-splits of large triangles and more reinsertion: slowest build, fastest
    /// rays for scenes with long thin triangles (Sponza, Sibenik).
    Quality,
}

impl BuildQuality {
    fn params(self) -> BvhBuildParams {
        match self {
            BuildQuality::Fast => BvhBuildParams::fast_build(),
            BuildQuality::Balanced => BvhBuildParams::medium_build(),
            BuildQuality::Quality => BvhBuildParams::slow_build(),
        }
    }
}

/// A bottom-level BVH over one mesh.
#[derive(Clone, Debug)]
pub struct Blas {
    /// Nodes; child indices and primitive indices are local (0-based) until [`Blas::offset`].
    pub nodes: Vec<GpuBvhNode>,
    /// For each triangle slot referenced by the leaves, the mesh's triangle index. A triangle
    /// split by pre-splitting appears more than once.
    pub triangle_order: Vec<u32>,
    pub bounds: (Vec3, Vec3),
    /// Longest root-to-leaf path; traversal stacks must be at least this deep.
    pub depth: u32,
    /// The tree's SAH cost ([`sah_cost`]).
    pub sah_cost: f32,
}

/// The triangles as obvhs builds from them.
fn obvhs_triangles(triangles: &[[Vec3; 3]]) -> Vec<Triangle> {
    triangles
        .iter()
        .map(|t| Triangle {
            v0: t[0].into(),
            v1: t[1].into(),
            v2: t[2].into(),
        })
        .collect()
}

pub fn build_blas(triangles: &[[Vec3; 3]], quality: BuildQuality) -> Blas {
    let mut bvh = obvhs::bvh2::builder::build_bvh2_from_tris(
        &obvhs_triangles(triangles),
        quality.params(),
        &mut Duration::default(),
    );
    depth::bound_height(&mut bvh, MAX_BLAS_DEPTH);
    let (nodes, triangle_order, depth) = pack(&bvh);
    let root = bvh.nodes[0].aabb;
    Blas {
        sah_cost: sah_cost(&bvh),
        nodes,
        triangle_order,
        bounds: (Vec3::from(root.min), Vec3::from(root.max)),
        depth,
    }
}

/// Deepest bottom-level tree the builders make, in inner levels. SAH trees of real meshes stay
/// below it (Sibenik's binary tree is 30 deep, its wide tree 11); a degenerate mesh (triangles nested
/// in shrinking sizes: a 240-triangle one made 219 levels) would otherwise make trees hundreds deep, and every ray's stack as
/// large. Traversal stacks are sized to the deepest tree of the scene, so never more than this.
pub const MAX_BLAS_DEPTH: u32 = 40;

/// The least depth bound [`build_tlas`] accepts for `instances` instances: room for a balanced
/// tree with a margin for SAH's imbalance, so that bounding rarely changes the tree.
pub fn tlas_depth_bound(instances: usize) -> u32 {
    let balanced = (instances.max(2) as u32)
        .next_power_of_two()
        .trailing_zeros();
    (2 * balanced + 4).min(instances as u32 + 2)
}

/// The top-level BVH over instance boxes. Leaf `first` indexes the returned `instance_order`.
#[derive(Clone, Debug)]
pub struct Tlas {
    pub nodes: Vec<GpuBvhNode>,
    pub instance_order: Vec<u32>,
    pub depth: u32,
}

/// The top-level BVH over instance boxes, no deeper than `max_depth` (at least
/// [`tlas_depth_bound`] of the instance count).
pub fn build_tlas(instance_bounds: &[(Vec3, Vec3)], max_depth: u32) -> Tlas {
    let boxes: Vec<Aabb> = instance_bounds
        .iter()
        .map(|(lo, hi)| Aabb::new(Vec3A::from(*lo), Vec3A::from(*hi)))
        .collect();
    let mut params = BvhBuildParams::medium_build();
    // One instance a leaf: instances overlap much more than triangles do.
    params.max_prims_per_leaf = 1;
    let mut bvh = obvhs::bvh2::builder::build_bvh2(&boxes, params, &mut Duration::default());
    depth::bound_height(
        &mut bvh,
        max_depth.max(tlas_depth_bound(instance_bounds.len())),
    );
    let (nodes, instance_order, depth) = pack(&bvh);
    Tlas {
        nodes,
        instance_order,
        depth,
    }
}

/// A binary tree's SAH cost (MacDonald and Booth 1990): the expected work of a ray that
/// enters the root's box, a node visit and a triangle test counting 1 each — Σ over inner
/// nodes of their area share, plus Σ over leaves of area share × triangles. A measure of the
/// tree alone, so that a change of tree can be told from a change of kernel.
pub fn sah_cost(bvh: &Bvh2) -> f32 {
    let Some(root) = bvh.nodes.first() else {
        return 0.0;
    };
    let root_area = root.aabb.half_area();
    if root_area <= 0.0 {
        return 0.0;
    }
    let mut cost = 0.0;
    let mut work = vec![0usize];
    while let Some(i) = work.pop() {
        let node = &bvh.nodes[i];
        let share = node.aabb.half_area() / root_area;
        if node.is_leaf() {
            cost += share * node.prim_count as f32;
        } else {
            cost += share;
            let first = node.first_index as usize;
            work.extend([first, first + 1]);
        }
    }
    cost
}

/// World-space bounds of a box under an affine transform (the 8 corners).
pub fn transform_bounds(bounds: (Vec3, Vec3), transform: &Mat4) -> (Vec3, Vec3) {
    let (lo, hi) = bounds;
    let mut out = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for i in 0..8 {
        let corner = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let w = transform.transform_point3(corner);
        out = (out.0.min(w), out.1.max(w));
    }
    out
}

/// `first` of an absent child.
pub const ABSENT: u32 = u32::MAX;
/// Coordinates of an absent child's box: shaders cap ray length at 1e20.
const ABSENT_BOX: f32 = 1e30;

/// Converts obvhs' node list (children side by side, leaves as nodes) into parent-holds-both-
/// children-boxes nodes. Leaves' primitives are laid out in leaf order, so `first` indexes the
/// returned order list directly.
fn pack(bvh: &Bvh2) -> (Vec<GpuBvhNode>, Vec<u32>, u32) {
    let mut nodes = Vec::new();
    let mut order = Vec::new();
    let root = &bvh.nodes[0];
    let mut depth = 1;
    if root.is_leaf() {
        // A one-leaf tree: an inner root with the leaf as child a and no child b.
        let first = order.len() as u32;
        order.extend_from_slice(
            &bvh.primitive_indices[root.first_index as usize..][..root.prim_count as usize],
        );
        nodes.push(GpuBvhNode {
            a_min: root.aabb.min.into(),
            a_first: first,
            a_max: root.aabb.max.into(),
            a_count: root.prim_count,
            b_min: [ABSENT_BOX; 3],
            b_first: ABSENT,
            b_max: [ABSENT_BOX; 3],
            b_count: 0,
        });
        return (nodes, order, depth);
    }
    // (obvhs node index, packed slot, depth)
    let mut work = vec![(0usize, 0usize, 1u32)];
    nodes.push(GpuBvhNode::zeroed());
    while let Some((source, slot, level)) = work.pop() {
        depth = depth.max(level);
        let first_child = bvh.nodes[source].first_index as usize;
        let mut children = [(0u32, 0u32, [0f32; 3], [0f32; 3]); 2];
        for (k, child) in children.iter_mut().enumerate() {
            let node = &bvh.nodes[first_child + k];
            if node.is_leaf() {
                let first = order.len() as u32;
                order.extend_from_slice(
                    &bvh.primitive_indices[node.first_index as usize..][..node.prim_count as usize],
                );
                *child = (
                    first,
                    node.prim_count,
                    node.aabb.min.into(),
                    node.aabb.max.into(),
                );
            } else {
                let packed = nodes.len();
                nodes.push(GpuBvhNode::zeroed());
                work.push((first_child + k, packed, level + 1));
                *child = (packed as u32, 0, node.aabb.min.into(), node.aabb.max.into());
            }
        }
        let [a, b] = children;
        nodes[slot] = GpuBvhNode {
            a_min: a.2,
            a_first: a.0,
            a_max: a.3,
            a_count: a.1,
            b_min: b.2,
            b_first: b.0,
            b_max: b.3,
            b_count: b.1,
        };
    }
    (nodes, order, depth)
}

impl Blas {
    /// Shifts node and triangle indices so that several BLASes share one node array and one
    /// triangle array on the GPU.
    pub fn offset(&mut self, node_base: u32, triangle_base: u32) {
        for n in &mut self.nodes {
            for (first, count) in [(&mut n.a_first, n.a_count), (&mut n.b_first, n.b_count)] {
                if *first == ABSENT {
                    continue;
                }
                *first += if count == 0 { node_base } else { triangle_base };
            }
        }
    }
}

#[cfg(test)]
mod tests;
