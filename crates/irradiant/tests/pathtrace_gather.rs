//! The path tracer's truth at points and lobes (pathtrace/gather), which DDGI's oracles measure
//! against, checked against closed forms: the glowing box, many small emitters, several
//! bounces, an emitter under a veil, and each way of sampling light (lavapipe-sized).

mod common;

use common::*;
use glam::Vec3;
use irradiant::GpuScene;
use irradiant::pathtrace::{GatherKind, GatherQuery, LightSampling, PathTraceSettings, gather};

fn truth_settings(samples: u32) -> PathTraceSettings {
    PathTraceSettings {
        samples_per_pixel: samples,
        samples_per_dispatch: 64,
        max_bounces: 64,
        seed: 3,
        light_sampling: Default::default(),
        schedule: Default::default(),
    }
}

#[test]
fn the_gather_pass_reads_the_glowing_box_in_closed_form() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("glowing-box").unwrap().scene;
    let gpu_scene = GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    // The light arriving anywhere, minus the emission of the wall it comes from:
    // ρ·Le / (1 − ρ).
    let (le, albedo) = (
        irradiant_scene::GLOWING_BOX_EMISSION,
        irradiant_scene::GLOWING_BOX_ALBEDO,
    );
    let reflected = albedo * le / (1.0 - albedo);
    let centre = Vec3::new(0.0, 1.0, 0.0);
    let radiance = |origin: Vec3, axis: Vec3, on_surface: bool| GatherQuery {
        origin,
        axis,
        exponent: 1.0,
        kind: GatherKind::Radiance,
        on_surface,
    };
    let queries = [
        radiance(centre, Vec3::X, false),
        radiance(centre, Vec3::NEG_Y, false),
        radiance(Vec3::new(0.3, 0.0, 0.2), Vec3::Y, true),
        // The wall at x = 1 is 1 m from the centre: a narrow lobe reads that distance.
        GatherQuery {
            origin: centre,
            axis: Vec3::X,
            exponent: 20_000.0,
            kind: GatherKind::Distance { far: 10.0 },
            on_surface: false,
        },
        // Capped at `far` where the wall is further.
        GatherQuery {
            origin: centre,
            axis: Vec3::X,
            exponent: 20_000.0,
            kind: GatherKind::Distance { far: 0.5 },
            on_surface: false,
        },
    ];
    // 2048 samples: the path tracer's MIS weights take the emitter grid's pdf, which fits walls
    // that all glow less well than power alone did (a third more noise at 1024 samples).
    let truth = gather(&ctx, &gpu_scene, &queries, &truth_settings(2048), |_, _| {}).unwrap();
    for i in 0..3 {
        let l = truth.radiance(i);
        let error = truth.luminance_standard_error(i);
        eprintln!("query {i}: {l:?} ± {error:.4} (closed form {reflected})");
        assert!(
            l.iter().all(|c| (c - reflected).abs() <= 0.05 * reflected) && error < 0.02,
            "query {i} gathered {l:?} ± {error}, not ρ·Le / (1 − ρ) = {reflected}"
        );
    }
    let [mean, square] = truth.distance_moments(3);
    assert!(
        (mean - 1.0).abs() < 0.01 && (square - 1.0).abs() < 0.02,
        "{mean} {square}"
    );
    assert_eq!(truth.distance_moments(4), [0.5, 0.25]);
}

/// Splits every triangle of every mesh into four, `levels` times over (flat shading, no texture
/// coordinates): the same surfaces as many small triangles.
fn subdivided(mut scene: irradiant_scene::Scene, levels: u32) -> irradiant_scene::Scene {
    for mesh in &mut scene.meshes {
        for _ in 0..levels {
            let mut positions = Vec::new();
            let mut materials = Vec::new();
            for (t, corner) in mesh.indices.chunks(3).enumerate() {
                let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[corner[k] as usize]);
                let [ab, bc, ca] = [(a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0];
                for triangle in [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]] {
                    positions.extend(triangle);
                    materials.push(mesh.triangle_materials[t]);
                }
            }
            mesh.indices = (0..positions.len() as u32).collect();
            mesh.positions = positions;
            mesh.triangle_materials = materials;
            mesh.normals.clear();
            mesh.uvs.clear();
        }
    }
    scene
}

/// Cosine lobes of radiance about these axes from a point off the middle of the glowing box.
fn lobes_from_box_middle(axes: &[Vec3]) -> Vec<GatherQuery> {
    axes.iter()
        .map(|&axis| GatherQuery {
            origin: Vec3::new(0.2, 1.1, -0.3),
            axis,
            exponent: 1.0,
            kind: GatherKind::Radiance,
            on_surface: false,
        })
        .collect()
}

