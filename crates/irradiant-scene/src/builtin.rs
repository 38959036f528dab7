//! Scenes made in code, needing no files: the quality tests' fixtures and the default scene.

use glam::{Mat4, Vec3, Vec4};

use crate::model::{Camera, Instance, Light, Material, Mesh, ProbeVolumeDesc, Region, Scene};

/// Names accepted by [`builtin`], with a line each for `--help` and error messages.
pub const BUILTIN_SCENES: &[(&str, &str)] = &[
    (
        "cornell",
        "the classic Cornell box with its area light (the default scene)",
    ),
    (
        "two-rooms",
        "a lit room and a dark room joined by a door: the light-leak test",
    ),
    (
        "box-cylinders",
        "a closed box with four cylinders that swallow probes: the dark-leak test",
    ),
    (
        "empty-box",
        "box-cylinders without its cylinders: the same room, lamp and probes, nothing in the way",
    ),
    (
        "thin-frames",
        "thin wooden frames in front of a lit wall: the self-shadow specks test",
    ),
    (
        "table",
        "a table with a 3 cm top under a lamp, a probe layer at the top's height: the extrapolation-leak test",
    ),
    (
        "slit-corridor",
        "a lit hall and a dark corridor joined by a 15 cm slit through a thick wall: light through openings narrower than the probe spacing",
    ),
    (
        "furnace",
        "a white diffuse sphere under a uniform white sky: the white-furnace test",
    ),
    (
        "glowing-box",
        "a closed box whose walls glow and reflect half the light: radiance 2 everywhere (the DDGI furnace)",
    ),
    (
        "dense-cluster",
        "a room with 330 000 tiny triangles packed into 4 cm on a table: the deep-tree bench",
    ),
    (
        "terrain",
        "480 m of ground under a sky, flat within 150 m of the middle, hills around: the large world's floor",
    ),
    (
        "tunnel",
        "an 80 m tunnel with five lamps and glowing strips: the large world's dark passage",
    ),
    (
        "many-lights",
        "a hall lit only by 120 small glowing tiles, partitions and pillars between them: the many-emitter test",
    ),
];

mod world;

/// The built-in scene called `name` (one of [`BUILTIN_SCENES`]), made anew; `None` for
/// any other name.
pub fn builtin(name: &str) -> Option<Scene> {
    match name {
        "cornell" => Some(cornell()),
        "two-rooms" => Some(two_rooms()),
        "box-cylinders" => Some(box_cylinders()),
        "empty-box" => Some(empty_box()),
        "thin-frames" => Some(thin_frames()),
        "table" => Some(table()),
        "slit-corridor" => Some(slit_corridor()),
        "furnace" => Some(furnace()),
        "glowing-box" => Some(glowing_box()),
        "dense-cluster" => Some(dense_cluster()),
        "terrain" => Some(world::terrain()),
        "tunnel" => Some(world::tunnel()),
        "many-lights" => Some(world::many_lights()),
        _ => None,
    }
}

/// A fixed sequence of numbers in [0, 1] (xorshift32 from `seed`, not 0): built-ins placed at
/// random are the same on every run, and so are tests' random weights.
pub fn xorshift(seed: u32) -> impl FnMut() -> f32 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state as f32 / u32::MAX as f32
    }
}

/// Appends quads, boxes and cylinders to one mesh.
struct Builder {
    mesh: Mesh,
    materials: Vec<Material>,
}

impl Builder {
    fn new(name: &str) -> Self {
        Self {
            mesh: Mesh {
                name: name.into(),
                ..Default::default()
            },
            materials: Vec::new(),
        }
    }

    fn material(&mut self, name: &str, albedo: Vec3, emission: Vec3) -> u32 {
        self.materials.push(Material {
            name: name.into(),
            base_color: albedo.extend(1.0),
            emission,
            ..Default::default()
        });
        self.materials.len() as u32 - 1
    }

