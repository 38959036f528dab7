//! The wide bottom level: obvhs' compressed 8-wide BVH (Ylitie, Karras and Laine 2017,
//! "Efficient Incoherent Ray Traversal on GPUs Through Compressed Wide BVHs"). One 80-byte
//! node holds eight children's boxes, quantised to bytes on a per-node grid, so a traversal
//! step tests eight boxes with five 16-byte loads; children are stored in an order from which
//! the ray's octant picks a near-to-far visit order with one XOR. On incoherent rays this
//! traverses in far fewer, cheaper steps than the binary tree of [`crate::GpuBvhNode`].

use bytemuck::{Pod, Zeroable};
use glam::Vec3;
use obvhs::{
    BvhBuildParams,
    aabb::Aabb,
    bvh2::{Bvh2, reinsertion::ReinsertionOptimizer},
    cwbvh::{bvh2_to_cwbvh::bvh2_to_cwbvh, node::CwBvhNode},
    ploc::PlocBuilder,
    splits::split_aabbs_preset,
    triangle::Triangle,
};

use crate::BuildQuality;

/// One node of the compressed 8-wide BVH, exactly obvhs' `CwBvhNode` (80 bytes) with its
/// byte arrays read as little-endian u32 words for WGSL, which has no bytes.
///
/// Bit layout (a "slot" is one of the 8 child positions; slot k lives in byte k % 4 of word
/// k / 4 of each two-word field):
/// - `exponents_imask`: bytes 0, 1, 2 are the biased exponents e of the child grid's scale on
///   x, y, z (a child plane lies at `origin + 2^(e−127) · q` for its byte q, i.e. the scale is
///   `bitcast<f32>(e << 23)`); byte 3 is imask, bit k set when slot k is an inner node.
/// - `child_base`: index of the first inner child; inner children are stored consecutively in
///   slot order, so slot k's node is `child_base + popcount(imask & ((1 << k) − 1))`.
/// - `primitive_base`: index of the first triangle slot of this node's leaves.
/// - `child_meta`, a byte per slot: 0 for an empty slot; for a leaf, its triangle count in
///   unary in the high 3 bits (1–3 triangles) and the offset of its first triangle from
///   `primitive_base` in the low 5 (0–23); for an inner child, 001 in the high 3 bits and
///   24 + slot in the low 5.
/// - `q_min_x` … `q_max_z`: each slot's quantised box planes, a byte per slot, rounded
///   outwards so that the quantised box contains the exact one.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct GpuWideBvhNode {
    pub origin: [f32; 3],
    pub exponents_imask: u32,
    pub child_base: u32,
    pub primitive_base: u32,
    pub child_meta: [u32; 2],
    pub q_min_x: [u32; 2],
    pub q_max_x: [u32; 2],
    pub q_min_y: [u32; 2],
    pub q_max_y: [u32; 2],
    pub q_min_z: [u32; 2],
    pub q_max_z: [u32; 2],
}
const _: () = assert!(size_of::<GpuWideBvhNode>() == 80);
const _: () = assert!(size_of::<CwBvhNode>() == 80);

impl GpuWideBvhNode {
    pub(crate) fn imask(&self) -> u32 {
        self.exponents_imask >> 24
    }

    /// Node index of the inner child in `slot`.
    pub(crate) fn inner_child(&self, slot: u32) -> u32 {
        self.child_base + (self.imask() & ((1 << slot) - 1)).count_ones()
    }
}

/// A bottom-level compressed wide BVH over one mesh.
#[derive(Clone, Debug)]
pub struct WideBlas {
    /// Nodes, the root first; indices are local (0-based) until [`WideBlas::offset`].
    pub nodes: Vec<GpuWideBvhNode>,
    /// For each triangle slot the leaves reference, the mesh's triangle index.
    pub triangle_order: Vec<u32>,
    pub bounds: (Vec3, Vec3),
    /// Longest root-to-leaf path in nodes: the traversal stack holds at most one entry a level.
    pub depth: u32,
    /// The SAH cost of the binary tree it was collapsed from ([`crate::sah_cost`]).
    pub sah_cost: f32,
}

