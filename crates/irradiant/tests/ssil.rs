//! Screen-space indirect illumination: the GPU steps against CPU oracles (one level's gather,
//! the voxel grid's parity and its AND levels), visibility only ever removing light, and the
//! technique against the path tracer and against direct light alone.

mod common;

use common::*;
use glam::{Vec2, Vec3};
use irradiant::gpu_types::GpuCamera;
use irradiant::ssil::{HybridSettings, Ssil, SsilDdgi, SsilSettings, StartResolution};
use irradiant::{Session, TechniqueSpec};

fn ssil_spec(settings: &SsilSettings) -> TechniqueSpec {
    TechniqueSpec::with_settings("ssil", settings)
}

/// shaders/random.wgsl, for the oracle to draw the same samples.
fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747796405).wrapping_add(2891336453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277803737);
    (word >> 22) ^ word
}

fn rng_seed(a: u32, b: u32, c: u32) -> u32 {
    pcg_hash(a ^ pcg_hash(b ^ pcg_hash(c)))
}

fn rand(state: &mut u32) -> f32 {
    *state = pcg_hash(*state);
    (*state >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// One level's gather (no visibility, diffuse) against the same sum on the CPU, over the
/// pyramid the GPU made: every texel's irradiance and coverage.
#[test]
fn a_level_gather_matches_the_cpu_oracle() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64u32, 64u32);
    let mut settings = SsilSettings::balanced();
    settings.start = StartResolution::Half;
    settings.levels = 3;
    settings.samples = 24;
    settings.visibility = false;
    settings.glossy = false;
    let mut session = session(&ctx, &scene, size, ssil_spec(&settings));
    session.render().unwrap();
    let ssil = session.technique_as::<Ssil>().unwrap();
    let camera = GpuCamera::new(session.camera(), size.0, size.1);
    let radius = settings.radius_at(size.1);
    let pixel_area0 = 4.0 * camera.tan_half_fov_y * camera.tan_half_fov_y * camera.aspect
        / (size.0 * size.1) as f32;
    let forward = Vec3::from(camera.forward);
    let mut compared = 0;
    let mut worst = 0.0f32;
    for j in 0..settings.levels {
        let level = settings.start.level() + j;
        let (w, h) = (size.0 >> level, size.1 >> level);
        let nd = read_level(&ctx, session.frame(), "pyramid_normal_depth", level);
        let radiance = read_level(&ctx, session.frame(), "pyramid_radiance", level);
        let gathered = ssil.read_gather(&ctx, j).unwrap();
        let position = |p: (u32, u32), depth: f32| {
            let dir = camera.ray_dir(
                Vec2::new(p.0 as f32 + 0.5, p.1 as f32 + 0.5) * (1 << level) as f32,
                size.0,
                size.1,
            );
            Vec3::from(camera.position) + dir * (depth / dir.dot(forward))
        };
        let inner = if j == 0 { 0.0 } else { 0.5 * radius };
        let region = std::f32::consts::PI * (radius * radius - inner * inner);
        let pixel_area = pixel_area0 * (1u32 << (2 * level)) as f32;
        for y in 0..h {
            for x in 0..w {
                let i = (y * w + x) as usize;
                if nd[i][3] < 0.0 {
                    continue;
                }
                let n = Vec3::new(nd[i][0], nd[i][1], nd[i][2]);
                let p = position((x, y), nd[i][3]);
                // The shader's draws: the spiral's rotation from the texel's seed, each
                // sample's jitter from its lane's (lane = sample mod GATHER_LANES).
                let texel_seed = rng_seed(y * w + x, 0, level * 7919 + 0x2545f491);
                let mut rng = texel_seed;
                let rotation = std::f32::consts::TAU * rand(&mut rng);
                let lanes = irradiant::ssil::constants::GATHER_LANES;
                let mut lane_rngs: Vec<u32> = (0..lanes)
                    .map(|lane| rng_seed(texel_seed, lane, 0x68e31da4))
                    .collect();
                let (mut light, mut coverage) = (Vec3::ZERO, 0.0f32);
                for s in 0..settings.samples {
                    let rng = &mut lane_rngs[(s % lanes) as usize];
                    let u = (s as f32 + rand(rng)) / settings.samples as f32;
                    let rho = (inner * inner + (radius * radius - inner * inner) * u).sqrt();
                    let angle = rotation + s as f32 * 2.399_963_2;
                    let q = Vec2::new(x as f32 + 0.5, y as f32 + 0.5)
                        + rho * Vec2::new(angle.cos(), angle.sin());
                    if q.x < 0.0 || q.y < 0.0 || q.x >= w as f32 || q.y >= h as f32 {
                        continue;
                    }
                    let k = (q.y as u32 * w + q.x as u32) as usize;
                    if nd[k][3] < 0.0 {
                        continue;
                    }
                    let nq = Vec3::new(nd[k][0], nd[k][1], nd[k][2]);
                    let pq = position((q.x as u32, q.y as u32), nd[k][3]);
                    let d = pq - p;
                    let r2 = d.length_squared();
                    let wi = d / r2.sqrt();
                    let (cos_r, cos_s) = (n.dot(wi), nq.dot(-wi));
                    if r2 < 1e-10 || cos_r <= 0.0 || cos_s <= 0.0 {
                        continue;
                    }
                    let view = (pq - Vec3::from(camera.position)).normalize();
                    let ds = nd[k][3]
                        * nd[k][3]
                        * pixel_area
                        * (region / settings.samples as f32)
                        * view.dot(forward)
                        / nq.dot(view).abs().max(0.05);
                    let g = cos_r * cos_s * ds / (r2 + cos_s * ds / std::f32::consts::PI);
                    light += Vec3::new(radiance[k][0], radiance[k][1], radiance[k][2]) * g;
                    coverage += g / std::f32::consts::PI;
                }
                let got = gathered[i];
                let error = (Vec3::new(got[0], got[1], got[2]) - light)
                    .abs()
                    .max_element()
                    / light.max_element().max(0.02);
                worst = worst.max(error);
                // Bound: f16 storage (1e-3) and float rounding of the sample positions, which
                // can move a sample across a texel edge now and then.
                assert!(
                    error < 0.05 && (got[3] - coverage.min(1.0)).abs() < 0.02,
                    "level {level} texel ({x}, {y}): GPU {got:?}, CPU {light} coverage {coverage}"
                );
                compared += 1;
            }
        }
    }
    eprintln!("{compared} texels compared; worst relative difference {worst:.4}");
    assert!(compared > 500);
}

