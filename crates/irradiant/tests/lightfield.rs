//! Light-field probes (issue 11): the baked maps against the BVH, light-field rays against
//! the BVH's, the three shading algorithms against the path tracer (Lambertian and glossy),
//! light leaks and the paper's Figure 10 against classic probes, the probe view, the disk
//! cache, and bad settings. Figures are printed for docs/lightfield.md.

mod common;

use common::*;
use glam::{UVec2, Vec3};
use irradiant::frame::Image;
use irradiant::lightfield::{Lightfield, LightfieldSettings, agreement};
use irradiant::raycast::types::GpuRay;
use irradiant::raycast::{RayCaster, RayOrder};
use irradiant::{Preset, Session, SessionSettings, TechniqueSpec};

/// Bakes lavapipe can afford: 3×3×3 probes, 128² maps, two bounces.
fn small() -> LightfieldSettings {
    let mut s = LightfieldSettings::balanced();
    s.bake.probe_counts = [3, 3, 3];
    s.bake.resolution = 128;
    s.bake.prefilter_resolution = 32;
    s.bake.irradiance_texels = 8;
    s.bake.distance_texels = 16;
    s.bake.bounces = 2;
    s.bake.emitter_samples = 8;
    s.shade.naive_rays = 8;
    s
}

fn spec(name: &str, settings: &LightfieldSettings) -> TechniqueSpec {
    TechniqueSpec::with_settings(name, settings)
}

fn render(
    ctx: &std::sync::Arc<irradiant::GpuContext>,
    scene: &irradiant_scene::Scene,
    size: (u32, u32),
    spec: TechniqueSpec,
    frames: u32,
) -> Session {
    let mut s = session(ctx, scene, size, spec);
    for _ in 0..frames {
        s.render().unwrap();
    }
    s
}

/// Every texel of a probe's distance map is the BVH's distance in the texel's direction (to
/// f16's precision), or "no surface" where the BVH's ray leaves; the normals face the probe;
/// the min-mip holds each 16×16 block's nearest distance.
#[test]
fn the_baked_maps_hold_what_the_bvh_sees() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut settings = small();
    settings.bake.resolution = 64;
    let s = render(&ctx, &scene, (32, 32), spec("lightfield", &settings), 1);
    let lf = s.technique_as::<Lightfield>().unwrap();
    let res = settings.bake.resolution;
    let caster = RayCaster::new(&ctx, s.gpu_scene()).unwrap();
    let low = lf.read_min_mip(&ctx).unwrap();
    let low_res = res / 16;
    let (mut front, mut surfaces, mut disagree) = (0, 0, 0);
    let positions = lf.probe_positions(&ctx).unwrap();
    for probe in [0, 13, 26] {
        let texels = lf.read_probe(&ctx, probe).unwrap();
        let origin = positions[probe as usize];
        let rays: Vec<GpuRay> = (0..res * res)
            .map(|i| {
                let d = irradiant::probes::octahedral::texel_direction(
                    UVec2::new(i % res, i / res),
                    res,
                );
                GpuRay {
                    origin: origin.to_array(),
                    t_max: 1e5,
                    dir: d.to_array(),
                    stop: 0.0,
                }
            })
            .collect();
        let hits = caster
            .trace(&ctx, s.gpu_scene(), &rays, false, RayOrder::Incoherent)
            .unwrap();
        for (i, (texel, hit)) in texels.iter().zip(&hits).enumerate() {
            // f16 keeps 11 significant bits.
            let same = if hit.t < 0.0 {
                texel.distance == 65504.0
            } else {
                (texel.distance - hit.t).abs() <= hit.t * 1e-3 + 1e-4
            };
            if !same {
                eprintln!(
                    "probe {probe} texel {i}: stored {} where the BVH says {}",
                    texel.distance, hit.t
                );
                disagree += 1;
                continue;
            }
            if hit.t < 0.0 {
                continue;
            }
            surfaces += 1;
            front += (texel.normal.dot(Vec3::from(rays[i].dir)) < 0.0) as u32;
        }
        for by in 0..low_res {
            for bx in 0..low_res {
                let nearest = (0..256)
                    .map(|k| {
                        texels[((by * 16 + k / 16) * res + bx * 16 + k % 16) as usize].distance
                    })
                    .fold(f32::MAX, f32::min);
                assert_eq!(
                    low[(probe * low_res * low_res + by * low_res + bx) as usize],
                    nearest
                );
            }
        }
    }
    // The bake's rays and these (directions computed on the CPU) may part where a ray grazes
    // an edge between two walls: a few texels in a thousand.
    assert!(
        disagree * 500 <= 3 * res * res,
        "{disagree} texels disagree with the BVH"
    );
    // The box is closed and the probes are inside: every surface they see faces them, except
    // where a probe sits inside one of the blocks.
    eprintln!("probe texels on front faces: {front} of {surfaces}");
    assert!(
        front as f64 >= 0.85 * surfaces as f64,
        "{front} of {surfaces}"
    );
    // The inspector's pictures hold each probe's maps in its tile, and its probes are where
    // the probes are.
    let inspection = s.technique().inspect(&ctx).unwrap();
    assert_eq!(inspection.images.len(), 3);
    assert_eq!(inspection.probes.len(), positions.len());
    let probe = &inspection.probes[13];
    assert_eq!(probe.position, positions[13]);
    let tile = inspection.images[probe.images.0].tile(probe.tile).unwrap();
    assert_eq!((tile.width, tile.height), (res, res));
    let expected: Vec<u8> = lf
        .read_probe(&ctx, 13)
        .unwrap()
        .iter()
        .flat_map(|t| irradiant::inspect::radiance_pixel(t.radiance.to_array()))
        .collect();
    assert_eq!(tile.rgba8, expected, "probe 13's radiance tile");
}

