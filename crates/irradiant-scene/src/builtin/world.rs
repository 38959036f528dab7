//! Built-in pieces of a large world (scenes/world): a terrain and a tunnel. A manifest places
//! them with the shipped scenes (`[[place]]`).

use glam::Vec3;

use super::Builder;
use crate::model::{Camera, Light, Scene};

/// Side of the terrain, in metres.
const TERRAIN_SIDE: f32 = 480.0;
/// Quads along each side of the terrain.
const TERRAIN_QUADS: u32 = 160;
/// Inside this radius the ground is flat (y = 0), where buildings stand.
const FLAT_RADIUS: f32 = 150.0;

/// The terrain's height at (x, z): flat in the middle, rolling hills rising towards the edges.
fn terrain_height(x: f32, z: f32) -> f32 {
    let r = (x * x + z * z).sqrt();
    let rise = ((r - FLAT_RADIUS) / 60.0).clamp(0.0, 1.0);
    let hills =
        9.0 + 6.0 * (x * 0.031).sin() * (z * 0.027).cos() + 4.0 * (x * 0.011 + z * 0.017).sin();
    rise * rise * (3.0 - 2.0 * rise) * hills.max(0.0)
}

/// A 480 m square of ground: flat within 150 m of the middle, hills around it.
pub fn terrain() -> Scene {
    let mut b = Builder::new("terrain");
    let grass = b.material("grass", Vec3::new(0.28, 0.36, 0.18), Vec3::ZERO);
    let step = TERRAIN_SIDE / TERRAIN_QUADS as f32;
    let at = |i: u32, j: u32| {
        let (x, z) = (
            -0.5 * TERRAIN_SIDE + i as f32 * step,
            -0.5 * TERRAIN_SIDE + j as f32 * step,
        );
        Vec3::new(x, terrain_height(x, z), z)
    };
    for j in 0..TERRAIN_QUADS {
        for i in 0..TERRAIN_QUADS {
            // Counter-clockwise seen from above.
            b.quad(
                [at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)],
                grass,
            );
        }
    }
    let camera = Camera::looking_at(Vec3::new(-60.0, 6.0, 40.0), Vec3::new(0.0, 0.0, 0.0), 60.0);
    let mut scene = b.into_scene("terrain", camera);
    scene.sky = Vec3::new(0.5, 0.6, 0.75);
    scene
}

/// Length of the tunnel along x, and its inner width and height, in metres.
const TUNNEL: Vec3 = Vec3::new(80.0, 5.0, 6.0);

/// A tunnel 80 m long along x (from x = 0 to 80), 6 m wide and 5 m high inside, open at both
/// ends, with walls 0.5 m thick: a lamp every 16 m and a glowing strip over each lamp.
pub fn tunnel() -> Scene {
    let mut b = Builder::new("tunnel");
    let concrete = b.material("concrete", Vec3::splat(0.55), Vec3::ZERO);
    let road = b.material("road", Vec3::splat(0.25), Vec3::ZERO);
    let strip = b.material("strip-light", Vec3::splat(0.8), Vec3::new(6.0, 5.5, 4.5));
    let (length, height, half) = (TUNNEL.x, TUNNEL.y, 0.5 * TUNNEL.z);
    let t = 0.5;
    let v = Vec3::new;
    b.cuboid(v(0.0, -t, -half - t), v(length, 0.0, half + t), road);
    b.cuboid(
        v(0.0, height, -half - t),
        v(length, height + t, half + t),
        concrete,
    );
    b.cuboid(v(0.0, 0.0, -half - t), v(length, height, -half), concrete);
    b.cuboid(v(0.0, 0.0, half), v(length, height, half + t), concrete);
    let mut lights = Vec::new();
    for k in 0..5 {
        let x = 8.0 + 16.0 * k as f32;
        // A strip 2 m × 0.3 m just under the roof, facing down.
        let y = height - 0.01;
        b.quad(
            [
                v(x - 1.0, y, -0.15),
                v(x + 1.0, y, -0.15),
                v(x + 1.0, y, 0.15),
                v(x - 1.0, y, 0.15),
            ],
            strip,
        );
        lights.push(Light::point(
            &format!("lamp-{k}"),
            v(x, height - 0.6, 0.0),
            Vec3::new(1.0, 0.85, 0.6),
            25.0,
        ));
    }
    let camera = Camera::looking_at(v(-6.0, 1.7, 0.0), v(40.0, 1.7, 0.0), 60.0);
    let mut scene = b.into_scene("tunnel", camera);
    scene.lights = lights;
    scene
}

