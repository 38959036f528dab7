//! A bound on tree depth. GPU traversal keeps a fixed-size stack per ray; a tree deeper than
//! the stack would drop subtrees and miss their triangles. SAH builders make degenerate trees
//! for degenerate input (thousands of triangles on one point, geometric series of sizes), so
//! after building, the lowest subtrees that reach past the bound are rebuilt as balanced trees
//! over their leaves (in leaf order, which keeps neighbours together). Ordinary meshes never
//! reach the bound and are left exactly as built.

use obvhs::{aabb::Aabb, bvh2::Bvh2, bvh2::node::Bvh2Node};

/// Levels of a balanced binary tree over `leaves` leaves, below its root.
fn balanced_height(leaves: u32) -> u32 {
    leaves.max(1).next_power_of_two().trailing_zeros()
}

/// Per node: levels below it (0 for a leaf) and leaf count, for the nodes reachable from the
/// root.
fn heights_and_leaves(bvh: &Bvh2) -> (Vec<u32>, Vec<u32>) {
    let mut height = vec![0u32; bvh.nodes.len()];
    let mut leaves = vec![1u32; bvh.nodes.len()];
    let mut preorder = vec![0usize];
    let mut i = 0;
    while i < preorder.len() {
        let node = &bvh.nodes[preorder[i]];
        if !node.is_leaf() {
            preorder.extend([node.first_index as usize, node.first_index as usize + 1]);
        }
        i += 1;
    }
    for &index in preorder.iter().rev() {
        let node = &bvh.nodes[index];
        if !node.is_leaf() {
            let (a, b) = (node.first_index as usize, node.first_index as usize + 1);
            height[index] = 1 + height[a].max(height[b]);
            leaves[index] = leaves[a] + leaves[b];
        }
    }
    (height, leaves)
}

/// Levels below the root of the tree (0 for a one-leaf tree).
pub(crate) fn tree_height(bvh: &Bvh2) -> u32 {
    heights_and_leaves(bvh).0[0]
}

/// Rebuilds `bvh` so that no leaf lies more than `max_height` levels below the root, touching
/// only subtrees that break the bound. Needs `max_height ≥ log2(leaves)`, which any bound
/// worth having meets (`max_height` ≥ 32 for up to 4 billion leaves).
pub(crate) fn bound_height(bvh: &mut Bvh2, max_height: u32) {
    if bvh.nodes.is_empty() {
        return;
    }
    let (height, leaves) = heights_and_leaves(bvh);
    if height[0] <= max_height {
        return;
    }
    assert!(
        balanced_height(leaves[0]) <= max_height,
        "{} leaves cannot fit in {max_height} levels",
        leaves[0]
    );
    let fits = |node: usize, level: u32| level + height[node] <= max_height;
    let fixable = |node: usize, level: u32| level + balanced_height(leaves[node]) <= max_height;
    // Descend into a node that breaks the bound only while both children can still be
    // fixed lower down: the balanced rebuild then covers as few leaves as possible.
    let descend = |node: usize, level: u32| {
        let first = bvh.nodes[node].first_index as usize;
        [first, first + 1]
            .into_iter()
            .all(|child| fits(child, level + 1) || fixable(child, level + 1))
    };
    let mut out: Vec<Bvh2Node> = vec![bvh.nodes[0]];
    // (node in `bvh`, its slot in `out`, its level)
    let mut work = vec![(0usize, 0usize, 0u32)];
    while let Some((node, slot, level)) = work.pop() {
        if bvh.nodes[node].is_leaf() {
            continue;
        }
        if !fits(node, level) && !descend(node, level) {
            let mut subtree_leaves = Vec::with_capacity(leaves[node] as usize);
            collect_leaves(bvh, node, &mut subtree_leaves);
            write_balanced(&mut out, slot, &subtree_leaves);
            continue;
        }
        let first = bvh.nodes[node].first_index as usize;
        let children = out.len();
        out[slot].first_index = children as u32;
        out.extend([bvh.nodes[first], bvh.nodes[first + 1]]);
        work.push((first, children, level + 1));
        work.push((first + 1, children + 1, level + 1));
    }
    bvh.nodes = out;
    // Lookups the builder keeps point at the old node indices.
    bvh.parents.clear();
    bvh.primitives_to_nodes.clear();
    bvh.children_are_ordered_after_parents = false;
    bvh.max_depth = bvh.max_depth.max(max_height as usize + 1);
    debug_assert!(tree_height(bvh) <= max_height);
}

fn collect_leaves(bvh: &Bvh2, root: usize, out: &mut Vec<Bvh2Node>) {
    let mut stack = vec![root];
    while let Some(index) = stack.pop() {
        let node = bvh.nodes[index];
        if node.is_leaf() {
            out.push(node);
        } else {
            // Second child first onto the stack: leaves come out in the tree's order.
            stack.extend([node.first_index as usize + 1, node.first_index as usize]);
        }
    }
}

/// Writes a balanced tree over `leaves` into `out`, its root at `slot`.
fn write_balanced(out: &mut Vec<Bvh2Node>, slot: usize, leaves: &[Bvh2Node]) {
    let mut work = vec![(slot, leaves)];
    while let Some((slot, range)) = work.pop() {
        if let [leaf] = range {
            out[slot] = *leaf;
            continue;
        }
        let bounds = range
            .iter()
            .fold(Aabb::empty(), |acc, leaf| acc.union(&leaf.aabb));
        let children = out.len();
        out[slot] = Bvh2Node::new(bounds, 0, children as u32);
        out.extend([Bvh2Node::default(), Bvh2Node::default()]);
        let (a, b) = range.split_at(range.len().next_power_of_two() / 2);
        work.push((children, a));
        work.push((children + 1, b));
    }
}
