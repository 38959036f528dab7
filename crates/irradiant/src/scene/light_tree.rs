//! The light tree: a binary tree over the emitters, each node bounding its emitters' positions,
//! power and facing, by which a shading point picks an emitter in proportion to an estimate of
//! the light it receives from it (Conty Estevez and Kulla 2018, "Importance Sampling of Many
//! Lights with Adaptive Tree Splitting", simplified: one pick a candidate, no splitting). Near
//! emitters that face the point win over far or turned-away ones of the same power, so few
//! candidates land behind the point or in the next room. Rebuilt with each pose (emitters
//! move with their instances); `sample_light_tree` in shaders/scene.wgsl walks it, and
//! `pick_probabilities` here walks it the same way on the CPU, as the oracle of the tests.

use glam::Vec3;

use super::constants::LIGHT_LEAF as LEAF;
use super::types::GpuLightNode;

/// An emitter as the tree sees it: its triangle's corners, unit normal and power.
#[derive(Clone, Copy, Debug)]
pub struct TreeEmitter {
    /// Its triangle's corners in world space.
    pub corners: [Vec3; 3],
    /// Its front face's unit normal.
    pub normal: Vec3,
    /// luminance(radiance) × area.
    pub power: f32,
}

/// The tree's nodes, root first, for `emitters` (in the emitter buffer's order).
pub fn build(emitters: &[TreeEmitter]) -> Vec<GpuLightNode> {
    if emitters.is_empty() {
        return Vec::new();
    }
    let mut nodes = vec![GpuLightNode::zeroed(); 1];
    let mut order: Vec<u32> = (0..emitters.len() as u32).collect();
    build_node(emitters, &mut order, 0, &mut nodes);
    nodes
}

fn build_node(emitters: &[TreeEmitter], order: &mut [u32], at: usize, nodes: &mut Vec<GpuLightNode>) {
    let (lo, hi, power, axis, cos_spread) = bound(emitters, order);
    let mut node = GpuLightNode {
        bounds_min: lo.into(),
        power,
        bounds_max: hi.into(),
        cos_spread,
        axis: axis.into(),
        child_or_emitter: 0,
    };
    if order.len() == 1 {
        node.child_or_emitter = LEAF | order[0];
        nodes[at] = node;
        return;
    }
    // Split at the median of the centroids along the box's longest side.
    let side = hi - lo;
    let dim = if side.x >= side.y && side.x >= side.z {
        0
    } else if side.y >= side.z {
        1
    } else {
        2
    };
    let centre = |i: &u32| {
        let c = emitters[*i as usize].corners;
        (c[0] + c[1] + c[2])[dim]
    };
    order.sort_by(|a, b| centre(a).total_cmp(&centre(b)));
    let first = nodes.len();
    node.child_or_emitter = first as u32;
    nodes[at] = node;
    nodes.push(GpuLightNode::zeroed());
    nodes.push(GpuLightNode::zeroed());
    let (left, right) = order.split_at_mut(order.len() / 2);
    build_node(emitters, left, first, nodes);
    build_node(emitters, right, first + 1, nodes);
}

/// Bounds of a set of emitters: box, power, the mean normal and the cosine of the widest angle
/// from it to any member's normal (a cone every normal lies in).
fn bound(emitters: &[TreeEmitter], order: &[u32]) -> (Vec3, Vec3, f32, Vec3, f32) {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let (mut power, mut sum) = (0.0, Vec3::ZERO);
    for &i in order {
        let e = &emitters[i as usize];
        for c in e.corners {
            lo = lo.min(c);
            hi = hi.max(c);
        }
        power += e.power;
        sum += e.normal;
    }
    let axis = sum.normalize_or_zero();
    let cos_spread = if axis == Vec3::ZERO {
        -1.0
    } else {
        order
            .iter()
            .map(|&i| emitters[i as usize].normal.dot(axis))
            .fold(1.0f32, f32::min)
    };
    (lo, hi, power, axis, cos_spread)
}

/// A node's importance seen from point p with normal n: power / d², where the box could face
/// the point and the point could face the box; 0 only where no emitter under the node can
/// light the point. The same arithmetic as `light_node_importance` in shaders/scene.wgsl.
#[cfg(test)]
pub fn importance(node: &GpuLightNode, p: Vec3, n: Vec3) -> f32 {
    let (lo, hi) = (Vec3::from(node.bounds_min), Vec3::from(node.bounds_max));
    let centre = 0.5 * (lo + hi);
    let radius = 0.5 * (hi - lo).length();
    let to_point = p - centre;
    let d2 = to_point.length_squared();
    // Inside or near the box every direction is possible.
    if d2 <= radius * radius * 1.0001 {
        return node.power / (radius * radius).max(1e-8);
    }
    let d = d2.sqrt();
    let dir = to_point / d;
    // The half-angle the box's bounding sphere subtends at p.
    let sin_u = (radius / d).min(1.0);
    let cos_u = (1.0 - sin_u * sin_u).max(0.0).sqrt();
    // Emitter side: the angle from the cone's axis to the point, less the cone and the box.
    let cos_theta = Vec3::from(node.axis).dot(dir);
    let emitter_side = cos_sub_clamped(cos_theta, node.cos_spread, cos_u);
    // Receiver side: the angle from n to the box's centre, less the box.
    let receiver_side = cos_sub_clamped(n.dot(-dir), 1.0, cos_u);
    if emitter_side <= 0.0 || receiver_side <= 0.0 {
        return 0.0;
    }
    node.power * emitter_side * receiver_side / d2.max(radius * radius)
}

