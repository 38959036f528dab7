//! Probe ray sets: spherical Fibonacci directions (optionally ordered into compact patches for
//! GPU coherence) and the per-frame random rotation that makes probes see every direction over
//! time.

use glam::{Quat, Vec3};

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

/// A uniformly random rotation for frame `frame` (Shoemake's method from three hashed numbers).
pub fn random_rotation(seed: u32, frame: u32) -> Quat {
    let hash = |mut x: u32| {
        x ^= x >> 16;
        x = x.wrapping_mul(0x7feb352d);
        x ^= x >> 15;
        x = x.wrapping_mul(0x846ca68b);
        x ^= x >> 16;
        x
    };
    let base = hash(seed.wrapping_mul(0x9e3779b9) ^ hash(frame));
    let u = [hash(base), hash(base ^ 0x68e31da4), hash(base ^ 0xb5297a4d)]
        .map(|v| (v >> 8) as f32 / 16_777_216.0);
    let (a, b) = ((1.0 - u[0]).sqrt(), u[0].sqrt());
    let (t1, t2) = (std::f32::consts::TAU * u[1], std::f32::consts::TAU * u[2]);
    Quat::from_xyzw(a * t1.sin(), a * t1.cos(), b * t2.sin(), b * t2.cos()).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

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
