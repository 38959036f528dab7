//! Octahedral maps of the sphere (Cigolle et al. 2014), as probe atlases store directions: the
//! CPU twins of `probes/octahedral.wgsl` and of the border mapping of `probes/atlas.wgsl`,
//! used by tests as oracles and by the CPU side of the probe techniques.

use glam::{UVec2, Vec2, Vec3};

/// The WGSL of the mapping (`oct_encode`, `oct_decode`), for shaders outside the library's
/// composition (the viewer decodes the G-buffer's normals with it).
pub const OCTAHEDRAL_WGSL: &str = include_str!("octahedral.wgsl");

fn sign_not_zero(v: Vec2) -> Vec2 {
    Vec2::new(
        if v.x >= 0.0 { 1.0 } else { -1.0 },
        if v.y >= 0.0 { 1.0 } else { -1.0 },
    )
}

/// The octahedral coordinates, in [-1, 1]², of direction `n` (need not be unit length).
pub fn oct_encode(n: Vec3) -> Vec2 {
    let p = Vec2::new(n.x, n.y) / (n.x.abs() + n.y.abs() + n.z.abs());
    if n.z < 0.0 {
        (Vec2::ONE - Vec2::new(p.y, p.x).abs()) * sign_not_zero(p)
    } else {
        p
    }
}

/// The unit direction of octahedral coordinates `p` in [-1, 1]²: [`oct_encode`]'s inverse.
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::probes::rays::spherical_fibonacci;

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
}
