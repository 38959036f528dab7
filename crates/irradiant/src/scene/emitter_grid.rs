//! The emitter grid: the light structure by which every ray picks an emitter in proportion to
//! what it can send to the place it is picked from, not to its power alone.
//!
//! The emissive triangles are split into up to [`MAX_CLUSTERS`] clusters of neighbours facing
//! alike (median splits along the widest axis of position and normal, so clusters are compact
//! and of equal count). A grid of cells over the scene keeps, per cell, an alias table over
//! the clusters, each weighted by the sum over its members of power × the best cosine the
//! triangle can have towards the cell / the squared gap between the triangle's box and the
//! cell's (past [`MEMBER_EVALUATIONS`], by the cluster's bounds and normal cone instead, after
//! Conty Estevez and Kulla 2018); a pick then takes a triangle within its cluster by power,
//! through a second alias table. Two table reads a pick, where a light tree's walk took ten levels of
//! two children each (docs/notes/light-quality.md); the pdf of any emitter at any point is one
//! more read, which the path tracer's MIS weights need.
//!
//! Every cluster keeps at least [`POWER_FLOOR`] of its power share in every cell, so that
//! every emitter stays reachable from everywhere and the estimators stay unbiased whatever
//! the cell's bounds miss (walls between a cell and a cluster, which the grid cannot see, are
//! left to the resampling's target function and shadow rays).
//!
//! Everything lives in one `rgba32uint` texture (`emitter_grid`, beside the scene's buffers,
//! whose count is at the adapter's limit in DDGI's passes): row c < cells holds cell c's table,
//! one texel a cluster (keep chance, alias, both clusters' probabilities); the rows from
//! `member_row` hold the clusters' members in cluster order, one texel a member (emitter,
//! alias emitter, keep chance). Cluster k holds members ⌊k·n/K⌋ to ⌊(k+1)·n/K⌋.

use glam::{UVec3, Vec3};
use rayon::prelude::*;

use super::emitter_alias;
use super::types::GpuEmitter;

/// Clusters at most: a cell's table is one texture row of this many texels.
pub const MAX_CLUSTERS: usize = 64;
/// Cells at most, when the adapter's textures allow (each a row of `MAX_CLUSTERS` texels:
/// 4 MiB in all). At 4 096, Sibenik's cells are 1.4 m and a 165 m city's about 5 m.
pub const MAX_CELLS: u32 = 4096;
/// The share of every cell's picks spread over the clusters by power alone: what keeps an
/// emitter the bounds rate at nothing still reachable. More wastes candidates on far emitters;
/// less trusts the bounds more.
pub const POWER_FLOOR: f32 = 0.05;

/// Cells × emitters up to which a cell weighs each cluster by its members one by one (the sum
/// of what each sends the cell); past it, by the cluster's bounds alone. 16 M evaluations take
/// about 60 ms on one core (1 000 emitters × 4 096 cells about 15 ms), spread over every core
/// (rayon).
pub const MEMBER_EVALUATIONS: usize = 1 << 24;

/// The grid's shape on the GPU, as `GpuSceneInfo` carries it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GridShape {
    /// The grid's low corner.
    pub min: Vec3,
    /// Cells per unit of length along each axis.
    pub inverse_cell: Vec3,
    /// Cells along each axis.
    pub dims: UVec3,
    /// Clusters: texels of a cell's row.
    pub clusters: u32,
    /// The texture's first member row (the cell count).
    pub member_row: u32,
}

/// The texture's size for a scene with room for `emitter_capacity` emitters on an adapter
/// whose 2D textures are at most `max_dimension` texels a side: (width, height, cell budget).
/// A scene without emitters gets one texel (nothing reads it); the grid switched off
/// (`enabled` false) one cell.
pub fn texture_size(emitter_capacity: usize, max_dimension: u32, enabled: bool) -> (u32, u32, u32) {
    if emitter_capacity == 0 {
        return (1, 1, 1);
    }
    let cells = if enabled {
        MAX_CELLS.min(max_dimension / 2).max(1)
    } else {
        1
    };
    let rows_left = (max_dimension - cells).max(1) as usize;
    // A power of two, so that a pick finds a member's texel by a mask and a shift.
    let width = emitter_capacity
        .div_ceil(rows_left)
        .max(MAX_CLUSTERS)
        .next_power_of_two() as u32;
    let member_rows = emitter_capacity.div_ceil(width as usize) as u32;
    (width, cells + member_rows, cells)
}

/// One cluster: its members' bounds, power and normal cone.
struct Cluster {
    lo: Vec3,
    hi: Vec3,
    power: f32,
    axis: Vec3,
    /// Half-angle of the cone holding every member's normal.
    spread: f32,
}

