//! CPU twins of `shaders/octahedral.wgsl` and of the atlas border mapping of
//! `ddgi/volume.wgsl` (border_source), used by tests as oracles.

use glam::{UVec2, Vec2, Vec3};

fn sign_not_zero(v: Vec2) -> Vec2 {
    Vec2::new(
        if v.x >= 0.0 { 1.0 } else { -1.0 },
        if v.y >= 0.0 { 1.0 } else { -1.0 },
    )
}

pub fn oct_encode(n: Vec3) -> Vec2 {
    let p = Vec2::new(n.x, n.y) / (n.x.abs() + n.y.abs() + n.z.abs());
    if n.z < 0.0 {
        (Vec2::ONE - Vec2::new(p.y, p.x).abs()) * sign_not_zero(p)
    } else {
        p
    }
}

pub fn oct_decode(p: Vec2) -> Vec3 {
    let mut n = Vec3::new(p.x, p.y, 1.0 - p.x.abs() - p.y.abs());
    if n.z < 0.0 {
        let xy = (Vec2::ONE - Vec2::new(n.y, n.x).abs()) * sign_not_zero(Vec2::new(n.x, n.y));
        n = Vec3::new(xy.x, xy.y, n.z);
    }
    n.normalize()
}

/// The direction an interior texel (i, j) of a `texels`-wide tile stands for.
pub fn texel_direction(texel: UVec2, texels: u32) -> Vec3 {
    oct_decode((texel.as_vec2() + 0.5) / texels as f32 * 2.0 - 1.0)
}

/// The tile texel (border included, so interior texels are 1…texels) that border texel (x, y)
/// copies.
pub fn border_source(x: u32, y: u32, texels: u32) -> UVec2 {
    let last = texels + 1;
    let corner = |c: u32| if c == 0 { texels } else { 1 };
    if (x == 0 || x == last) && (y == 0 || y == last) {
        return UVec2::new(corner(x), corner(y));
    }
    if y == 0 || y == last {
        return UVec2::new(last - x, if y == 0 { 1 } else { texels });
    }
    UVec2::new(if x == 0 { 1 } else { texels }, last - y)
}

/// Spherical Fibonacci point i of n.
pub fn spherical_fibonacci(i: u32, n: u32) -> Vec3 {
    let phi = std::f32::consts::TAU * (i as f32 * 0.618_034).fract();
    let cos_theta = 1.0 - (2.0 * i as f32 + 1.0) / n as f32;
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    Vec3::new(phi.cos() * sin_theta, phi.sin() * sin_theta, cos_theta)
}

/// The probe ray set before this frame's rotation: n spherical Fibonacci directions. With
/// `coherent`, they are ordered so that every aligned run of 2^k rays is a compact patch of
/// the sphere (a GPU warp traces 32 side by side, and rays into one patch walk the same part
/// of the BVH): the set is split at the median of its widest axis, and each half again, down
/// to single rays. The set itself is unchanged, and the rotation keeps patches compact.
pub fn probe_ray_set(n: u32, coherent: bool) -> Vec<Vec3> {
    let mut rays: Vec<Vec3> = (0..n).map(|i| spherical_fibonacci(i, n)).collect();
    if coherent {
        median_split(&mut rays);
    }
    rays
}