/// Möller–Trumbore, both sides: the distance along the ray, if it crosses the triangle.
fn crossing(origin: Vec3, dir: Vec3, [a, b, c]: [Vec3; 3]) -> Option<f32> {
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-12 {
        return None;
    }
    let s = origin - a;
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = dir.dot(q) / det;
    let t = e2.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 1e-6).then_some(t)
}

/// The voxel grid against every crossing of each texel's ray on the CPU: each slice's bit is
/// the parity of the crossings before it; each further level is the AND of the four below.
#[test]
fn the_voxel_grid_holds_the_parity_of_the_crossings() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64u32, 48u32);
    let mut settings = SsilSettings::balanced();
    settings.start = StartResolution::Half;
    settings.levels = 3;
    settings.samples = 4;
    let mut session = session(&ctx, &scene, size, ssil_spec(&settings));
    session.render().unwrap();
    let ssil = session.technique_as::<Ssil>().unwrap();
    let (near, far) = ssil.depth_range(session.camera());
    let camera = GpuCamera::new(session.camera(), size.0, size.1);
    let forward = Vec3::from(camera.forward);
    let triangles: Vec<[Vec3; 3]> = scene
        .instances
        .iter()
        .flat_map(|i| {
            let mesh = &scene.meshes[i.mesh as usize];
            (0..mesh.triangle_count())
                .map(move |t| mesh.triangle(t).map(|p| i.transform.transform_point3(p)))
        })
        .collect();
    let slice = |depth: f32| ((depth - near) / (far - near) * 128.0).floor() as i32;
    let grid = ssil.read_voxels(&ctx, 0).unwrap();
    let (w, h) = (size.0 >> 1, size.1 >> 1);
    let mut mismatched = 0;
    for y in 0..h {
        for x in 0..w {
            let dir = camera.ray_dir(
                Vec2::new(x as f32 + 0.5, y as f32 + 0.5) * 2.0,
                size.0,
                size.1,
            );
            let mut ts: Vec<f32> = triangles
                .iter()
                .filter_map(|&t| crossing(Vec3::from(camera.position), dir, t))
                .collect();
            ts.sort_by(f32::total_cmp);
            // The shader steps past each surface by 1e-4·max(1, t): crossings closer than that
            // (a ray through the edge two triangles share) are one surface.
            ts.dedup_by(|later, earlier| *later - *earlier < 1e-4 * earlier.max(1.0));
            let depths: Vec<f32> = ts.iter().map(|t| t * dir.dot(forward)).collect();
            let got = grid[(y * w + x) as usize];
            let bit = |s: u32| (got[(s / 32) as usize] >> (s % 32)) & 1 == 1;
            let wrong: Vec<u32> = (0..128u32)
                .filter(|&s| {
                    let inside = depths.iter().filter(|&&d| slice(d) <= s as i32).count() % 2 == 1;
                    inside != bit(s)
                })
                .collect();
            mismatched += !wrong.is_empty() as u32;
        }
    }
    // Bound: a crossing that lands on a slice boundary may round to either slice on the GPU
    // and the CPU; 1% of the 32×24 texels may disagree (none do on lavapipe).
    eprintln!(
        "voxel level 0: {mismatched} of {} texels differ from the CPU's crossings",
        w * h
    );
    assert!(
        mismatched * 100 <= w * h,
        "{mismatched} of {} texels differ",
        w * h
    );
    for level in 1..settings.levels {
        let above = ssil.read_voxels(&ctx, level).unwrap();
        let below = ssil.read_voxels(&ctx, level - 1).unwrap();
        let (wb, hb) = (w >> (level - 1), h >> (level - 1));
        let (wa, ha) = (w >> level, h >> level);
        for y in 0..ha {
            for x in 0..wa {
                let mut and = [u32::MAX; 4];
                for k in 0..4u32 {
                    let (sx, sy) = (
                        (2 * x + (k & 1)).min(wb - 1),
                        (2 * y + (k >> 1)).min(hb - 1),
                    );
                    let v = below[(sy * wb + sx) as usize];
                    for c in 0..4 {
                        and[c] &= v[c];
                    }
                }
                assert_eq!(
                    above[(y * wa + x) as usize],
                    and,
                    "level {level} texel ({x}, {y})"
                );
            }
        }
    }
    // The box's blocks are closed, its walls are not: some rays end inside.
    let (open, total) = ssil.read_open_rays(&ctx).unwrap();
    assert_eq!(total, w * h);
    eprintln!("rays ending inside a solid: {open} of {total}");
}