/// cos(max(θ − α − β, 0)) from the cosines of θ, α and β (angles in [0, π]); 1 where θ is
/// within α + β.
#[cfg(test)]
pub fn cos_sub_clamped(cos_theta: f32, cos_alpha: f32, cos_beta: f32) -> f32 {
    let sin = |c: f32| (1.0 - c * c).max(0.0).sqrt();
    // cos(α + β), and whether θ ≤ α + β (α + β ≥ π always counts).
    let (sa, sb) = (sin(cos_alpha), sin(cos_beta));
    let cos_sum = cos_alpha * cos_beta - sa * sb;
    let sin_sum = sa * cos_beta + cos_alpha * sb;
    if sin_sum < 0.0 || cos_theta >= cos_sum {
        return 1.0;
    }
    // cos(θ − (α + β)) = cos θ cos(α+β) + sin θ sin(α+β)
    cos_theta * cos_sum + sin(cos_theta) * sin_sum
}

/// The probability each emitter is picked from p with normal n: the product of the choices
/// down the tree, each child in proportion to its importance (both children in proportion to
/// power where both are 0, which then light nothing).
#[cfg(test)]
pub fn pick_probabilities(nodes: &[GpuLightNode], count: usize, p: Vec3, n: Vec3) -> Vec<f64> {
    let mut out = vec![0.0; count];
    if !nodes.is_empty() {
        walk(nodes, 0, 1.0, p, n, &mut out);
    }
    out
}

#[cfg(test)]
fn walk(nodes: &[GpuLightNode], at: usize, probability: f64, p: Vec3, n: Vec3, out: &mut [f64]) {
    let node = &nodes[at];
    if node.child_or_emitter & LEAF != 0 {
        out[(node.child_or_emitter & !LEAF) as usize] += probability;
        return;
    }
    let first = node.child_or_emitter as usize;
    let left = child_probability(&nodes[first], &nodes[first + 1], p, n) as f64;
    walk(nodes, first, probability * left, p, n, out);
    walk(nodes, first + 1, probability * (1.0 - left), p, n, out);
}

/// The chance of taking `left` over `right` at p: their importances' share, or their powers'
/// where neither can light p. The same rule as the shader's.
#[cfg(test)]
pub fn child_probability(left: &GpuLightNode, right: &GpuLightNode, p: Vec3, n: Vec3) -> f32 {
    let (a, b) = (importance(left, p, n), importance(right, p, n));
    if a + b > 0.0 {
        a / (a + b)
    } else {
        left.power / (left.power + right.power).max(1e-30)
    }
}

trait Zeroed {
    fn zeroed() -> Self;
}

impl Zeroed for GpuLightNode {
    fn zeroed() -> Self {
        bytemuck::Zeroable::zeroed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 960 tiles in four rooms side by side, as `four-halls` has them, seen from points in the
    /// first: each point's pick probabilities sum to 1, every tile that can light the point
    /// (in front of it, facing it) has a chance, and a tile in the point's own room is picked
    /// far more often than one of the same power three rooms away.
    #[test]
    fn the_light_trees_picks_sum_to_one_and_reach_every_emitter_that_can_light() {
        let mut state = 0x2545_f491u32;
        let mut random = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32
        };
        let mut emitters = Vec::new();
        for room in 0..4 {
            for _ in 0..240 {
                let c = Vec3::new(-9.5 + 19.0 * random(), 3.999, -5.5 + 11.0 * random() + 13.0 * room as f32);
                let h = 0.075;
                emitters.push(TreeEmitter {
                    corners: [c + Vec3::new(-h, 0.0, -h), c + Vec3::new(h, 0.0, -h), c + Vec3::new(h, 0.0, h)],
                    normal: Vec3::NEG_Y,
                    power: 0.5 + random(),
                });
            }
        }
        let nodes = build(&emitters);
        assert_eq!(nodes.len(), 2 * emitters.len() - 1);
        for k in 0..20 {
            let p = Vec3::new(-9.0 + 18.0 * random(), 0.01 + 3.5 * random(), -5.0 + 10.0 * random());
            let n = if k % 2 == 0 { Vec3::Y } else { Vec3::new(random() - 0.5, random(), random() - 0.5).normalize() };
            let probabilities = pick_probabilities(&nodes, emitters.len(), p, n);
            let total: f64 = probabilities.iter().sum();
            assert!((total - 1.0).abs() < 1e-5, "point {p}: picks sum to {total}");
            for (i, (e, &pi)) in emitters.iter().zip(&probabilities).enumerate() {
                let lights = e.corners.iter().any(|&c| {
                    let to = c - p;
                    to.dot(n) > 0.0 && -to.dot(e.normal) > 0.0
                });
                assert!(!lights || pi > 0.0, "emitter {i} can light {p} but is never picked");
            }
            let own: f64 = probabilities[..240].iter().sum();
            let farthest: f64 = probabilities[720..].iter().sum();
            if n == Vec3::Y {
                assert!(own > 20.0 * farthest, "point {p}: own room {own}, three rooms away {farthest}");
            }
        }
    }

    /// cos(max(θ − α − β, 0)) against the angles themselves.
    #[test]
    fn the_cone_arithmetic_matches_the_angles() {
        for (theta, alpha, beta) in [(1.2f32, 0.3f32, 0.2f32), (0.4, 0.3, 0.2), (3.0, 1.0, 0.5), (2.5, 2.0, 1.5)] {
            let expected = (theta - alpha - beta).max(0.0).cos();
            let got = cos_sub_clamped(theta.cos(), alpha.cos(), beta.cos());
            assert!((got - expected).abs() < 1e-5, "θ {theta} α {alpha} β {beta}: {got} against {expected}");
        }
    }
}