    /// A planar quad p0 p1 p2 p3 (counter-clockwise seen from the side its normal faces).
    fn quad(&mut self, p: [Vec3; 4], material: u32) {
        let base = self.mesh.positions.len() as u32;
        self.mesh.positions.extend(p);
        for [i, j, k] in [[0u32, 1, 2], [0, 2, 3]] {
            let [a, b, c] = [p[i as usize], p[j as usize], p[k as usize]];
            // Quads that touch a sphere's pole have one zero-area half.
            if (b - a).cross(c - a).length_squared() > 0.0 {
                self.mesh.indices.extend([base + i, base + j, base + k]);
                self.mesh.triangle_materials.push(material);
            }
        }
    }

    /// An axis-aligned box, faces pointing out.
    fn cuboid(&mut self, lo: Vec3, hi: Vec3, material: u32) {
        self.transformed_box(
            Mat4::from_translation((lo + hi) * 0.5) * Mat4::from_scale(hi - lo),
            material,
        );
    }

    /// The unit cube [-0.5, 0.5]³ under `transform`, faces pointing out.
    fn transformed_box(&mut self, transform: Mat4, material: u32) {
        let c = |x: f32, y: f32, z: f32| transform.transform_point3(Vec3::new(x, y, z) - 0.5);
        let faces = [
            [c(0., 0., 1.), c(1., 0., 1.), c(1., 1., 1.), c(0., 1., 1.)],
            [c(1., 0., 0.), c(0., 0., 0.), c(0., 1., 0.), c(1., 1., 0.)],
            [c(1., 0., 1.), c(1., 0., 0.), c(1., 1., 0.), c(1., 1., 1.)],
            [c(0., 0., 0.), c(0., 0., 1.), c(0., 1., 1.), c(0., 1., 0.)],
            [c(0., 1., 1.), c(1., 1., 1.), c(1., 1., 0.), c(0., 1., 0.)],
            [c(0., 0., 0.), c(1., 0., 0.), c(1., 0., 1.), c(0., 0., 1.)],
        ];
        for f in faces {
            self.quad(f, material);
        }
    }

    /// The inside of a closed room from `lo` to `hi`: floor, ceiling and four walls as solid
    /// slabs `thickness` thick outside it (solid, so that probes and rays see proper backfaces).
    fn closed_room(&mut self, lo: Vec3, hi: Vec3, thickness: f32, floor: u32, walls: u32) {
        let (l, h) = (lo - Vec3::splat(thickness), hi + Vec3::splat(thickness));
        self.cuboid(Vec3::new(l.x, l.y, l.z), Vec3::new(h.x, lo.y, h.z), floor);
        self.cuboid(Vec3::new(l.x, hi.y, l.z), Vec3::new(h.x, h.y, h.z), walls);
        self.cuboid(Vec3::new(l.x, lo.y, l.z), Vec3::new(h.x, hi.y, lo.z), walls);
        self.cuboid(Vec3::new(l.x, lo.y, hi.z), Vec3::new(h.x, hi.y, h.z), walls);
        self.cuboid(
            Vec3::new(l.x, lo.y, lo.z),
            Vec3::new(lo.x, hi.y, hi.z),
            walls,
        );
        self.cuboid(
            Vec3::new(hi.x, lo.y, lo.z),
            Vec3::new(h.x, hi.y, hi.z),
            walls,
        );
    }

    /// A closed vertical cylinder (side plus caps).
    fn cylinder(&mut self, center: Vec3, radius: f32, height: f32, segments: u32, material: u32) {
        let point = |i: u32, y: f32| {
            let a = i as f32 / segments as f32 * std::f32::consts::TAU;
            center + Vec3::new(radius * a.cos(), y, -radius * a.sin())
        };
        for i in 0..segments {
            let (a0, a1) = (point(i, 0.0), point(i + 1, 0.0));
            let (b0, b1) = (point(i, height), point(i + 1, height));
            self.quad([a0, a1, b1, b0], material);
            let top = center + Vec3::Y * height;
            let base = self.mesh.positions.len() as u32;
            self.mesh.positions.extend([top, b0, b1, center, a1, a0]);
            self.mesh
                .indices
                .extend([base, base + 1, base + 2, base + 3, base + 4, base + 5]);
            self.mesh.triangle_materials.extend([material, material]);
        }
    }