fn mean_indirect(session: &Session) -> f64 {
    let indirect = session.indirect().unwrap();
    masked_mean(&indirect, &vec![true; indirect.pixels.len()])
}

/// Visibility only removes light: with the same samples, every pixel's light with visibility
/// is at most its light without (the paper's Figure 7), and the blocks shadow some of it.
#[test]
fn visibility_only_removes_light() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let run = |visibility: bool| {
        let mut settings = SsilSettings::balanced();
        settings.visibility = visibility;
        let mut s = session(&ctx, &scene, size, ssil_spec(&settings));
        s.render().unwrap();
        let light = s.technique_as::<Ssil>().unwrap().read_light(&ctx).unwrap();
        (light, mean_indirect(&s))
    };
    let (with, mean_with) = run(true);
    let (without, mean_without) = run(false);
    let mut darker = 0;
    for (a, b) in with.iter().zip(&without) {
        for c in 0..3 {
            // f16 rounding of the same sum.
            assert!(
                a[c] <= b[c] * 1.002 + 1e-4,
                "visibility added light: {a:?} against {b:?}"
            );
        }
        darker += (a[1] < 0.9 * b[1]) as u32;
    }
    eprintln!(
        "mean indirect: visibility {mean_with:.5}, none {mean_without:.5}; {darker} pixels lost over 10 %"
    );
    assert!(
        darker > 50,
        "the blocks should shadow some indirect light ({darker} pixels lost over 10 %)"
    );
    assert!(mean_with < mean_without);
}

/// After a reset the screen's history is a running mean until it holds `hysteresis`: with the
/// same samples, the light after the second and third frames is the mean of the frames so
/// far, which a filter with no history (hysteresis 0) shows one by one. A first frame kept at
/// the full hysteresis weighed 0.9 against the second's 0.1, and its noise lingered for tens of
/// frames (ssil+ddgi's first 30 frames after a cut, docs/ssil.md).
#[test]
fn the_screens_history_starts_as_a_running_mean() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (32, 32);
    let frames = |hysteresis: f32| {
        let mut settings = SsilSettings::balanced();
        settings.hysteresis = hysteresis;
        let mut s = session(&ctx, &scene, size, ssil_spec(&settings));
        (0..3)
            .map(|_| {
                s.render().unwrap();
                s.indirect().unwrap()
            })
            .collect::<Vec<_>>()
    };
    let (filtered, raw) = (frames(0.9), frames(0.0));
    let mut worst = 0.0f32;
    for (n, image) in filtered.iter().enumerate().skip(1) {
        for (i, got) in image.pixels.iter().enumerate() {
            for (c, value) in got.iter().enumerate() {
                let so_far = raw[..=n].iter().map(|frame| frame.pixels[i][c]);
                let mean = so_far.sum::<f32>() / (n + 1) as f32;
                worst = worst.max((value - mean).abs() / (1e-3 + mean.abs()));
            }
        }
    }
    // The old weights put 0.4 × the first two frames' difference between them and the mean:
    // the test tells them apart where some pixel moves by far more than 2.5 × the bound.
    let moved = raw[1]
        .pixels
        .iter()
        .zip(&raw[0].pixels)
        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs() / (1e-3 + b[c].abs())))
        .fold(0.0f32, f32::max);
    eprintln!(
        "frames 2 and 3 against the mean of the frames so far: {worst:e}; frame 2 moved {moved:.3}"
    );
    assert!(
        moved > 0.05,
        "the frames should differ for the test to tell ({moved})"
    );
    assert!(
        worst <= 5e-3,
        "the history is {worst} from the running mean"
    );
}

