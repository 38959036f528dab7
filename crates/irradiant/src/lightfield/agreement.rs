//! Light-field rays against the BVH's (§4 proved on our scenes): rays leave the surfaces the
//! camera sees, in random directions away from them, and each is traced twice — through the
//! light field alone and through the BVH. A hit agrees when both hit within `tolerance` of
//! each other along the ray; a miss when both miss.

use glam::Vec3;

use super::Lightfield;
use crate::RenderError;
use crate::Session;
use crate::raycast::types::GpuRay;
use crate::raycast::{RayCaster, RayOrder};

/// How many rays agreed, and how the others failed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Agreement {
    /// Rays traced (those that met the surface they left at once are not counted).
    pub rays: u32,
    /// Both hit, within the tolerance.
    pub hits: u32,
    /// Both missed (left the scene).
    pub misses: u32,
    /// Both hit, farther apart than the tolerance.
    pub wrong_distance: u32,
    /// The light field hit where the BVH saw nothing, and the reverse.
    pub false_hits: u32,
    /// The BVH hit where the light field saw nothing.
    pub false_misses: u32,
    /// The distance tolerance, in scene units: the widest thickness a probe texel's surface is
    /// given plus the width of a map texel seen from the farthest corner of a probe cage —
    /// the light field cannot place a surface more finely than that.
    pub tolerance: f32,
    /// Mean probes a ray visited.
    pub mean_visits: f64,
}

impl Agreement {
    /// The share of rays on which the light field and the BVH agree.
    pub fn share(&self) -> f64 {
        (self.hits + self.misses) as f64 / self.rays.max(1) as f64
    }
}

/// A small deterministic generator (xorshift64*): the rays are the same on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn direction(&mut self) -> Vec3 {
        let z = 1.0 - 2.0 * self.next();
        let phi = std::f32::consts::TAU * self.next();
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// Traces `count` rays from the surfaces of the session's last frame both ways. The session's
/// technique must be a light-field one.
pub fn measure(session: &Session, count: u32, seed: u64) -> Result<Agreement, RenderError> {
    let lightfield = session.technique_as::<Lightfield>().ok_or_else(|| {
        RenderError::Settings("the agreement test needs a light-field technique".into())
    })?;
    let ctx = session.ctx();
    let params = lightfield.params(0);
    let surfaces: Vec<Vec3> = session
        .gbuffer()?
        .iter()
        .filter(|s| s.depth >= 0.0)
        .map(|s| Vec3::from(s.position))
        .collect();
    if surfaces.is_empty() {
        return Err(RenderError::Settings(
            "the camera sees no surface to start rays from".into(),
        ));
    }
    let camera = session.camera().position;
    let offset = 2.0 * params.min_thickness;
    let far = 4.0 * params.max_distance;
    let mut rng = Rng(seed.max(1));
    let rays: Vec<GpuRay> = (0..count)
        .map(|_| {
            let p =
                surfaces[((rng.next() * surfaces.len() as f32) as usize).min(surfaces.len() - 1)];
            let towards_camera = (camera - p).normalize_or(Vec3::Y);
            let mut d = rng.direction();
            if d.dot(towards_camera) < 0.0 {
                d = -d;
            }
            GpuRay {
                origin: (p + towards_camera * offset).to_array(),
                t_max: far,
                dir: d.to_array(),
                stop: 0.0,
            }
        })
        .collect();
    let bvh = RayCaster::new(ctx, session.gpu_scene())?.trace(
        ctx,
        session.gpu_scene(),
        &rays,
        false,
        RayOrder::Incoherent,
    )?;
    let lf = lightfield.trace_rays(ctx, session.gpu_scene(), session.frame(), &rays)?;
    let grid = lightfield.grid();
    let texel_angle =
        (4.0 * std::f32::consts::PI).sqrt() / lightfield.settings().bake.resolution as f32;
    let tolerance = params.max_thickness + grid.spacing.length() * texel_angle;
    let mut a = Agreement {
        tolerance,
        ..Default::default()
    };
    let mut visits = 0u64;
    for (b, l) in bvh.iter().zip(&lf) {
        // A direction into the surface the ray left meets it at once: not a light-field ray.
        if b.t >= 0.0 && b.t < 4.0 * offset {
            continue;
        }
        a.rays += 1;
        visits += l.visits as u64;
        let lf_hit = l.result == super::constants::LF_HIT;
        match (b.t >= 0.0, lf_hit) {
            (true, true) if (b.t - l.t).abs() <= tolerance => a.hits += 1,
            (true, true) => a.wrong_distance += 1,
            (false, false) => a.misses += 1,
            (false, true) => a.false_hits += 1,
            (true, false) => a.false_misses += 1,
        }
    }
    a.mean_visits = visits as f64 / a.rays.max(1) as f64;
    Ok(a)
}