/// Rays from the visible surfaces, traced through the light field alone, meet what the BVH
/// meets: the same surface within the tolerance (texel footprint and surface thickness), or
/// nothing where the BVH's ray leaves the scene.
#[test]
fn light_field_rays_agree_with_the_bvh() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let s = render(&ctx, &scene, (64, 64), spec("lightfield", &small()), 1);
    let a = agreement::measure(&s, 8192, 7).unwrap();
    eprintln!(
        "cornell 3×3×3, 128²: {:.1} % of {} rays agree ({a:?})",
        100.0 * a.share(),
        a.rays
    );
    // Seen on lavapipe: 96.5 %. Bound: 93 %.
    assert!(a.share() >= 0.93, "{a:?}");
    assert!(a.false_misses as f64 <= 0.01 * a.rays as f64, "{a:?}");
}

/// The three shading algorithms on the Cornell box against the path tracer: each far closer
/// than direct light alone.
#[test]
fn the_three_algorithms_approach_the_path_tracer() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let reference = path_trace(&ctx, &scene, size, 256);
    let none = flip_mean(
        &reference,
        &render(
            &ctx,
            &scene,
            size,
            TechniqueSpec::new("none", Preset::Balanced),
            1,
        )
        .image()
        .unwrap(),
    );
    let mut figures = vec![("none", none)];
    for name in ["lightfield", "lightfield-traced", "lightfield-naive"] {
        let f = flip_mean(
            &reference,
            &render(&ctx, &scene, size, spec(name, &small()), 20)
                .image()
                .unwrap(),
        );
        figures.push((name, f));
    }
    eprintln!("Cornell box, FLIP against the path tracer: {figures:?}");
    // Seen on lavapipe: none 0.50, lightfield 0.15, traced 0.12, naive 0.12.
    for (name, f) in &figures[1..] {
        assert!(
            *f < 0.5 * none,
            "{name}: FLIP {f:.3} against direct light's {none:.3}"
        );
    }
}

/// Glossy reflection of indirect light: on the glossy Cornell box, the traced glossy ray
/// brings the image closer to the path tracer than the Lambertian term alone.
#[test]
fn the_glossy_ray_reflects_indirect_light() {
    let Some(ctx) = gpu() else { return };
    let path = repo_root().join("scenes/cornell-box/glossy.toml");
    let scene = irradiant_scene::load(path.to_str().unwrap()).unwrap().scene;
    let size = (64, 64);
    let reference = path_trace(&ctx, &scene, size, 256);
    let mut settings = small();
    let glossy = flip_mean(
        &reference,
        &render(&ctx, &scene, size, spec("lightfield", &settings), 20)
            .image()
            .unwrap(),
    );
    settings.shade.glossy = false;
    let lambertian = flip_mean(
        &reference,
        &render(&ctx, &scene, size, spec("lightfield", &settings), 20)
            .image()
            .unwrap(),
    );
    eprintln!(
        "glossy Cornell box, FLIP against the path tracer: glossy ray {glossy:.4}, Lambertian only {lambertian:.4}"
    );
    assert!(
        glossy < lambertian,
        "glossy {glossy:.4} against Lambertian only {lambertian:.4}"
    );
}