fn median_split(rays: &mut [Vec3]) {
    if rays.len() <= 1 {
        return;
    }
    let (lo, hi) = rays
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(*d), hi.max(*d))
        });
    let extent = hi - lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    // Halves of power-of-two size first, so that warp-sized runs stay aligned.
    let half = rays.len().next_power_of_two() / 2;
    rays.sort_by(|a, b| a[axis].total_cmp(&b[axis]));
    let (left, right) = rays.split_at_mut(half);
    median_split(left);
    median_split(right);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encode_decode_round_trips_over_the_sphere() {
        for i in 0..2000 {
            let d = spherical_fibonacci(i, 2000);
            let back = oct_decode(oct_encode(d));
            assert!((back - d).length() < 1e-5, "{d} → {back}");
            let p = oct_encode(d);
            assert!(p.x.abs() <= 1.0 && p.y.abs() <= 1.0);
        }
    }

    /// A border texel stands for the point just beyond the map's edge, which the octahedral
    /// fold maps back inside: its source texel must stand for (almost) the same direction.
    #[test]
    fn border_texels_continue_the_sphere_across_the_edges() {
        for texels in [6u32, 14] {
            let t = texels as f32;
            for y in 0..texels + 2 {
                for x in 0..texels + 2 {
                    if x != 0 && y != 0 && x != texels + 1 && y != texels + 1 {
                        continue;
                    }
                    let source = border_source(x, y, texels);
                    assert!((1..=texels).contains(&source.x) && (1..=texels).contains(&source.y));
                    // The border texel's own (out-of-range) position, folded back onto the map.
                    let p = (Vec2::new(x as f32, y as f32) - 1.0 + 0.5) / t * 2.0 - 1.0;
                    let mut q = p;
                    if q.x.abs() > 1.0 {
                        q = Vec2::new(q.x.signum() * 2.0 - q.x, -q.y);
                    }
                    if q.y.abs() > 1.0 {
                        q = Vec2::new(-q.x, q.y.signum() * 2.0 - q.y);
                    }
                    let expected = oct_decode(q);
                    let got = texel_direction(source - 1, texels);
                    assert!(
                        (expected - got).length() < 1e-4,
                        "texels {texels}, border ({x}, {y}) → {source}: {expected} vs {got}"
                    );
                }
            }
        }
    }

    #[test]
    fn coherent_ray_set_is_the_same_set_in_compact_runs() {
        let n = 256;
        let plain = probe_ray_set(n, false);
        let coherent = probe_ray_set(n, true);
        let key = |v: &Vec3| (v.x.to_bits(), v.y.to_bits(), v.z.to_bits());
        let mut a: Vec<_> = plain.iter().map(key).collect();
        let mut b: Vec<_> = coherent.iter().map(key).collect();
        a.sort();
        b.sort();
        assert_eq!(a, b, "sorting must not change the directions");
        // Widest angle between two rays of a warp-sized run, averaged over runs.
        let spread = |rays: &[Vec3]| {
            let runs = rays.chunks(32);
            let count = runs.len() as f32;
            rays.chunks(32)
                .map(|run| {
                    let mut min_dot = 1.0f32;
                    for p in run {
                        for q in run {
                            min_dot = min_dot.min(p.dot(*q));
                        }
                    }
                    min_dot.acos().to_degrees()
                })
                .sum::<f32>()
                / count
        };
        let (plain_spread, coherent_spread) = (spread(&plain), spread(&coherent));
        // Fibonacci order runs round a latitude band (about 180° across); a 32-ray patch,
        // an eighth of the sphere, is about 90° across.
        // Fibonacci order runs round latitude bands: rings up to 180° across (129° on
        // average, measured). An eighth of the sphere is a cap about 83° across.
        assert!(plain_spread > 120.0, "plain runs span {plain_spread}°");
        assert!(
            coherent_spread < 90.0,
            "coherent runs span {coherent_spread}°"
        );
        // Any count works, not only powers of two.
        assert_eq!(probe_ray_set(100, true).len(), 100);
    }

    #[test]
    fn fibonacci_directions_cover_the_sphere_evenly() {
        let n = 256;
        let dirs: Vec<Vec3> = (0..n).map(|i| spherical_fibonacci(i, n)).collect();
        let mean = dirs.iter().sum::<Vec3>() / n as f32;
        assert!(mean.length() < 0.01, "mean {mean}");
        // Every direction of a fine test set has a ray within 15°.
        for i in 0..1000 {
            let probe = spherical_fibonacci(i, 1000);
            let best = dirs.iter().map(|d| d.dot(probe)).fold(-1.0f32, f32::max);
            assert!(
                best > 15f32.to_radians().cos(),
                "a hole in the ray set near {probe}"
            );
        }
    }
}