    fn into_scene(self, name: &str, camera: Camera) -> Scene {
        Scene {
            name: name.into(),
            meshes: vec![self.mesh],
            instances: vec![Instance {
                name: name.into(),
                mesh: 0,
                transform: Mat4::IDENTITY,
            }],
            materials: self.materials,
            camera,
            ..Default::default()
        }
    }
}

/// The Cornell box: 2 units on a side, floor at y = 0, open towards +z, with the
/// measured wall colours and area light of the Cornell data set.
pub fn cornell() -> Scene {
    let mut b = Builder::new("cornell");
    let white = b.material("white", Vec3::new(0.725, 0.71, 0.68), Vec3::ZERO);
    let red = b.material("red", Vec3::new(0.63, 0.065, 0.05), Vec3::ZERO);
    let green = b.material("green", Vec3::new(0.14, 0.45, 0.091), Vec3::ZERO);
    let light = b.material("light", Vec3::splat(0.78), Vec3::new(17.0, 12.0, 4.0));
    let v = Vec3::new;
    b.quad(
        [
            v(-1., 0., 1.),
            v(1., 0., 1.),
            v(1., 0., -1.),
            v(-1., 0., -1.),
        ],
        white,
    ); // floor
    b.quad(
        [
            v(-1., 2., 1.),
            v(-1., 2., -1.),
            v(1., 2., -1.),
            v(1., 2., 1.),
        ],
        white,
    ); // ceiling
    b.quad(
        [
            v(-1., 0., -1.),
            v(1., 0., -1.),
            v(1., 2., -1.),
            v(-1., 2., -1.),
        ],
        white,
    ); // back
    b.quad(
        [
            v(-1., 0., 1.),
            v(-1., 0., -1.),
            v(-1., 2., -1.),
            v(-1., 2., 1.),
        ],
        red,
    ); // left
    b.quad(
        [v(1., 0., -1.), v(1., 0., 1.), v(1., 2., 1.), v(1., 2., -1.)],
        green,
    ); // right
    b.quad(
        [
            v(-0.24, 1.98, 0.16),
            v(-0.24, 1.98, -0.22),
            v(0.23, 1.98, -0.22),
            v(0.23, 1.98, 0.16),
        ],
        light,
    );
    let short = Mat4::from_translation(v(0.33, 0.3, 0.37))
        * Mat4::from_rotation_y(-0.29)
        * Mat4::from_scale(Vec3::splat(0.6));
    b.transformed_box(short, white);
    let tall = Mat4::from_translation(v(-0.335, 0.6, -0.29))
        * Mat4::from_rotation_y(0.3)
        * Mat4::from_scale(v(0.6, 1.2, 0.6));
    b.transformed_box(tall, white);
    let mut scene = b.into_scene("cornell", Camera::default());
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "box",
        v(-0.9, 0.1, -0.9),
        v(0.9, 1.9, 0.9),
        [4, 4, 4],
    ));
    scene
}