/// Two rooms joined by a door, one lit: the light field's visibility keeps the dark room dark
/// where classic probes leak the lit room's light through the wall.
#[test]
fn two_rooms_light_field_visibility_stops_the_leak() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("two-rooms").unwrap().scene;
    let size = (64, 48);
    let reference = path_trace(&ctx, &scene, size, 512);
    let mut classic = irradiant::ddgi::DdgiSettings::balanced();
    classic.update.weights = irradiant::ddgi::ProbeWeights::Classic;
    classic.update.hysteresis = 0.9;
    let dark = |spec: TechniqueSpec, frames: u32| {
        let s = render(&ctx, &scene, size, spec, frames);
        let result = frame_result(&s);
        let mask = region_mask(&result.gbuffer, scene.region("dark-room").unwrap());
        (
            masked_mean(&result.indirect, &mask),
            masked_mean(&path_traced_indirect(&reference, &result), &mask),
        )
    };
    let (c, pt) = dark(TechniqueSpec::with_settings("classic-probes", &classic), 60);
    let mut lf = small();
    lf.bake.probe_counts = [0, 0, 0];
    // The dark room is lit through the door after several bounces: bake eight.
    lf.bake.bounces = 8;
    let (l, _) = dark(spec("lightfield", &lf), 2);
    eprintln!(
        "two-rooms dark room, mean indirect: path tracer {pt:.5}, classic probes {c:.5} (error {:.5}), light field {l:.5} (error {:.5})",
        (c - pt).abs(),
        (l - pt).abs()
    );
    // Seen on lavapipe: path tracer 0.071, classic probes 0.135, light field 0.064 (9.2×
    // closer). Bound: 3× closer.
    assert!(
        (l - pt).abs() * 3.0 <= (c - pt).abs(),
        "the light field must leak far less"
    );
}

/// The paper's Figure 10: box-cylinders, probes swallowed by the cylinders. Irradiance with
/// the light field's visibility against classic probes: no tile around the cylinders darker
/// than half the median.
#[test]
fn box_cylinders_light_field_irradiance_has_no_dark_halo() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("box-cylinders").unwrap().scene;
    let size = (64, 48);
    let reference = path_trace(&ctx, &scene, size, 512);
    let tiles = |spec: TechniqueSpec, frames: u32| {
        let s = render(&ctx, &scene, size, spec, frames);
        let result = frame_result(&s);
        let mask = region_mask(&result.gbuffer, scene.region("around-cylinders").unwrap());
        let mut ratios = block_ratios(
            &result.indirect,
            &path_traced_indirect(&reference, &result),
            &mask,
            8,
        );
        ratios.sort_by(f64::total_cmp);
        (ratios[0], ratios[ratios.len() / 2])
    };
    let mut classic = irradiant::ddgi::DdgiSettings::balanced();
    classic.update.weights = irradiant::ddgi::ProbeWeights::Classic;
    classic.update.hysteresis = 0.9;
    // The figure's classic probes stay where the grid puts them, in the cylinders, and every
    // one of them shades.
    classic.update.relocation = false;
    classic.update.shade_probes_in_geometry = true;
    let classic = tiles(TechniqueSpec::with_settings("classic-probes", &classic), 60);
    let mut lf = small();
    lf.bake.probe_counts = [0, 0, 0];
    let light_field = tiles(spec("lightfield", &lf), 2);
    let s = render(&ctx, &scene, size, spec("lightfield", &lf), 1);
    let lightfield = s.technique_as::<Lightfield>().unwrap();
    let grid = lightfield.grid().clone();
    let moved = lightfield
        .probe_positions(&ctx)
        .unwrap()
        .iter()
        .enumerate()
        .filter(|(p, at)| at.distance(grid.probe_position(*p as u32)) > 1e-4)
        .count();
    eprintln!("box-cylinders: {moved} probes moved out of the cylinders");
    assert!(moved > 0, "the cylinders swallow probes: some must move");
    eprintln!(
        "box-cylinders, indirect ÷ path tracer over 8×8 tiles around the cylinders (worst, median): classic probes {classic:.2?}, light field {light_field:.2?}"
    );
    assert!(
        light_field.0 >= 0.5 * light_field.1,
        "a dark halo: {light_field:.2?}"
    );
    // Seen on lavapipe (commit 2eecf16): classic probes left in the cylinders (0.04, 0.10), light
    // field with relocation (0.39, 0.48); without relocation the light field's worst tile was
    // 0.14, black between the cylinders. (DDGI's classic weights with relocation and its tied
    // probes read (0.62, 0.71); this baseline used relocation until commit 2eecf16.)
    assert!(
        (1.0 - light_field.1).abs() < (1.0 - classic.1).abs(),
        "light field {light_field:.2?} against classic {classic:.2?}"
    );
}

