//! The emitter grid's CPU oracle: what the GPU's pick (`pick_emitter` in shaders/scene.wgsl)
//! does, decoded from the texels alone, against the pdf the shaders weigh samples by.

use glam::Vec3;

use super::*;

/// Each emitter's chance of being picked at `p`, summed exactly over both alias tables the way
/// the shader reads them.
fn pick_probabilities(grid: &EmitterGrid, n: usize, p: Vec3) -> Vec<f64> {
    let clusters = grid.shape.clusters as usize;
    let cell = grid.cell(p);
    let mut cluster_chance = vec![0.0f64; clusters];
    for j in 0..clusters {
        let [keep, alias, _, _] = grid.texel(j as u32, cell);
        let keep = f32::from_bits(keep).clamp(0.0, 1.0) as f64;
        cluster_chance[j] += keep / clusters as f64;
        cluster_chance[alias as usize] += (1.0 - keep) / clusters as f64;
    }
    let mut chance = vec![0.0f64; n];
    for (k, &pk) in cluster_chance.iter().enumerate() {
        let range = k * n / clusters..(k + 1) * n / clusters;
        let count = range.len() as f64;
        for slot in range {
            let slot = slot as u32;
            let [emitter, alias, keep, _] =
                grid.texel(slot % grid.width, grid.shape.member_row + slot / grid.width);
            let keep = f32::from_bits(keep).clamp(0.0, 1.0) as f64;
            chance[emitter as usize] += pk * keep / count;
            chance[alias as usize] += pk * (1.0 - keep) / count;
        }
    }
    chance
}

/// The area pdf the shaders give emitter `index`'s points at `p` (`emitter_area_pdf`): the
/// cell's probability of its cluster × its area pdf within the cluster.
fn area_pdf(grid: &EmitterGrid, emitters: &[GpuEmitter], p: Vec3, index: usize) -> f64 {
    let e = &emitters[index];
    let [_, _, cluster_probability, _] = grid.texel(e.cluster, grid.cell(p));
    f32::from_bits(cluster_probability) as f64 * e.pdf_area as f64
}

fn area(e: &GpuEmitter) -> f32 {
    0.5 * Vec3::from(e.e1).cross(Vec3::from(e.e2)).length()
}

/// A square tile of side `side` at `centre` facing `normal` (±y), as two triangles.
fn tile(centre: Vec3, side: f32, facing_down: bool, radiance: Vec3) -> [GpuEmitter; 2] {
    let h = side / 2.0;
    let corner = |dx: f32, dz: f32| centre + Vec3::new(dx * h, 0.0, dz * h);
    let (a, b, c, d) = (
        corner(-1., -1.),
        corner(1., -1.),
        corner(1., 1.),
        corner(-1., 1.),
    );
    let normal = if facing_down { -Vec3::Y } else { Vec3::Y };
    let triangle = |p: Vec3, q: Vec3, r: Vec3| GpuEmitter {
        v0: p.into(),
        e1: (q - p).into(),
        e2: (r - p).into(),
        normal: normal.into(),
        radiance: radiance.into(),
        ..bytemuck::Zeroable::zeroed()
    };
    [triangle(a, b, c), triangle(a, c, d)]
}

/// A hall 20 × 4 × 12 m with tiles on its ceiling, of powers over three orders of magnitude,
/// and a row of twelve tiles on the ceiling facing up (away from the whole hall).
fn hall(tiles_x: usize, tiles_z: usize) -> Vec<GpuEmitter> {
    let mut random = irradiant_scene::xorshift(0x2545_f491);
    let mut emitters = Vec::new();
    for i in 0..tiles_x {
        for k in 0..tiles_z {
            let centre = Vec3::new(
                20.0 * (i as f32 + 0.5) / tiles_x as f32,
                4.0,
                12.0 * (k as f32 + 0.5) / tiles_z as f32,
            );
            let radiance = Vec3::splat(10f32.powf(3.0 * random()));
            emitters.extend(tile(centre, 0.15, true, radiance));
        }
    }
    for i in 0..12 {
        let centre = Vec3::new(1.0 + 1.5 * i as f32, 4.01, 6.0);
        emitters.extend(tile(centre, 0.15, false, Vec3::splat(5.0)));
    }
    emitters
}