/// Two 4 × 3 × 4 rooms side by side along x, joined by a door in a 10 cm wall. A point light
/// burns in the left room; the right room sees only what comes through the door, so any
/// technique that leaks through the wall brightens it.
pub fn two_rooms() -> Scene {
    let mut b = Builder::new("two-rooms");
    let white = b.material("plaster", Vec3::splat(0.75), Vec3::ZERO);
    let floor = b.material("floor", Vec3::new(0.6, 0.45, 0.3), Vec3::ZERO);
    let v = Vec3::new;
    let t = 0.1;
    b.closed_room(v(-4.0, 0.0, -2.0), v(4.0, 3.0, 2.0), t, floor, white);
    // The dividing wall, with a door 1 m wide and 2 m high at z in [-0.5, 0.5].
    let h = t * 0.5;
    b.cuboid(v(-h, 0.0, -2.0), v(h, 3.0, -0.5), white);
    b.cuboid(v(-h, 0.0, 0.5), v(h, 3.0, 2.0), white);
    b.cuboid(v(-h, 2.0, -0.5), v(h, 3.0, 0.5), white);
    let camera = Camera::looking_at(v(3.6, 1.6, 1.7), v(0.0, 1.0, -0.3), 60.0);
    let mut scene = b.into_scene("two-rooms", camera);
    scene.lights.push(Light::point(
        "lamp",
        v(-2.0, 2.5, 0.0),
        Vec3::new(1.0, 0.9, 0.75),
        12.0,
    ));
    // Probes span the rooms up to 10–20 cm from the walls (the query extrapolates at most half
    // a cell past the outermost probes), and straddle the dividing wall at x = ±0.43.
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "rooms",
        v(-3.9, 0.2, -1.9),
        v(3.9, 2.8, 1.9),
        [10, 4, 5],
    ));
    scene
        .regions
        .push(Region::new("dark-room", v(h, 0.0, -2.0), v(4.0, 3.0, 2.0)));
    scene
        .regions
        .push(Region::new("lit-room", v(-4.0, 0.0, -2.0), v(-h, 3.0, 2.0)));
    scene
}

/// A closed 6 × 3 × 6 box with four floor-to-ceiling cylinders placed exactly on probe
/// positions of its 4 × 4 × 4 probe grid (the light-field paper's Fig. 10 setup): probes inside
/// geometry must not darken the surfaces around the cylinders.
pub fn box_cylinders() -> Scene {
    cylinder_box("box-cylinders", true)
}

/// `box_cylinders` without the cylinders: what is left of DDGI's error with nothing in the
/// way of the probes.
pub fn empty_box() -> Scene {
    cylinder_box("empty-box", false)
}

fn cylinder_box(name: &str, cylinders: bool) -> Scene {
    let mut b = Builder::new(name);
    let white = b.material("white", Vec3::splat(0.7), Vec3::ZERO);
    let column = b.material("column", Vec3::new(0.7, 0.55, 0.4), Vec3::ZERO);
    let v = Vec3::new;
    let t = 0.1;
    b.closed_room(v(-3.0, 0.0, -3.0), v(3.0, 3.0, 3.0), t, white, white);
    if cylinders {
        for (x, z) in [(-0.75, -0.75), (0.75, -0.75), (-0.75, 0.75), (0.75, 0.75)] {
            b.cylinder(v(x, 0.0, z), 0.35, 3.0, 24, column);
        }
    }
    let camera = Camera::looking_at(v(0.0, 1.6, 2.9), v(0.0, 1.0, -1.0), 70.0);
    let mut scene = b.into_scene(name, camera);
    scene
        .lights
        .push(Light::point("lamp", v(-2.2, 2.6, 2.2), Vec3::ONE, 8.0));
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "box",
        v(-2.25, 0.375, -2.25),
        v(2.25, 2.625, 2.25),
        [4, 4, 4],
    ));
    scene.regions.push(Region::new(
        "around-cylinders",
        v(-1.5, 0.0, -1.5),
        v(1.5, 3.0, 1.5),
    ));
    scene
}

