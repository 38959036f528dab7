//! CPU ray–triangle intersection: the oracle that GPU traversal is tested against.

use glam::Vec3;

use crate::GpuBvhNode;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CpuHit {
    pub t: f32,
    pub triangle: u32,
}

/// Möller–Trumbore, two-sided; returns the distance along `dir` (not normalised) if it lies in
/// (t_min, t_max).
pub fn intersect_triangle(
    origin: Vec3,
    dir: Vec3,
    tri: &[Vec3; 3],
    t_min: f32,
    t_max: f32,
) -> Option<f32> {
    let e1 = tri[1] - tri[0];
    let e2 = tri[2] - tri[0];
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let inv = 1.0 / det;
    let s = origin - tri[0];
    let u = s.dot(p) * inv;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let t = e2.dot(q) * inv;
    (t > t_min && t < t_max).then_some(t)
}

/// The closest hit by testing every triangle.
pub fn brute_force_closest_hit(
    origin: Vec3,
    dir: Vec3,
    triangles: &[[Vec3; 3]],
    t_max: f32,
) -> Option<CpuHit> {
    let mut best: Option<CpuHit> = None;
    for (i, tri) in triangles.iter().enumerate() {
        let limit = best.map_or(t_max, |b| b.t);
        if let Some(t) = intersect_triangle(origin, dir, tri, 0.0, limit) {
            best = Some(CpuHit {
                t,
                triangle: i as u32,
            });
        }
    }
    best
}

/// Closest hit by walking packed nodes the way the WGSL traversal does: checks the packing.
pub fn traverse_packed(
    nodes: &[GpuBvhNode],
    order: &[u32],
    origin: Vec3,
    dir: Vec3,
    triangles: &[[Vec3; 3]],
) -> Option<CpuHit> {
    let mut best: Option<CpuHit> = None;
    let mut stack = vec![0u32];
    let inv = dir.recip();
    while let Some(index) = stack.pop() {
        let n = &nodes[index as usize];
        for (lo, hi, first, count) in [
            (n.a_min, n.a_max, n.a_first, n.a_count),
            (n.b_min, n.b_max, n.b_first, n.b_count),
        ] {
            let t_max = best.map_or(1e20, |b| b.t);
            if first == crate::ABSENT || !slab(origin, inv, Vec3::from(lo), Vec3::from(hi), t_max) {
                continue;
            }
            if count == 0 {
                stack.push(first);
            } else {
                for slot in first..first + count {
                    let triangle = order[slot as usize];
                    let limit = best.map_or(f32::INFINITY, |b| b.t);
                    if let Some(t) =
                        intersect_triangle(origin, dir, &triangles[triangle as usize], 0.0, limit)
                    {
                        best = Some(CpuHit { t, triangle });
                    }
                }
            }
        }
    }
    best
}

/// Widens each box's exit distance by the rounding error its computation can carry (Ize 2013,
/// "Robust BVH Ray Traversal": 1 + 2γ₃), so that a ray through a tiny box — a dense cluster of
/// small triangles — is never culled by rounding while it hits the triangle inside.
pub const SLAB_FAR_SCALE: f32 =
    1.0 + 2.0 * (3.0 * f32::EPSILON / 2.0) / (1.0 - 3.0 * f32::EPSILON / 2.0);

fn slab(origin: Vec3, inv_dir: Vec3, lo: Vec3, hi: Vec3, t_max: f32) -> bool {
    let t0 = (lo - origin) * inv_dir;
    let t1 = (hi - origin) * inv_dir;
    let near = t0.min(t1).max_element().max(0.0);
    let far = t0.max(t1).min_element() * SLAB_FAR_SCALE;
    near <= far.min(t_max)
}