/// The grid over the hall: `enabled` false is the grid switched off (one cell), and
/// `member_evaluations` 0 makes every cell weigh clusters by their bounds.
fn grid_with(emitters: &mut [GpuEmitter], enabled: bool, member_evaluations: usize) -> EmitterGrid {
    let powers: Vec<f32> = emitters
        .iter()
        .map(|e| super::super::build::luminance(e.radiance.into()) * area(e))
        .collect();
    let (width, _, cells) = texture_size(emitters.len(), 8192, enabled);
    EmitterGrid::build(
        emitters,
        &powers,
        (Vec3::ZERO, Vec3::new(20.0, 4.1, 12.0)),
        (width, cells),
        member_evaluations,
    )
}

fn grid_over(emitters: &mut [GpuEmitter]) -> EmitterGrid {
    grid_with(emitters, true, MEMBER_EVALUATIONS)
}

/// At points all over the hall the pick's probabilities sum to 1, reach every emitter, and are
/// the pdf the shaders weigh each sample by (else every estimate would be biased): cells that
/// weigh members one by one, cells that weigh clusters by their bounds, and the grid off.
#[test]
fn the_grid_picks_every_emitter_with_the_probability_the_shaders_weigh_it_by() {
    let layouts = [
        (true, MEMBER_EVALUATIONS),
        (true, 0),
        (false, MEMBER_EVALUATIONS),
    ];
    for ((tiles_x, tiles_z), (enabled, member_evaluations)) in [(12, 10), (1, 1), (5, 3), (40, 25)]
        .into_iter()
        .flat_map(|hall| layouts.map(|layout| (hall, layout)))
    {
        let mut emitters = hall(tiles_x, tiles_z);
        let grid = grid_with(&mut emitters, enabled, member_evaluations);
        let n = emitters.len();
        let power = |e: &GpuEmitter| {
            super::super::build::luminance(e.radiance.into()) as f64 * area(e) as f64
        };
        let total: f64 = emitters.iter().map(power).sum();
        for x in 0..9 {
            for z in 0..5 {
                let p = Vec3::new(
                    0.1 + 2.45 * x as f32,
                    0.3 + 0.8 * (x % 4) as f32,
                    0.2 + 2.9 * z as f32,
                );
                let chance = pick_probabilities(&grid, n, p);
                let sum: f64 = chance.iter().sum();
                assert!(
                    (sum - 1.0).abs() < 1e-5,
                    "{n} emitters at {p}: the picks sum to {sum}"
                );
                for (i, e) in emitters.iter().enumerate() {
                    assert!(
                        chance[i] > 0.0,
                        "{n} emitters at {p}: emitter {i} is never picked"
                    );
                    let pdf = area_pdf(&grid, &emitters, p, i) * area(e) as f64;
                    assert!(
                        (pdf - chance[i]).abs() <= 1e-4 * chance[i] + 1e-9,
                        "{n} emitters at {p}: emitter {i} picked with {} but weighed as {pdf}",
                        chance[i]
                    );
                    // Switched off, the grid is the power pick it replaced.
                    assert!(
                        enabled || (chance[i] - power(e) / total).abs() <= 1e-4 * chance[i],
                        "{n} emitters, grid off: emitter {i} picked with {} against its power's share {}",
                        chance[i],
                        power(e) / total
                    );
                }
            }
        }
    }
}