/// Two ladder-like frames of 3 cm bars before a wall, and between the wall and the frames a
/// lamp that the camera sees the frames' shadowed sides against, in a room with 0.5 m probe
/// spacing: bars far thinner than the self-shadow bias and a probe's distance texel, whose dark
/// sides may read the bright probes behind them — the specks on thin chair frames (issue 15).
pub fn thin_frames() -> Scene {
    let mut b = Builder::new("thin-frames");
    let white = b.material("white", Vec3::splat(0.75), Vec3::ZERO);
    let wood = b.material("wood", Vec3::new(0.45, 0.3, 0.18), Vec3::ZERO);
    let v = Vec3::new;
    b.closed_room(v(-2.0, 0.0, -2.0), v(2.0, 3.0, 2.0), 0.1, white, white);
    let bar = 0.03;
    for (z, x0) in [(-1.3, -0.9), (-0.7, -0.5)] {
        // Two posts and five rails.
        for x in [x0, x0 + 1.2] {
            b.cuboid(v(x, 0.0, z), v(x + bar, 1.6, z + bar), wood);
        }
        for k in 0..5 {
            let y = 0.3 + 0.3 * k as f32;
            b.cuboid(v(x0, y, z), v(x0 + 1.2 + bar, y + bar, z + bar), wood);
        }
    }
    let camera = Camera::looking_at(v(0.3, 1.2, 1.8), v(-0.1, 0.8, -1.5), 60.0);
    let mut scene = b.into_scene("thin-frames", camera);
    scene
        .lights
        .push(Light::point("lamp", v(0.1, 1.0, -1.65), Vec3::ONE, 2.0));
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "room",
        v(-1.75, 0.25, -1.75),
        v(1.75, 2.75, 1.75),
        [8, 6, 8],
    ));
    scene
        .regions
        .push(Region::new("frames", v(-1.0, 0.0, -1.4), v(0.8, 1.7, -0.6)));
    scene
}

/// A lit hall and a dark corridor behind a wall half a metre thick, joined only by a slit
/// 15 cm high, far narrower than the probe spacing (about 1.2 m): Sponza's upper corridors in
/// small (docs/ddgi.md). No ray from the lamp passes the slit, so the corridor's light comes
/// from the hall's surfaces and the slit's reveals, which the corridor's probes see at a small
/// angle and the surfaces by the slit at a large one.
pub fn slit_corridor() -> Scene {
    let mut b = Builder::new("slit-corridor");
    let white = b.material("plaster", Vec3::splat(0.75), Vec3::ZERO);
    let v = Vec3::new;
    b.closed_room(v(-3.0, 0.0, -2.0), v(3.0, 3.0, 2.0), 0.1, white, white);
    let (wall_front, wall_back) = (0.2, 0.7);
    let (slit_bottom, slit_top, slit_half_width) = (1.0, 1.15, 1.0);
    b.cuboid(
        v(-3.0, 0.0, wall_front),
        v(3.0, slit_bottom, wall_back),
        white,
    );
    b.cuboid(v(-3.0, slit_top, wall_front), v(3.0, 3.0, wall_back), white);
    for (x0, x1) in [(-3.0, -slit_half_width), (slit_half_width, 3.0)] {
        b.cuboid(
            v(x0, slit_bottom, wall_front),
            v(x1, slit_top, wall_back),
            white,
        );
    }
    let camera = Camera::looking_at(v(2.7, 1.7, 1.9), v(-1.5, 0.9, 0.7), 60.0);
    let mut scene = b.into_scene("slit-corridor", camera);
    scene.lights.push(Light::point(
        "lamp",
        v(0.0, 2.7, -1.2),
        Vec3::new(1.0, 0.9, 0.75),
        12.0,
    ));
    // Four layers along z: two in the hall, one in the wall (relocated out of it), one in the
    // corridor.
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "hall and corridor",
        v(-2.75, 0.25, -1.75),
        v(2.75, 2.75, 1.75),
        [6, 3, 4],
    ));
    scene.regions.push(Region::new(
        "corridor",
        v(-3.0, 0.0, wall_back),
        v(3.0, 3.0, 2.0),
    ));
    scene
}