impl Cluster {
    fn of(members: &[u32], emitters: &[GpuEmitter], powers: &[f32]) -> Self {
        let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
        let (mut power, mut axis) = (0.0, Vec3::ZERO);
        for &m in members {
            let e = &emitters[m as usize];
            let v0 = Vec3::from(e.v0);
            for p in [v0, v0 + Vec3::from(e.e1), v0 + Vec3::from(e.e2)] {
                lo = lo.min(p);
                hi = hi.max(p);
            }
            power += powers[m as usize];
            axis += Vec3::from(e.normal) * powers[m as usize].max(1e-30);
        }
        let axis = axis.normalize_or_zero();
        let spread = if axis == Vec3::ZERO {
            std::f32::consts::PI
        } else {
            members
                .iter()
                .map(|&m| {
                    let normal = Vec3::from(emitters[m as usize].normal);
                    normal.dot(axis).clamp(-1.0, 1.0).acos()
                })
                .fold(0.0, f32::max)
        };
        Self {
            lo,
            hi,
            power,
            axis,
            spread,
        }
    }

    /// What the cluster can send to the cell `lo..hi`, from its bounds alone (scenes of more
    /// emitters than `MEMBER_EVALUATIONS` allows): power × the best cosine any member can
    /// have towards the cell / the squared gap between the two boxes (plus a third of the
    /// cell's squared half-diagonal, so that clusters in or touching the cell weigh alike).
    /// The gap, not the distance between centres: a long cluster (a row of windows) must not
    /// look far from a cell beside one of its members, or the points there pick that member
    /// too rarely and its light arrives as fireflies (the stained-glass Sibenik).
    fn importance(&self, (lo, hi): (Vec3, Vec3)) -> f32 {
        let radius = 0.5 * (hi - lo).length();
        let own_radius = 0.5 * (self.hi - self.lo).length();
        let to_cell = 0.5 * (lo + hi) - 0.5 * (self.lo + self.hi);
        let distance = to_cell.length();
        let facing = if self.spread >= std::f32::consts::PI || distance <= 1e-6 {
            1.0
        } else {
            let subtended = ((radius + own_radius) / distance).min(1.0).asin();
            best_cosine(to_cell / distance, self.axis, self.spread + subtended)
        };
        self.power * facing / squared_gap((self.lo, self.hi), (lo, hi))
    }
}

/// The largest cosine between `axis` and any direction within `widening` of `direction` (both
/// unit), 0 past a right angle: how well an emitter facing `axis` can face a cell seen along
/// `direction` from it, the cell and the emitter's extent widening that direction to a cone.
fn best_cosine(direction: Vec3, axis: Vec3, widening: f32) -> f32 {
    let angle = direction.dot(axis).clamp(-1.0, 1.0).acos();
    let least = (angle - widening).max(0.0);
    if least >= std::f32::consts::FRAC_PI_2 {
        0.0
    } else {
        least.cos()
    }
}

/// The squared gap between an emitter's box and a cell's, plus a third of the cell's squared
/// half-diagonal (so that emitters in or touching the cell weigh alike): the d² of a cell's
/// importance, kept from 0.
fn squared_gap((own_lo, own_hi): (Vec3, Vec3), (lo, hi): (Vec3, Vec3)) -> f32 {
    let radius = 0.5 * (hi - lo).length();
    let gap = (own_lo - hi).max(lo - own_hi).max(Vec3::ZERO);
    (gap.length_squared() + radius * radius / 3.0).max(1e-12)
}

/// One emitter as a cell weighs it: its bounds, centroid, unit normal and power.
struct Member {
    lo: Vec3,
    hi: Vec3,
    centroid: Vec3,
    normal: Vec3,
    power: f32,
}

impl Member {
    /// What the emitter can send to the cell `lo..hi`: power × the best cosine it can have
    /// towards the cell / the squared gap between the triangle's box and the cell's (plus a
    /// third of the cell's squared half-diagonal). The gap, not the distance to the cell's
    /// centre: a window pane at the edge of a cell lights the sill beside it at a tenth of a
    /// metre, and a weight taken at the centre picked it so rarely there that its light
    /// arrived as fireflies (the stained-glass Sibenik's final gather: relative MSE 0.020
    /// against 0.003).
    fn importance(&self, (lo, hi): (Vec3, Vec3)) -> f32 {
        let radius = 0.5 * (hi - lo).length();
        let to_cell = 0.5 * (lo + hi) - self.centroid;
        let distance = to_cell.length();
        // Directions from any point of the triangle to any of the cell lie within the angle
        // the two bounding spheres subtend. The cell's alone rated a large glowing wall beside
        // the cell as facing away, and DDGI read the glowing box 23 % bright.
        let spread = radius + 0.5 * (self.hi - self.lo).length();
        let facing = if distance <= spread {
            1.0
        } else {
            best_cosine(to_cell / distance, self.normal, (spread / distance).asin())
        };
        self.power * facing / squared_gap((self.lo, self.hi), (lo, hi))
    }
}