/// Near emitters win over far ones of the same power, and those facing away from the whole hall
/// keep little more than the power floor's share.
#[test]
fn the_grid_favours_near_emitters_facing_the_point() {
    let mut emitters = hall(12, 10);
    let radiance = Vec3::splat(50.0);
    for e in &mut emitters {
        e.radiance = radiance.into();
    }
    let grid = grid_over(&mut emitters);
    let n = emitters.len();
    let near_corner = Vec3::new(0.5, 0.5, 0.5);
    let chance = pick_probabilities(&grid, n, near_corner);
    let centre = |e: &GpuEmitter| Vec3::from(e.v0) + (Vec3::from(e.e1) + Vec3::from(e.e2)) / 3.0;
    let share_within = |radius: f32| -> f64 {
        emitters
            .iter()
            .zip(&chance)
            .filter(|(e, _)| (centre(e) - near_corner).length() < radius)
            .map(|(_, &c)| c)
            .sum()
    };
    // By power alone every tile would have the same chance: 1 in 120.
    let near = share_within(4.5);
    let near_count = emitters
        .iter()
        .filter(|e| (centre(e) - near_corner).length() < 4.5)
        .count();
    let by_power = near_count as f64 / n as f64;
    assert!(
        near > 5.0 * by_power,
        "the {near_count} tiles within 4.5 m get {near} of the picks; by power alone {by_power}"
    );
    let far = Vec3::new(19.5, 0.5, 11.5);
    let far_share: f64 = emitters
        .iter()
        .zip(&chance)
        .filter(|(e, _)| (centre(e) - far).length() < 4.5)
        .map(|(_, &c)| c)
        .sum();
    assert!(
        near > 20.0 * far_share,
        "near {near}, far corner {far_share}"
    );
    // The tiles facing up: the last 24 triangles, of the same power as every other. Clusters
    // are of equal count, so one may mix them with tiles facing down.
    let away: f64 = chance[n - 24..].iter().sum();
    let by_power = 24.0 / n as f64;
    assert!(
        away <= 0.25 * by_power,
        "the tiles facing away get {away} of the picks; by power alone {by_power}"
    );
}

/// Room for any emitter count within the adapter's largest texture side, and one texel for a
/// scene without emitters.
#[test]
fn the_grid_texture_fits_the_adapter() {
    assert_eq!(texture_size(0, 8192, true), (1, 1, 1));
    assert_eq!(texture_size(960, 8192, false).2, 1);
    for (capacity, side) in [
        (1, 8192),
        (960, 8192),
        (300_000, 8192),
        (5_000_000, 16_384),
        (10, 2048),
    ] {
        let (width, height, cells) = texture_size(capacity, side, true);
        assert!(
            width <= side && height <= side,
            "{capacity} emitters: {width}×{height}"
        );
        assert!((width * (height - cells)) as usize >= capacity);
        assert!(width as usize >= MAX_CLUSTERS && cells <= MAX_CELLS);
        // pick_emitter finds a member's texel by a mask and a shift.
        assert!(width.is_power_of_two(), "{capacity} emitters: {width} wide");
    }
    let dims = grid_dims(Vec3::new(165.0, 0.0, 165.0), MAX_CELLS);
    assert!(
        dims.x * dims.y * dims.z <= MAX_CELLS && dims.x >= 32,
        "{dims}"
    );
}

/// pick_emitter finds cluster k's first member, ⌊k·n/K⌋, as k·⌊n/K⌋ + ⌊k·r/K⌋ (r = n mod K)
/// with the last quotient in floats: (k·r + ½) × (1/K), truncated. Exact for every cluster
/// count, remainder and cluster, with 1/K off by far more than a GPU's reciprocal may be.
/// (The formula's arithmetic written again in Rust: no test runs the shader's own text of it
/// against the build's ranges.)
#[test]
fn the_shaders_cluster_bounds_are_the_builds() {
    for clusters in 1..=MAX_CLUSTERS as u32 {
        for off in [1.0 - 1e-5, 1.0, 1.0 + 1e-5] {
            let step = off / clusters as f32;
            for whole in [1, 2, 15, 262_143] {
                for rest in 0..clusters {
                    let n = whole * clusters + rest;
                    for k in 0..=clusters {
                        let shader = k * whole + (((k * rest) as f32 + 0.5) * step) as u32;
                        let build = (k as u64 * n as u64 / clusters as u64) as u32;
                        assert_eq!(shader, build, "cluster {k} of {clusters}, {n} emitters");
                    }
                }
            }
        }
    }
}