/// The light field relocates its probes by DDGI's rule (`relocation_keeps_grid`): the probes
/// in the Cornell box's two boxes leave them through a side and stay on. Its own steps left
/// the tall box's probe off, within 1.5 cm of where it started.
#[test]
fn light_field_probes_in_boxes_on_the_floor_leave_them_through_a_side() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut lf = small();
    lf.bake.probe_counts = [0, 0, 0];
    let s = render(&ctx, &scene, (16, 16), spec("lightfield", &lf), 1);
    let lightfield = s.technique_as::<Lightfield>().unwrap();
    let positions = lightfield.probe_positions(&ctx).unwrap();
    let states = lightfield.read_probe_states(&ctx).unwrap();
    assert_cornell_box_probes_left_through_a_side(&scene, &positions, |p| {
        states[p] & irradiant::ddgi::constants::PROBE_STATE_MASK
            != irradiant::ddgi::constants::PROBE_OFF
    });
}

/// lightfield/prefilter sums a probe's whole reduced map in one shader invocation. Where the
/// adapter ends an invocation's loops past a limit (llvmpipe: 65 535 iterations), a map too
/// large to sum under it (2 × 256² texels) is refused, naming the setting; below it the bake
/// runs.
#[test]
fn a_prefilter_map_past_the_adapters_loop_limit_is_refused() {
    let Some(ctx) = gpu() else { return };
    if ctx.info.loop_iteration_limit.is_none() {
        eprintln!("{} ends no loops early: nothing to refuse", ctx.info.name);
        return;
    }
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut lf = small();
    lf.bake.resolution = 256;
    lf.bake.prefilter_resolution = 256;
    let new_session = |lf: &LightfieldSettings| {
        Session::new(
            ctx.clone(),
            scene.clone(),
            SessionSettings {
                size: (16, 16),
                technique: spec("lightfield", lf),
                ..Default::default()
            },
        )
    };
    let message = new_session(&lf).err().unwrap().to_string();
    eprintln!("{message}");
    assert!(
        message.contains("technique.bake.prefilter_resolution") && message.contains("128 or less"),
        "{message}"
    );
    lf.bake.prefilter_resolution = 128;
    assert!(
        new_session(&lf).is_ok(),
        "2 × 128² texels sum under the limit"
    );
}

/// The debug view (the paper's Figure 20): primary rays traced through the probes alone see
/// the box as the camera does — red wall left, green wall right.
#[test]
fn the_probe_view_sees_the_scene_from_the_probes_alone() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (48, 48);
    let mut s = session(&ctx, &scene, size, spec("lightfield", &small()));
    s.set_show_probes(true);
    s.render().unwrap();
    let view = s.image().unwrap();
    let side_mean = |x0: u32, x1: u32| {
        let mut sum = [0.0f64; 3];
        for y in 12..36 {
            for x in x0..x1 {
                let p = view.pixels[(y * size.0 + x) as usize];
                for c in 0..3 {
                    sum[c] += p[c] as f64;
                }
            }
        }
        sum
    };
    let (left, right) = (side_mean(0, 6), side_mean(42, 48));
    eprintln!("probe view: left wall {left:?}, right wall {right:?}");
    assert!(
        left[0] > 2.0 * left[1] && right[1] > 2.0 * right[0],
        "{left:?} {right:?}"
    );
}