/// The emitters are sampled per triangle (∝ power, by a CDF over all of them) and mixed with
/// BRDF samples by multiple importance: with the walls cut into 12 288 small triangles, in a
/// BVH many levels deep, one bounce of their light must still add up to the closed form.
#[test]
fn one_bounce_from_many_small_emitters_reads_the_closed_form() {
    let Some(ctx) = gpu() else { return };
    let scene = subdivided(irradiant_scene::load("glowing-box").unwrap().scene, 5);
    let triangles: usize = scene.meshes.iter().map(|m| m.triangle_count()).sum();
    assert!(triangles >= 12_000, "{triangles} triangles");
    let gpu_scene = GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    // One bounce off a wall that every direction sees: ρ·Le.
    let expected = irradiant_scene::GLOWING_BOX_ALBEDO * irradiant_scene::GLOWING_BOX_EMISSION;
    let queries =
        lobes_from_box_middle(&[Vec3::X, Vec3::NEG_Y, Vec3::Z, Vec3::new(1.0, 1.0, -1.0)]);
    let settings = PathTraceSettings {
        max_bounces: 1,
        ..truth_settings(2048)
    };
    let truth = gather(&ctx, &gpu_scene, &queries, &settings, |_, _| {}).unwrap();
    for i in 0..queries.len() {
        let l = truth.radiance(i);
        let error = truth.luminance_standard_error(i);
        eprintln!("query {i}: {l:?} ± {error:.4} (closed form {expected})");
        assert!(
            l.iter().all(|c| (c - expected).abs() <= 0.05 * expected),
            "query {i} gathered {l:?} ± {error}, not ρ·Le = {expected}"
        );
    }
}

/// A floor-wide panel of the box below: at this height, glowing or a black veil, facing up
/// or down.
#[derive(Clone, Copy)]
struct Panel {
    height: f32,
    glows: bool,
    up: bool,
}

/// The glowing box with its walls dark, and panels over its floor.
fn box_with_floor_panels(panels: &[Panel]) -> irradiant_scene::Scene {
    let mut scene = irradiant_scene::load("glowing-box").unwrap().scene;
    for m in &mut scene.materials {
        m.emission = Vec3::ZERO;
    }
    let lamp = scene.materials.len() as u32;
    scene.materials.push(irradiant_scene::Material {
        name: "lamp".into(),
        base_color: glam::Vec4::new(0.5, 0.5, 0.5, 1.0),
        emission: Vec3::splat(irradiant_scene::GLOWING_BOX_EMISSION),
        ..Default::default()
    });
    scene.materials.push(irradiant_scene::Material {
        name: "veil".into(),
        base_color: glam::Vec4::new(0.0, 0.0, 0.0, 1.0),
        ..Default::default()
    });
    let mesh = &mut scene.meshes[0];
    for panel in panels {
        let base = mesh.positions.len() as u32;
        for (x, z) in [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            mesh.positions.push(Vec3::new(x, panel.height, z));
            if !mesh.normals.is_empty() {
                mesh.normals
                    .push(if panel.up { Vec3::Y } else { Vec3::NEG_Y });
            }
            if !mesh.uvs.is_empty() {
                mesh.uvs.push(glam::Vec2::ZERO);
            }
        }
        // Counter-clockwise seen from above faces up.
        let corners = if panel.up {
            [0, 1, 2, 0, 2, 3]
        } else {
            [0, 2, 1, 0, 3, 2]
        };
        mesh.indices.extend(corners.map(|k| base + k));
        let material = if panel.glows { lamp } else { lamp + 1 };
        mesh.triangle_materials.extend([material, material]);
    }
    scene
}

/// Every bounce of the truth reaches its closed form in a scene whose rays traverse deep
/// trees, however many samples a dispatch asks for. llvmpipe (lavapipe) ends all the loops of
/// a shader invocation once they have run 65 535 iterations together, silently: asked for all
/// 1024 samples in one dispatch, this box read 0.079 instead of 0.875 on lavapipe before the
/// path tracer split its work there (`GpuInfo::loop_iteration_limit`; docs/ddgi.md, "A fault of
/// the path tracer on lavapipe").
#[test]
fn three_bounces_in_a_finely_cut_box_read_the_closed_form() {
    let Some(ctx) = gpu() else { return };
    let scene = subdivided(irradiant_scene::load("glowing-box").unwrap().scene, 6);
    let gpu_scene = GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    let queries = lobes_from_box_middle(&[Vec3::X, Vec3::NEG_Y]);
    // BRDF samples alone: in a box glowing alike everywhere every path of three bounces
    // brings exactly ρLe + ρ²Le + ρ³Le, without noise.
    let settings = PathTraceSettings {
        max_bounces: 3,
        samples_per_dispatch: 1024,
        light_sampling: LightSampling::Brdf,
        ..truth_settings(1024)
    };
    let truth = gather(&ctx, &gpu_scene, &queries, &settings, |_, _| {}).unwrap();
    let (rho, le) = (
        irradiant_scene::GLOWING_BOX_ALBEDO,
        irradiant_scene::GLOWING_BOX_EMISSION,
    );
    let expected = (rho + rho * rho + rho * rho * rho) * le;
    for i in 0..queries.len() {
        let l = truth.radiance(i);
        eprintln!("three bounces, lobe {i}: {l:?} (closed form {expected})");
        assert!(
            l.iter().all(|c| (c - expected).abs() <= 0.01 * expected),
            "lobe {i} gathered {l:?}, not {expected}"
        );
    }
}