/// A table (a 3 cm top, aprons, legs, low stretchers) half a metre under a lamp in a white room,
/// probes every 0.5 m with a layer at the height of the top, as in the interior of issue 15: the
/// probes on the top relocate under it, and the floor under it lies below the lowest probe
/// layer, where the query extrapolates the last two layers' trend (docs/ddgi.md).
pub fn table() -> Scene {
    let mut b = Builder::new("table");
    let white = b.material("white", Vec3::splat(0.75), Vec3::ZERO);
    let wood = b.material("wood", Vec3::new(0.55, 0.4, 0.25), Vec3::ZERO);
    let v = Vec3::new;
    b.closed_room(v(-3.0, 0.0, -2.5), v(3.0, 3.0, 2.5), 0.1, white, white);
    b.cuboid(v(-0.6, 0.72, -0.4), v(0.6, 0.75, 0.4), wood);
    for (x, z) in [(-0.57, -0.37), (0.53, -0.37), (-0.57, 0.33), (0.53, 0.33)] {
        b.cuboid(v(x, 0.0, z), v(x + 0.04, 0.72, z + 0.04), wood);
    }
    // Aprons under the top's edges, between the legs.
    for z in [-0.37, 0.35] {
        b.cuboid(v(-0.53, 0.64, z), v(0.53, 0.72, z + 0.02), wood);
    }
    for x in [-0.57, 0.55] {
        b.cuboid(v(x, 0.64, -0.33), v(x + 0.02, 0.72, 0.33), wood);
    }
    // Stretchers 15 cm off the floor: one along the table, one at each end.
    b.cuboid(v(-0.53, 0.15, -0.015), v(0.53, 0.18, 0.015), wood);
    for x in [-0.565, 0.535] {
        b.cuboid(v(x, 0.15, -0.33), v(x + 0.03, 0.18, 0.33), wood);
    }
    let camera = Camera::looking_at(v(1.6, 0.55, 1.5), v(0.0, 0.45, 0.0), 55.0);
    let mut scene = b.into_scene("table", camera);
    scene.lights.push(Light::point(
        "lamp",
        v(0.0, 1.3, 0.0),
        Vec3::new(1.0, 0.95, 0.85),
        3.0,
    ));
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "room",
        v(-2.75, 0.25, -2.25),
        v(2.75, 2.75, 2.25),
        [12, 6, 10],
    ));
    scene
        .regions
        .push(Region::new("table", v(-0.6, 0.0, -0.4), v(0.6, 0.76, 0.4)));
    scene
}

/// A white Lambertian sphere under a uniform sky of radiance 1: every pixel converges to 1,
/// whatever the number of bounces (the white-furnace test).
pub fn furnace() -> Scene {
    let mut b = Builder::new("furnace");
    let white = b.material("white", Vec3::ONE, Vec3::ZERO);
    let (rings, segments) = (24u32, 48u32);
    let point = |r: u32, s: u32| {
        let theta = r as f32 / rings as f32 * std::f32::consts::PI;
        let phi = s as f32 / segments as f32 * std::f32::consts::TAU;
        Vec3::new(
            theta.sin() * phi.cos(),
            theta.cos(),
            -theta.sin() * phi.sin(),
        )
    };
    for r in 0..rings {
        for s in 0..segments {
            b.quad(
                [
                    point(r, s),
                    point(r + 1, s),
                    point(r + 1, s + 1),
                    point(r, s + 1),
                ],
                white,
            );
        }
    }
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO, 40.0);
    let mut scene = b.into_scene("furnace", camera);
    scene.sky = Vec3::ONE;
    // Probes around the sphere, none inside it (the inner ones sit at |p| = 1.15).
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "around",
        Vec3::splat(-2.0),
        Vec3::splat(2.0),
        [4, 4, 4],
    ));
    scene.materials[0].base_color = Vec4::ONE;
    scene
}