/// A bake is stored and read back unchanged; a changed scene, changed bake settings or a
/// changed self-shadow bias (the bake's bounces read it) bake anew; a damaged entry is baked
/// over, not read.
#[test]
fn a_bake_is_cached_and_a_stale_one_is_never_read() {
    let Some(ctx) = gpu() else { return };
    let dir =
        std::env::temp_dir().join(format!("irradiant-lightfield-cache-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let mut settings = small();
    settings.bake.resolution = 32;
    settings.bake.probe_counts = [2, 2, 2];
    let run = |scene: &irradiant_scene::Scene, settings: &LightfieldSettings| {
        let mut s = Session::new(
            ctx.clone(),
            scene.clone(),
            SessionSettings {
                size: (32, 32),
                technique: spec("lightfield", settings),
                cache_dir: Some(dir.clone()),
                ..Default::default()
            },
        )
        .unwrap();
        s.render().unwrap();
        let report = s.technique_as::<Lightfield>().unwrap().bake_report();
        (report.cached, s.image().unwrap())
    };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let (cached, baked) = run(&scene, &settings);
    assert!(!cached, "an empty cache has nothing to read");
    let (cached, loaded) = run(&scene, &settings);
    assert!(cached, "the second run reads the bake");
    assert_eq!(
        baked.pixels, loaded.pixels,
        "a cached bake renders as the bake did"
    );
    let mut repainted = scene.clone();
    repainted.materials[0].base_color *= 0.5;
    assert!(!run(&repainted, &settings).0, "a changed scene bakes anew");
    let mut more_bounces = settings.clone();
    more_bounces.bake.bounces += 1;
    assert!(
        !run(&scene, &more_bounces).0,
        "changed bake settings bake anew"
    );
    let mut shading = settings.clone();
    shading.shade.glossy_hysteresis = 0.5;
    assert!(
        run(&scene, &shading).0,
        "shading settings do not touch the bake"
    );
    let mut bias = settings.clone();
    bias.shade.self_shadow_bias = 0.6;
    assert!(
        !run(&scene, &bias).0,
        "the self-shadow bias, which the bake's bounces read, bakes anew"
    );
    // Damage every entry: each is baked over.
    for entry in std::fs::read_dir(&dir).unwrap().flatten() {
        let bytes = std::fs::read(entry.path()).unwrap();
        std::fs::write(entry.path(), &bytes[..bytes.len() / 2]).unwrap();
    }
    let (cached, rebaked) = run(&scene, &settings);
    assert!(!cached, "a damaged entry is not read");
    assert_eq!(rebaked.pixels, baked.pixels);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Settings out of range are refused naming the key and what is allowed.
#[test]
fn bad_settings_are_refused_naming_the_key() {
    type Change = fn(&mut LightfieldSettings);
    let cases: [(&str, Change, &str); 6] = [
        (
            "resolution",
            |s| s.bake.resolution = 100,
            "technique.bake.resolution",
        ),
        (
            "probe counts",
            |s| s.bake.probe_counts = [0, 2, 2],
            "technique.bake.probe_counts",
        ),
        (
            "prefilter",
            |s| s.bake.prefilter_resolution = 48,
            "technique.bake.prefilter_resolution",
        ),
        (
            "thickness",
            |s| s.shade.max_thickness = s.shade.min_thickness / 2.0,
            "technique.shade.max_thickness",
        ),
        (
            "hysteresis",
            |s| s.shade.lambert_hysteresis = 1.5,
            "technique.shade.lambert_hysteresis",
        ),
        (
            "visits",
            |s| s.shade.max_probe_visits = 0,
            "technique.shade.max_probe_visits",
        ),
    ];
    for (what, change, key) in cases {
        let mut s = LightfieldSettings::balanced();
        change(&mut s);
        let kind = irradiant::registry::find("lightfield").unwrap();
        let message = kind
            .check(&spec("lightfield", &s))
            .err()
            .unwrap()
            .to_string();
        assert!(message.contains(key), "{what}: {message}");
    }
    // More probes than a bake dispatch holds: refused before anything is built.
    let mut s = LightfieldSettings::balanced();
    s.bake.probe_counts = [64, 64, 64];
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let kind = irradiant::registry::find("lightfield").unwrap();
    let message = kind
        .plan(&spec("lightfield", &s), &scene, (64, 64))
        .err()
        .unwrap()
        .to_string();
    assert!(
        message.contains("technique.bake.probe_counts") && message.contains("fewer probes"),
        "{message}"
    );
}

/// Dynamic objects receive indirect light from the baked probes: a block that slides across
/// the Cornell box after the bake is lit at its new place about as a bake made with it there
/// lights it (the bake itself never sees it move).
#[test]
fn a_moving_object_is_lit_by_the_baked_probes() {
    use glam::Vec3;
    use irradiant_scene::{Animation, AnimationTarget, Tracks};
    let Some(ctx) = gpu() else { return };
    let size = (48, 48);
    let there = Vec3::new(0.5, 0.6, 0.2);
    let mut moving = cornell_with_block(Vec3::new(-0.5, 0.6, 0.2));
    moving.animations.push(Animation {
        target: AnimationTarget::Instance("block".into()),
        tracks: Tracks {
            translation: vec![(0.0, Vec3::ZERO), (1.0, Vec3::new(1.0, 0.0, 0.0))],
            ..Default::default()
        },
    });
    // Mean indirect light over the pixels that see the block at `there`.
    let on_block = |s: &Session| {
        let result = frame_result(s);
        let (lo, hi) = (there - 0.26, there + 0.26);
        let mask: Vec<bool> = result
            .gbuffer
            .iter()
            .map(|g| {
                let p = Vec3::from(g.position);
                g.depth >= 0.0 && p.cmpge(lo).all() && p.cmple(hi).all()
            })
            .collect();
        assert!(
            mask.iter().filter(|&&m| m).count() > 20,
            "the block is in view"
        );
        masked_mean(&result.indirect, &mask)
    };
    let mut s = session(&ctx, &moving, size, spec("lightfield", &small()));
    s.render().unwrap();
    s.seek(1.0);
    for _ in 0..4 {
        s.render().unwrap();
    }
    let moved = on_block(&s);
    let placed = cornell_with_block(there);
    let baked = on_block(&render(
        &ctx,
        &placed,
        size,
        spec("lightfield", &small()),
        4,
    ));
    eprintln!(
        "indirect light on the moved block {moved:.5}, baked with the block there {baked:.5}"
    );
    assert!(
        moved > 0.5 * baked && moved < 2.0 * baked,
        "{moved} against {baked}"
    );
}

/// `shade.self_shadow_bias` is applied between frames (`Session::set_technique` keeps the
/// bake): the irradiance query then reads close to what a session started with the new bias
/// reads — not exactly, since that one's bake gathered its bounces with the new bias too (seen:
/// 0.0205 moved, 0.0024 left). Before commit 2eecf16 the change did not reach the query at all.
#[test]
fn a_live_change_of_the_self_shadow_bias_reaches_the_query() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (32, 32);
    let mut settings = small();
    settings.shade.glossy = false;
    settings.shade.irradiance_block = 1;
    let mut changed = settings.clone();
    changed.shade.self_shadow_bias = 1.5;
    let mut live = render(&ctx, &scene, size, spec("lightfield", &settings), 2);
    let before = frame_result(&live).indirect;
    live.set_technique(spec("lightfield", &changed)).unwrap();
    live.render().unwrap();
    let after = frame_result(&live).indirect;
    let fresh = frame_result(&render(&ctx, &scene, size, spec("lightfield", &changed), 1)).indirect;
    let differ = |a: &Image, b: &Image| {
        a.pixels
            .iter()
            .zip(&b.pixels)
            .map(|(p, q)| (p[0] - q[0]).abs() + (p[1] - q[1]).abs() + (p[2] - q[2]).abs())
            .sum::<f32>()
            / a.pixels.len() as f32
    };
    let (moved, left) = (differ(&before, &after), differ(&after, &fresh));
    eprintln!("mean |Δ| after the change {moved:.5}, against a fresh session {left:.6}");
    assert!(
        moved > 1e-3,
        "a bias of 1.5 should change the light: {moved}"
    );
    // What is left is the bake's: its bounces gathered with the bias it was baked with.
    assert!(
        left < 0.25 * moved,
        "the live change reads {left} off a fresh session, against {moved} moved"
    );
}