/// The grid built for one pose: its shape and the texture's texels.
pub struct EmitterGrid {
    /// Where the cells lie.
    pub shape: GridShape,
    /// The texture's texels, row by row, `width` a row (only the rows in use).
    pub texels: Vec<[u32; 4]>,
    /// Texels a row.
    pub width: u32,
}

/// Cells along each axis for a box of extent `extent`, as near cubic as the budget allows.
fn grid_dims(extent: Vec3, cell_budget: u32) -> UVec3 {
    let floor = extent.max_element().max(1e-3) / 64.0;
    let extent = extent.max(Vec3::splat(floor));
    let edge = (extent.x * extent.y * extent.z / cell_budget as f32).cbrt();
    let mut dims = (extent / edge).floor().as_uvec3().max(UVec3::ONE);
    while dims.x * dims.y * dims.z > cell_budget {
        let widest = if dims.x >= dims.y && dims.x >= dims.z {
            0
        } else if dims.y >= dims.z {
            1
        } else {
            2
        };
        dims[widest] -= 1;
    }
    dims
}

/// Splits `members` (emitter indices) into the clusters `first..last` of `n` members in all,
/// by median splits along the widest of six axes: the centroids' three and the normals' three,
/// the normals' scaled by half the members' diagonal, so that emitters facing opposite ways
/// (a ceiling's tiles and a floor's) part before neighbours do and each cluster's normal cone
/// stays narrow; cluster k gets the members ⌊k·n/K⌋ to ⌊(k+1)·n/K⌋ of the reordered list.
fn split(
    members: &mut [u32],
    keys: &[[Vec3; 2]],
    (first, last): (usize, usize),
    n: usize,
    clusters: usize,
) {
    if last - first <= 1 {
        return;
    }
    let middle = (first + last) / 2;
    let start = first * n / clusters;
    let boundary = middle * n / clusters - start;
    let mut lo = [Vec3::splat(f32::MAX); 2];
    let mut hi = [Vec3::splat(f32::MIN); 2];
    for &m in members.iter() {
        for (kind, key) in keys[m as usize].iter().enumerate() {
            lo[kind] = lo[kind].min(*key);
            hi[kind] = hi[kind].max(*key);
        }
    }
    let spatial = hi[0] - lo[0];
    let facing = (hi[1] - lo[1]) * 0.5 * spatial.length();
    let (kind, axis) = if facing.max_element() > spatial.max_element() {
        (1, facing.max_position())
    } else {
        (0, spatial.max_position())
    };
    if boundary > 0 && boundary < members.len() {
        members.select_nth_unstable_by(boundary, |&a, &b| {
            keys[a as usize][kind][axis].total_cmp(&keys[b as usize][kind][axis])
        });
    }
    let (left, right) = members.split_at_mut(boundary);
    split(left, keys, (first, middle), n, clusters);
    split(right, keys, (middle, last), n, clusters);
}