/// Against the path tracer on the Cornell box: screen-space light, alone and with DDGI's
/// probes, must bring the image closer to the reference than direct light alone.
#[test]
fn screen_space_light_brings_the_cornell_box_closer_to_the_path_tracer() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let reference = path_trace(&ctx, &scene, size, 512);
    let render = |spec: TechniqueSpec| {
        let mut s = session(&ctx, &scene, size, spec);
        for _ in 0..40 {
            s.render().unwrap();
        }
        s.image().unwrap()
    };
    let flip = |image: &irradiant::frame::Image| flip_mean(&reference, image);
    let none = flip(&render(spec(None)));
    let ssil = flip(&render(ssil_spec(&SsilSettings::balanced())));
    let hybrid = flip(&render(TechniqueSpec::with_settings(
        "ssil+ddgi",
        &HybridSettings::balanced(),
    )));
    eprintln!(
        "Cornell box, FLIP against the path tracer: direct light {none:.4}, ssil {ssil:.4}, ssil+ddgi {hybrid:.4}"
    );
    assert!(
        ssil < none,
        "screen-space light must improve on direct light alone"
    );
    assert!(hybrid < ssil, "the probes must fill what the screen misses");
}

/// More bounces add light, and ssil+ddgi runs both techniques' passes.
#[test]
fn bounces_add_light_and_the_hybrid_runs_both() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (48, 48);
    let mean = |bounces: u32| {
        let mut settings = SsilSettings::balanced();
        settings.bounces = bounces;
        settings.visibility = false;
        let mut s = session(&ctx, &scene, size, ssil_spec(&settings));
        s.render().unwrap();
        mean_indirect(&s)
    };
    let (one, two) = (mean(1), mean(2));
    eprintln!("mean indirect: 1 bounce {one:.5}, 2 bounces {two:.5}");
    assert!(two > one * 1.02, "a second bounce must add light");
    let mut hybrid = session(
        &ctx,
        &scene,
        size,
        TechniqueSpec::with_settings("ssil+ddgi", &HybridSettings::fast()),
    );
    let timed = hybrid.render_profiled().unwrap();
    let labels: Vec<&str> = timed.iter().map(|t| t.label.as_str()).collect();
    if !timed.is_empty() {
        assert!(
            labels.contains(&"ddgi/trace")
                && labels.contains(&"ssil/probe_light")
                && labels.contains(&"ssil/temporal"),
            "{labels:?}"
        );
    }
    assert!(hybrid.technique_as::<SsilDdgi>().is_some());
}

/// Levels that would fall under a pixel are refused, naming the setting; a scene that is not
/// watertight is warned about, naming the fix.
#[test]
fn bad_settings_are_refused_and_open_scenes_warned_about() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut settings = SsilSettings::balanced();
    settings.levels = 6;
    let error = Session::new(
        ctx.clone(),
        scene.clone(),
        irradiant::SessionSettings {
            size: (40, 30),
            technique: ssil_spec(&settings),
            ..Default::default()
        },
    )
    .err()
    .expect("six levels from a half start do not fit 40×30")
    .to_string();
    assert!(
        error.contains("technique.levels") && error.contains("under one pixel"),
        "{error}"
    );
    for (key, value) in [
        ("radius", toml::Value::Float(1.0)),
        ("samples", toml::Value::Integer(0)),
        ("samples", toml::Value::Integer(5000)),
        ("levels", toml::Value::Integer(9)),
        ("bounces", toml::Value::Integer(0)),
        ("visibility_bias", toml::Value::Float(0.5)),
    ] {
        let mut spec = TechniqueSpec::new("ssil", irradiant::Preset::Balanced);
        spec.settings.insert(key.into(), value.clone());
        let error = spec
            .kind()
            .unwrap()
            .check(&spec)
            .err()
            .map(|e| e.to_string());
        let error = error.unwrap_or_else(|| panic!("{key} = {value} must be refused"));
        assert!(error.contains(&format!("technique.{key}")), "{error}");
    }
    let s = session(&ctx, &scene, (32, 32), ssil_spec(&SsilSettings::balanced()));
    let warnings = s.warnings().join("\n");
    assert!(
        warnings.contains("not watertight") && warnings.contains("technique.visibility = false"),
        "{warnings}"
    );
}