/// One bounce of the floor panels' light at two lobes looking up from the middle of the box
/// (the ceiling and the upper walls), luminance summed over the channels.
fn one_bounce_looking_up(
    ctx: &std::sync::Arc<irradiant::GpuContext>,
    scene: &irradiant_scene::Scene,
    light_sampling: LightSampling,
) -> Vec<f32> {
    let queries = lobes_from_box_middle(&[Vec3::Y, Vec3::new(1.0, 1.0, 0.0)]);
    let settings = PathTraceSettings {
        max_bounces: 1,
        light_sampling,
        ..truth_settings(32768)
    };
    let gpu_scene = GpuScene::new(ctx, scene, &Default::default()).unwrap();
    let truth = gather(ctx, &gpu_scene, &queries, &settings, |_, _| {}).unwrap();
    (0..queries.len())
        .map(|i| truth.radiance(i).iter().sum::<f32>())
        .collect()
}

/// A surface a hair in front of an emitter hides it from the emitter sample as it does from
/// BRDF-sampled rays. A shadow ray stopped short of the sampled point by a margin (once
/// 10⁻⁴ of its length, 0.2 mm here) missed a veil closer than that: a glowing Sponza, whose
/// surfaces lie that close in places, read 16 % too bright (docs/ddgi.md).
#[test]
fn an_emitter_under_a_veil_a_hair_above_it_is_dark() {
    let Some(ctx) = gpu() else { return };
    let lamp = Panel {
        height: 2e-5,
        glows: true,
        up: true,
    };
    let veil = Panel {
        height: 4e-5,
        glows: false,
        up: true,
    };
    let both = LightSampling::Both;
    let open = one_bounce_looking_up(&ctx, &box_with_floor_panels(&[lamp]), both);
    let veiled = one_bounce_looking_up(&ctx, &box_with_floor_panels(&[lamp, veil]), both);
    eprintln!(
        "one bounce from the floor's panel: open {open:?}, under a veil 20 µm above {veiled:?}"
    );
    for (o, v) in open.iter().zip(&veiled) {
        assert!(*o > 0.1, "the open panel lights the box: {o}");
        assert!(*v < 0.01 * o, "the veiled panel leaks {v} against {o} open");
    }
}

/// The emitter sample and BRDF-sampled rays each find the same light alone
/// (`LightSampling`), also where a wall is two coincident faces back to back — a glowing
/// panel over a second one facing down, as two-sided walls are modelled. A BRDF-sampled ray
/// sees whichever face its closest hit returns; an emitter sample whose shadow ray only asked
/// whether anything else lay before the point saw the panel through the other face.
#[test]
fn each_way_of_sampling_light_finds_the_same_light() {
    let Some(ctx) = gpu() else { return };
    let face = |up| Panel {
        height: 2e-5,
        glows: true,
        up,
    };
    let scenes = [
        ("a glowing panel", box_with_floor_panels(&[face(true)])),
        (
            "a two-sided glowing panel",
            box_with_floor_panels(&[face(false), face(true)]),
        ),
    ];
    for (name, scene) in &scenes {
        let [both, emitters, brdf] = [
            LightSampling::Both,
            LightSampling::Emitters,
            LightSampling::Brdf,
        ]
        .map(|sampling| one_bounce_looking_up(&ctx, scene, sampling));
        eprintln!(
            "{name}, one bounce: both {both:?}, emitters alone {emitters:?}, BRDF alone {brdf:?}"
        );
        for i in 0..both.len() {
            assert!(
                both[i] > 0.1,
                "{name}: the panel lights the box: {}",
                both[i]
            );
            for (way, l) in [("emitters", emitters[i]), ("BRDF", brdf[i])] {
                assert!(
                    (l / both[i] - 1.0).abs() < 0.05,
                    "{name}, lobe {i}: {way} alone {l}, both {}",
                    both[i]
                );
            }
        }
    }
}