impl EmitterGrid {
    /// Builds the grid over `bounds` (the scene's, emitters included) for `emitters` of
    /// `powers` (luminance × area), and sets each emitter's cluster and its area pdf within it.
    /// Past `member_evaluations` cells × emitters, cells weigh clusters by their bounds
    /// ([`MEMBER_EVALUATIONS`] but in tests). A power that is not finite counts as none.
    pub fn build(
        emitters: &mut [GpuEmitter],
        powers: &[f32],
        bounds: (Vec3, Vec3),
        (width, cell_budget): (u32, u32),
        member_evaluations: usize,
    ) -> Self {
        let powers: Vec<f32> = powers
            .iter()
            .map(|&p| if p.is_finite() { p.max(0.0) } else { 0.0 })
            .collect();
        let powers = powers.as_slice();
        let n = emitters.len();
        let clusters = n.min(MAX_CLUSTERS);
        if n == 0 {
            return Self {
                shape: GridShape::default(),
                texels: vec![[0; 4]],
                width,
            };
        }
        let keys: Vec<[Vec3; 2]> = emitters
            .iter()
            .map(|e| {
                let centroid = Vec3::from(e.v0) + (Vec3::from(e.e1) + Vec3::from(e.e2)) / 3.0;
                [centroid, Vec3::from(e.normal)]
            })
            .collect();
        let mut order: Vec<u32> = (0..n as u32).collect();
        split(&mut order, &keys, (0, clusters), n, clusters);
        let range = |k: usize| k * n / clusters..(k + 1) * n / clusters;
        let groups: Vec<Cluster> = (0..clusters)
            .map(|k| Cluster::of(&order[range(k)], emitters, powers))
            .collect();

        let mut member_texels = vec![[0u32; 4]; n];
        for (k, group) in groups.iter().enumerate() {
            let members = &order[range(k)];
            let weights: Vec<f32> = members.iter().map(|&m| powers[m as usize]).collect();
            for (slot, (&m, (keep, alias))) in members
                .iter()
                .zip(emitter_alias::table(&weights))
                .enumerate()
            {
                member_texels[range(k).start + slot] =
                    [m, members[alias as usize], keep.to_bits(), 0];
                let e = &mut emitters[m as usize];
                e.cluster = k as u32;
                // A point's area pdf given its cluster: luminance / the cluster's power.
                e.pdf_area = super::build::luminance(e.radiance.into()) / group.power.max(1e-30);
            }
        }

        let (lo, hi) = bounds;
        let dims = grid_dims(hi - lo, cell_budget);
        let cell = (hi - lo).max(Vec3::splat(1e-6)) / dims.as_vec3();
        let total_power: f32 = groups.iter().map(|g| g.power).sum();
        let cells = dims.x * dims.y * dims.z;
        let by_member = cells as usize * n <= member_evaluations;
        let members: Vec<(Member, usize)> = (0..clusters)
            .flat_map(|k| order[range(k)].iter().map(move |&m| (m, k)))
            .map(|(m, k)| {
                let e = &emitters[m as usize];
                let v0 = Vec3::from(e.v0);
                let corners = [v0, v0 + Vec3::from(e.e1), v0 + Vec3::from(e.e2)];
                let member = Member {
                    lo: corners[0].min(corners[1]).min(corners[2]),
                    hi: corners[0].max(corners[1]).max(corners[2]),
                    centroid: keys[m as usize][0],
                    normal: Vec3::from(e.normal),
                    power: powers[m as usize],
                };
                (member, k)
            })
            .collect();
        let tables: Vec<Vec<f32>> = (0..cells)
            .into_par_iter()
            .map(|c| {
                let index = UVec3::new(c % dims.x, (c / dims.x) % dims.y, c / (dims.x * dims.y));
                let cell_lo = lo + index.as_vec3() * cell;
                if !by_member {
                    return groups
                        .iter()
                        .map(|g| g.importance((cell_lo, cell_lo + cell)))
                        .collect();
                }
                let mut importance = vec![0.0f32; clusters];
                for (member, k) in &members {
                    importance[*k] += member.importance((cell_lo, cell_lo + cell));
                }
                importance
            })
            .collect();
        let mut texels = vec![[0u32; 4]; (cells * width) as usize];
        for (c, mut importance) in (0..cells).zip(tables) {
            // A weight that is not finite (an emitter of absurd size) counts as none: the power
            // floor still reaches its cluster.
            for i in &mut importance {
                if !i.is_finite() {
                    *i = 0.0;
                }
            }
            let sum: f32 = importance.iter().sum();
            // One cell is the grid switched off (GpuSceneSettings::emitter_grid): power alone.
            let by_importance = sum > 0.0 && sum.is_finite() && cells > 1;
            let probabilities: Vec<f32> = groups
                .iter()
                .zip(&importance)
                .map(|(g, &i)| {
                    let by_power = g.power / total_power.max(1e-30);
                    if by_importance {
                        (1.0 - POWER_FLOOR) * i / sum + POWER_FLOOR * by_power
                    } else {
                        by_power
                    }
                })
                .collect();
            let row = (c * width) as usize;
            for (j, (keep, alias)) in emitter_alias::table(&probabilities).into_iter().enumerate() {
                texels[row + j] = [
                    keep.to_bits(),
                    alias,
                    probabilities[j].to_bits(),
                    probabilities[alias as usize].to_bits(),
                ];
            }
        }
        // The members after the cells, `width` a row.
        texels.extend(member_texels);
        texels.resize(texels.len().next_multiple_of(width as usize), [0; 4]);
        Self {
            shape: GridShape {
                min: lo,
                inverse_cell: cell.recip(),
                dims,
                clusters: clusters as u32,
                member_row: cells,
            },
            texels,
            width,
        }
    }

    /// The cell holding `p`, clamped to the grid (`emitter_cell` in shaders/scene.wgsl): the
    /// oracle's; the GPU alone looks cells up at run time.
    #[cfg(test)]
    fn cell(&self, p: Vec3) -> u32 {
        let s = &self.shape;
        let max = (s.dims.as_ivec3() - 1).max(glam::IVec3::ZERO);
        let c = ((p - s.min) * s.inverse_cell)
            .floor()
            .as_ivec3()
            .clamp(glam::IVec3::ZERO, max)
            .as_uvec3();
        c.x + s.dims.x * (c.y + s.dims.y * c.z)
    }

    #[cfg(test)]
    fn texel(&self, x: u32, y: u32) -> [u32; 4] {
        self.texels[(y * self.width + x) as usize]
    }
}

#[cfg(test)]
mod tests;