/// A room whose table carries a dense cluster of tiny triangles, most of the scene's triangles
/// in a few centimetres (as scanned or sculpted detail often is): its tree is deep and
/// unbalanced, which is what made ray timings depend on what ran before (issue 13).
pub fn dense_cluster() -> Scene {
    const CLUSTER_TRIANGLES: u32 = 330_000;
    let mut b = Builder::new("dense-cluster");
    let white = b.material("white", Vec3::splat(0.7), Vec3::ZERO);
    let wood = b.material("wood", Vec3::new(0.55, 0.4, 0.25), Vec3::ZERO);
    let clay = b.material("clay", Vec3::new(0.8, 0.35, 0.25), Vec3::ZERO);
    let v = Vec3::new;
    b.closed_room(v(-3.0, 0.0, -3.0), v(3.0, 3.0, 3.0), 0.1, white, white);
    b.cuboid(v(-0.6, 0.7, -0.4), v(0.6, 0.75, 0.4), wood);
    b.cuboid(v(-0.55, 0.0, -0.35), v(-0.5, 0.7, -0.3), wood);
    b.cuboid(v(0.5, 0.0, 0.3), v(0.55, 0.7, 0.35), wood);
    // Triangles of about 0.3 mm, uniformly in a 4 cm cube: a fixed sequence, so every run
    // builds the same scene.
    let mut random = xorshift(0x9e37_79b9);
    let centre = v(0.0, 0.77, 0.0);
    for _ in 0..CLUSTER_TRIANGLES {
        let p = centre + (v(random(), random(), random()) - 0.5) * 0.04;
        let mut corner = || p + (v(random(), random(), random()) - 0.5) * 0.0003;
        let (a, b_, c) = (corner(), corner(), corner());
        if (b_ - a).cross(c - a).length_squared() > 0.0 {
            let base = b.mesh.positions.len() as u32;
            b.mesh.positions.extend([a, b_, c]);
            b.mesh.indices.extend([base, base + 1, base + 2]);
            b.mesh.triangle_materials.push(clay);
        }
    }
    let camera = Camera::looking_at(v(0.0, 1.2, 1.4), v(0.0, 0.75, 0.0), 50.0);
    let mut scene = b.into_scene("dense-cluster", camera);
    scene
        .lights
        .push(Light::point("lamp", v(0.5, 2.5, 0.5), Vec3::ONE, 10.0));
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "room",
        v(-2.5, 0.4, -2.5),
        v(2.5, 2.6, 2.5),
        [6, 4, 6],
    ));
    scene
}

/// Emitted radiance of the walls of the built-in `glowing-box` scene.
pub const GLOWING_BOX_EMISSION: f32 = 1.0;
/// Diffuse albedo of the walls of the built-in `glowing-box` scene.
pub const GLOWING_BOX_ALBEDO: f32 = 0.5;

/// A closed box whose every wall emits `GLOWING_BOX_EMISSION` and reflects
/// `GLOWING_BOX_ALBEDO` diffusely, with no other light: the radiance leaving every point in
/// every direction is Le / (1 − ρ) = 2 after infinitely many bounces, and the indirect light a
/// probe holds (what arrives, minus what the walls emit) is ρ·Le / (1 − ρ) = 1 — a furnace test
/// of energy across bounces, in closed form.
pub fn glowing_box() -> Scene {
    let mut b = Builder::new("glowing-box");
    let glow = b.material(
        "glow",
        Vec3::splat(GLOWING_BOX_ALBEDO),
        Vec3::splat(GLOWING_BOX_EMISSION),
    );
    let v = Vec3::new;
    b.closed_room(v(-1.0, 0.0, -1.0), v(1.0, 2.0, 1.0), 0.1, glow, glow);
    let camera = Camera::looking_at(v(0.0, 1.0, 0.9), v(0.0, 1.0, -1.0), 70.0);
    let mut scene = b.into_scene("glowing-box", camera);
    scene.probe_volumes.push(ProbeVolumeDesc::new(
        "box",
        v(-0.8, 0.2, -0.8),
        v(0.8, 1.8, 0.8),
        [3, 3, 3],
    ));
    scene
}