pub fn build_wide_blas(triangles: &[[Vec3; 3]], quality: BuildQuality) -> WideBlas {
    let params = quality.params();
    let triangles = crate::obvhs_triangles(triangles);
    let mut bvh2 = ploc_tree(&triangles, params);
    ReinsertionOptimizer::default().run(&mut bvh2, params.reinsertion_batch_ratio, None);
    crate::depth::bound_height(&mut bvh2, crate::MAX_BLAS_DEPTH);
    let sah_cost = crate::sah_cost(&bvh2);
    let bvh = bvh2_to_cwbvh(&bvh2, params.max_prims_per_leaf.clamp(1, 3), true, false);
    let nodes: Vec<GpuWideBvhNode> = bvh.nodes.iter().map(|n| bytemuck::cast(*n)).collect();
    let depth = tree_depth(&nodes);
    WideBlas {
        nodes,
        triangle_order: bvh.primitive_indices,
        bounds: (bvh.total_aabb.min.into(), bvh.total_aabb.max.into()),
        depth,
        sah_cost,
    }
}

/// The binary tree obvhs turns into a wide one: PLOC over the triangles' boxes, after
/// splitting the largest of them first when `params.pre_split` asks for it (as obvhs'
/// `build_cwbvh_from_tris` does; rewritten here so that the depth bound comes before the
/// conversion).
fn ploc_tree(triangles: &[Triangle], params: BvhBuildParams) -> Bvh2 {
    let mut aabbs: Vec<Aabb> = triangles.iter().map(|t| t.aabb()).collect();
    let mut indices: Vec<u32> = (0..triangles.len() as u32).collect();
    if params.pre_split && !triangles.is_empty() {
        let largest = aabbs.iter().map(Aabb::half_area).fold(0.0, f32::max);
        let average = aabbs.iter().map(Aabb::half_area).sum::<f32>() / aabbs.len() as f32;
        split_aabbs_preset(&mut aabbs, &mut indices, triangles, average, largest);
    }
    let mut bvh2 = PlocBuilder::with_capacity(aabbs.len()).build(
        params.ploc_search_distance,
        &aabbs,
        indices,
        params.sort_precision,
        params.search_depth_threshold,
    );
    bvh2.uses_spatial_splits = params.pre_split;
    bvh2
}

fn tree_depth(nodes: &[GpuWideBvhNode]) -> u32 {
    let mut depth = 0;
    let mut work = vec![(0u32, 1u32)];
    while let Some((index, level)) = work.pop() {
        depth = depth.max(level);
        let node = &nodes[index as usize];
        for slot in 0..8 {
            if node.imask() & (1 << slot) != 0 {
                work.push((node.inner_child(slot), level + 1));
            }
        }
    }
    depth
}

impl WideBlas {
    /// Shifts node and triangle indices so that several BLASes share one node array and one
    /// triangle array on the GPU.
    pub fn offset(&mut self, node_base: u32, triangle_base: u32) {
        for n in &mut self.nodes {
            n.child_base += node_base;
            n.primitive_base += triangle_base;
        }
    }

    /// Every triangle slot a leaf references, with the box of that leaf, decoded from the
    /// quantised node: for checking that each leaf's box contains its triangles.
    pub fn leaves(&self) -> Vec<(u32, (Vec3, Vec3))> {
        let mut out = Vec::new();
        for n in &self.nodes {
            let scale = Vec3::new(
                f32::from_bits((n.exponents_imask & 0xff) << 23),
                f32::from_bits(((n.exponents_imask >> 8) & 0xff) << 23),
                f32::from_bits(((n.exponents_imask >> 16) & 0xff) << 23),
            );
            let origin = Vec3::from(n.origin);
            let byte =
                |words: [u32; 2], slot: u32| (words[slot as usize / 4] >> (8 * (slot % 4))) & 0xff;
            for slot in 0..8 {
                let meta = byte(n.child_meta, slot);
                if meta == 0 || n.imask() & (1 << slot) != 0 {
                    continue;
                }
                let lo = origin
                    + scale
                        * Vec3::new(
                            byte(n.q_min_x, slot) as f32,
                            byte(n.q_min_y, slot) as f32,
                            byte(n.q_min_z, slot) as f32,
                        );
                let hi = origin
                    + scale
                        * Vec3::new(
                            byte(n.q_max_x, slot) as f32,
                            byte(n.q_max_y, slot) as f32,
                            byte(n.q_max_z, slot) as f32,
                        );
                for k in 0..(meta >> 5).count_ones() {
                    out.push((n.primitive_base + (meta & 31) + k, (lo, hi)));
                }
            }
        }
        out
    }
}