/// Small glowing tiles of `many-lights`.
const MANY_LIGHTS: u32 = 120;

/// A closed hall 20 × 4 × 12 m lit only by 120 small glowing tiles (15 cm square) on its
/// ceiling and walls, with partitions and pillars between them, so that most tiles are hidden
/// from most points: the many-emitter test of the direct light (issue 41).
pub fn many_lights() -> Scene {
    let mut b = Builder::new("many-lights");
    let plaster = b.material("plaster", Vec3::splat(0.7), Vec3::ZERO);
    let floor = b.material("floor", Vec3::new(0.5, 0.42, 0.35), Vec3::ZERO);
    let brick = b.material("brick", Vec3::new(0.6, 0.3, 0.22), Vec3::ZERO);
    let tile = b.material("tile-light", Vec3::splat(0.8), Vec3::new(40.0, 34.0, 26.0));
    let v = Vec3::new;
    let (lo, hi) = (v(-10.0, 0.0, -6.0), v(10.0, 4.0, 6.0));
    b.closed_room(lo, hi, 0.2, floor, plaster);
    // Two partitions across the hall with doorways, and a row of pillars along it.
    for x in [-3.5f32, 3.5] {
        b.cuboid(v(x - 0.1, 0.0, -6.0), v(x + 0.1, 4.0, -1.0), brick);
        b.cuboid(v(x - 0.1, 0.0, 1.0), v(x + 0.1, 4.0, 6.0), brick);
        b.cuboid(v(x - 0.1, 2.5, -1.0), v(x + 0.1, 4.0, 1.0), brick);
    }
    for k in 0..6 {
        let x = -8.5 + 3.4 * k as f32;
        b.cuboid(v(x - 0.25, 0.0, 2.75), v(x + 0.25, 4.0, 3.25), plaster);
    }
    // Tiles at fixed pseudo-random places: on the ceiling, and high on the long walls, each a
    // 15 cm square facing into the hall.
    let mut random = super::xorshift(0x2545_f491);
    let h = 0.075;
    for k in 0..MANY_LIGHTS {
        let x = lo.x + 0.5 + random() * (hi.x - lo.x - 1.0);
        if k % 3 == 0 {
            // A wall tile, 3 m up, on the north (−z) or south (+z) wall.
            let y = 2.6 + random() * 1.0;
            if k % 2 == 0 {
                let z = lo.z + 0.001;
                b.quad(
                    [
                        v(x - h, y - h, z),
                        v(x + h, y - h, z),
                        v(x + h, y + h, z),
                        v(x - h, y + h, z),
                    ],
                    tile,
                );
            } else {
                let z = hi.z - 0.001;
                b.quad(
                    [
                        v(x + h, y - h, z),
                        v(x - h, y - h, z),
                        v(x - h, y + h, z),
                        v(x + h, y + h, z),
                    ],
                    tile,
                );
            }
        } else {
            let z = lo.z + 0.5 + random() * (hi.z - lo.z - 1.0);
            let y = hi.y - 0.001;
            b.quad(
                [
                    v(x - h, y, z - h),
                    v(x + h, y, z - h),
                    v(x + h, y, z + h),
                    v(x - h, y, z + h),
                ],
                tile,
            );
        }
    }
    let camera = Camera::looking_at(v(-9.0, 1.7, -4.5), v(2.0, 1.2, 1.0), 70.0);
    let mut scene = b.into_scene("many-lights", camera);
    scene.probe_volumes.push(crate::model::ProbeVolumeDesc::new(
        "hall",
        v(-9.8, 0.2, -5.8),
        v(9.8, 3.8, 5.8),
        [20, 4, 12],
    ));
    scene
}
