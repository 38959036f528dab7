//! Tracking windows (003 §7.3, issue 39): a DDGI volume that follows the camera in whole
//! cells, stored as a circular buffer. The CPU oracle of the indexing is in probes/grid.rs;
//! here the GPU follows it: a window that walked through a wall into the next room lights the
//! frame as a volume placed where it stopped does, its entered probes relocated and classified
//! on their own; and a follow setting that names nothing is refused.

mod common;

use common::*;
use glam::Vec3;
use irradiant::ddgi::{Ddgi, DdgiSettings};
use irradiant_scene::{Camera, Follow, ProbeVolumeDesc};

const SIZE: (u32, u32) = (32, 32);

fn settings() -> DdgiSettings {
    let mut s = DdgiSettings::fast();
    s.update.hysteresis = 0.9;
    s
}

fn camera_at(x: f32) -> Camera {
    Camera::looking_at(Vec3::new(x, 1.5, 0.0), Vec3::new(x + 1.0, 1.3, -0.6), 70.0)
}

/// The image's light summed over blocks of 8 × 8 pixels (the probes' noise averaged).
fn block_sums(image: &irradiant::frame::Image) -> Vec<f64> {
    let (w, h) = (image.width as usize, image.height as usize);
    let mut sums = vec![0.0; (w / 8) * (h / 8)];
    for (i, p) in image.pixels.iter().enumerate() {
        let (x, y) = (i % w / 8, i / w / 8);
        sums[y * (w / 8) + x] += (p[0] + p[1] + p[2]) as f64;
    }
    sums
}

#[test]
fn a_window_that_walked_into_the_next_room_lights_it_as_a_volume_placed_there() {
    let Some(ctx) = gpu() else { return };
    // Two rooms joined by a door; the lamp burns in the left one. A window of 4 × 4 × 4
    // probes a metre apart starts around the camera in the left room.
    let mut scene = irradiant_scene::load("two-rooms").unwrap().scene;
    let window = |min: Vec3| ProbeVolumeDesc {
        follow: Some(Follow::Camera),
        ..ProbeVolumeDesc::new("window", min, min + Vec3::new(3.0, 2.4, 3.0), [4, 4, 4])
    };
    scene.probe_volumes = vec![window(Vec3::new(-3.5, 0.3, -1.5))];
    let mut walked = session(&ctx, &scene, SIZE, spec(Some(&settings())));
    walked.set_camera(camera_at(-2.5));
    for _ in 0..20 {
        walked.render().unwrap();
    }
    // Through the door, half a metre a frame: the window steps a cell every other frame, its
    // probes crossing the dividing wall and coming to rest with some inside it.
    let end = -2.5 + 0.5 * 7.0;
    for step in 1..=7 {
        walked.set_camera(camera_at(-2.5 + 0.5 * step as f32));
        walked.render().unwrap();
    }
    for _ in 0..240 {
        walked.render().unwrap();
    }
    let ddgi = walked.technique_as::<Ddgi>().unwrap();
    let grid = ddgi.volumes[0].grid.clone();
    // 3.5 m: the window stepped 3 or 4 cells along x (its phase turned), none along y or z.
    assert!(grid.origin.x > -0.6, "the window stayed at {}", grid.origin);
    assert_ne!(grid.phase, glam::UVec3::ZERO);
    let (lo, _) = grid.bounds();
    let walked_states = ddgi.volumes[0].read_state_counts(walked.ctx()).unwrap();

    // The same volume, placed where the window stopped and never moved.
    let mut placed_scene = scene.clone();
    placed_scene.probe_volumes = vec![ProbeVolumeDesc {
        follow: None,
        ..window(lo)
    }];
    // Placed twice, with two seeds of the probes' rays: how far two converged volumes at
    // the same place differ by noise alone.
    let place = |seed: u32| {
        let mut settings = settings();
        settings.update.seed = seed;
        let mut placed = session(&ctx, &placed_scene, SIZE, spec(Some(&settings)));
        placed.set_camera(camera_at(end));
        for _ in 0..240 {
            placed.render().unwrap();
        }
        placed
    };
    let (placed, reseeded) = (place(settings().update.seed), place(7));
    let placed_ddgi = placed.technique_as::<Ddgi>().unwrap();
    assert_eq!(placed_ddgi.volumes[0].grid.origin, grid.origin);
    let placed_states = placed_ddgi.volumes[0]
        .read_state_counts(placed.ctx())
        .unwrap();

    let (a, b) = (walked.indirect().unwrap(), placed.indirect().unwrap());
    let (a, b) = (block_sums(&a), block_sums(&b));
    let noise = block_sums(&reseeded.indirect().unwrap());
    let total = |s: &[f64]| s.iter().sum::<f64>();
    let in_all = total(&a) / total(&b) - 1.0;
    let per_block =
        |a: &[f64]| a.iter().zip(&b).map(|(p, q)| (p - q).abs()).sum::<f64>() / total(&b);
    let (walked_off, noise_floor) = (per_block(&a), per_block(&noise));
    eprintln!(
        "walked window against a placed volume: indirect {in_all:+.4} in all, {walked_off:.4} block by block (another seed: {noise_floor:.4}); states {walked_states:?} against {placed_states:?}"
    );
    assert!(total(&b) > 0.0, "the placed volume lit nothing");
    // Before the planes that changed layer were classified again, four probes stayed vigilant
    // that the placed volume put to sleep; a walk that ended 60 frames before the comparison
    // read +32 % (the placed volume had not converged through the door).
    assert!(in_all.abs() < 0.03, "indirect differs by {in_all:+} in all");
    assert!(
        walked_off < 1.5 * noise_floor + 0.01,
        "indirect differs by {walked_off} block by block, where another seed differs by {noise_floor}"
    );
    // The entered probes were classified on their own frames, as the placed volume's were.
    assert_eq!(walked_states.off, placed_states.off);
    assert_eq!(walked_states.sleeping, placed_states.sleeping);
}

/// A follow naming neither the camera nor an instance is refused by name: in the settings
/// when the session starts, in a manifest when the scene loads.
#[test]
fn a_follow_that_names_nothing_is_refused_by_name() {
    let Some(ctx) = gpu() else { return };
    let mut settings = DdgiSettings::fast();
    settings.volume.follow = "sun".into();
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let e = irradiant::Session::new(
        ctx,
        scene,
        irradiant::SessionSettings {
            size: (8, 8),
            technique: spec(Some(&settings)),
            ..Default::default()
        },
    )
    .err()
    .unwrap()
    .to_string();
    assert!(
        e.contains("technique.volume.follow = \"sun\"") && e.contains("cornell"),
        "{e}"
    );
    let dir = std::env::temp_dir().join(format!("irradiant-window-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let manifest = dir.join("moon.toml");
    std::fs::write(
        &manifest,
        "name = \"m\"\n[mesh]\npath = \"cornell\"\n[[probe_volume]]\nmin = [0, 0, 0]\nmax = [1, 1, 1]\ncounts = [2, 2, 2]\nfollow = \"moon\"\n",
    )
    .unwrap();
    let e = irradiant_scene::load(manifest.to_str().unwrap())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("follow = \"moon\"") && e.contains("volume0") && e.contains("moon.toml"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A window that follows an instance (by the settings' name for it) steps as the host moves
/// the instance, and stays when the camera moves.
#[test]
fn a_window_follows_the_instance_it_names() {
    let Some(ctx) = gpu() else { return };
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    let at = |x: f32| {
        glam::Mat4::from_scale_rotation_translation(
            Vec3::splat(0.2),
            glam::Quat::IDENTITY,
            Vec3::new(x, 0.4, 0.0),
        )
    };
    scene.instances.push(irradiant_scene::Instance {
        name: "cart".into(),
        mesh: 0,
        transform: at(-0.5),
    });
    let mut settings = settings();
    settings.volume.follow = "cart".into();
    settings.volume.probe_counts = [4, 4, 4];
    let mut s = session(&ctx, &scene, (8, 8), spec(Some(&settings)));
    let origin = |s: &irradiant::Session| s.technique_as::<Ddgi>().unwrap().volumes[0].grid.origin;
    let centre = |s: &irradiant::Session| {
        let (lo, hi) = s.technique_as::<Ddgi>().unwrap().volumes[0].grid.bounds();
        (lo + hi) * 0.5
    };
    for _ in 0..3 {
        s.render().unwrap();
    }
    let start = centre(&s);
    assert!(
        (start.x + 0.5).abs() < 0.5,
        "the window is not on the cart: {start}"
    );
    s.set_instance_transform(1, at(0.5)).unwrap();
    s.render().unwrap();
    let moved = centre(&s);
    assert!(
        (moved.x - 0.5).abs() < 0.5 && moved.x > start.x,
        "{start} → {moved}"
    );
    let before = origin(&s);
    s.set_camera(Camera::looking_at(
        Vec3::new(3.0, 1.0, 3.0),
        Vec3::ZERO,
        40.0,
    ));
    s.render().unwrap();
    assert_eq!(origin(&s), before, "the camera moved the cart's window");
}

/// A window's probes move with the camera: saving them is refused, with the reason.
#[test]
fn the_probes_of_a_window_are_not_saved() {
    let Some(ctx) = gpu() else { return };
    let mut settings = DdgiSettings::fast();
    settings.volume.follow = "camera".into();
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut s = session(&ctx, &scene, (8, 8), spec(Some(&settings)));
    s.render().unwrap();
    let path = std::env::temp_dir().join(format!("irradiant-window-{}.probes", std::process::id()));
    let e = s.save_probes(&path).unwrap_err().to_string();
    assert!(e.contains("follows the camera"), "{e}");
    assert!(!path.exists());
}

/// A floor 400 m across under a uniform sky: every point of it receives the same light, so
/// whatever the cascades do at their borders shows as a step in the floor's indirect light.
fn open_floor() -> irradiant_scene::Scene {
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    let r = 200.0;
    scene.meshes = vec![irradiant_scene::Mesh {
        name: "floor".into(),
        positions: vec![
            Vec3::new(-r, 0.0, -r),
            Vec3::new(r, 0.0, -r),
            Vec3::new(r, 0.0, r),
            Vec3::new(-r, 0.0, r),
        ],
        indices: vec![0, 2, 1, 0, 3, 2],
        triangle_materials: vec![0, 0],
        ..Default::default()
    }];
    scene.materials.truncate(1);
    scene.instances = vec![irradiant_scene::Instance {
        name: "floor".into(),
        mesh: 0,
        transform: glam::Mat4::IDENTITY,
    }];
    scene.sky = Vec3::ONE;
    scene.probe_volumes.clear();
    scene.camera = Camera::looking_at(Vec3::new(0.0, 1.7, 0.0), Vec3::new(0.0, 0.0, -12.0), 60.0);
    scene
}

/// Three cascades over the open floor: down the middle of the image, from the camera's feet
/// to 20 m off, the floor's indirect light stays level across the cascades' borders (their
/// weights add up to 1 and fade without a step), and the schedule updated the finest every
/// frame and the coarser ones on their turns.
#[test]
fn cascades_light_an_open_floor_without_a_seam() {
    let Some(ctx) = gpu() else { return };
    let mut settings = settings();
    settings.volume.cascades = 3;
    settings.volume.cascade_spacing = 0.5;
    settings.volume.cascade_probes = [8, 4, 8];
    let scene = open_floor();
    let mut s = session(&ctx, &scene, SIZE, spec(Some(&settings)));
    for _ in 0..80 {
        s.render().unwrap();
    }
    let ddgi = s.technique_as::<Ddgi>().unwrap();
    let frames: Vec<u32> = ddgi.volumes.iter().map(|v| v.frame).collect();
    assert_eq!(frames, [80, 40, 40]);
    let spacing: Vec<f32> = ddgi.volumes.iter().map(|v| v.grid.spacing.x).collect();
    assert_eq!(spacing, [0.5, 1.0, 2.0]);
    let indirect = s.indirect().unwrap();
    let gbuffer = s.gbuffer().unwrap();
    let (w, h) = (SIZE.0 as usize, SIZE.1 as usize);
    // The floor's rows from the bottom of the image up, each the mean of the middle 8 pixels.
    let rows: Vec<(f32, f32)> = (0..h)
        .rev()
        .filter_map(|y| {
            let pixels = (w / 2 - 4..w / 2 + 4).map(|x| y * w + x);
            let depth = gbuffer[y * w + w / 2].depth;
            (depth > 0.0).then(|| {
                let light = pixels.map(|i| indirect.pixels[i][1]).sum::<f32>() / 8.0;
                (depth, light)
            })
        })
        .collect();
    // The coarsest cascade reaches 7 m to either side: past 30 m no cascade holds the floor.
    let rows: Vec<(f32, f32)> = rows.into_iter().filter(|r| r.0 < 30.0).collect();
    let far = rows.last().unwrap().0;
    assert!(
        far > 8.0,
        "the floor's rows reach only {far} m: not past the cascades' borders"
    );
    let mean = rows.iter().map(|r| r.1).sum::<f32>() / rows.len() as f32;
    let worst_step = rows
        .windows(2)
        .map(|p| (p[1].1 - p[0].1).abs())
        .fold(0.0, f32::max);
    let worst_off = rows.iter().map(|r| (r.1 - mean).abs()).fold(0.0, f32::max);
    eprintln!(
        "the open floor's indirect light: mean {mean:.4}, the largest step between rows {:.4}, the farthest from the mean {:.4} (rows to {far:.1} m)",
        worst_step / mean,
        worst_off / mean
    );
    assert!(mean > 0.0, "the floor has no indirect light");
    assert!(
        worst_step < 0.05 * mean,
        "a step of {worst_step} between rows"
    );
    assert!(
        worst_off < 0.1 * mean,
        "a row {worst_off} from the mean {mean}"
    );
}

/// Each pixel's volume weights (finest, middle, coarsest) from the volumes view
/// (ProbeView::Volumes leaves them in `indirect` as red, green and blue), None on the sky.
fn volume_weights(s: &mut irradiant::Session) -> Vec<Option<[f32; 3]>> {
    s.render().unwrap();
    let gbuffer = s.gbuffer().unwrap();
    let weights = s.indirect().unwrap().pixels;
    weights
        .into_iter()
        .zip(gbuffer)
        .map(|(w, g)| (g.depth > 0.0).then_some(w))
        .collect()
}

/// Three cascades seen from 0.8 m above the open floor, looking down with a wide lens, the
/// camera moving 5 cm a frame along x over 3 m: at every pixel of the floor the weights sum
/// to 1, the view passes through all three cascades, and no pixel's weights jump between two
/// frames — not at the finest cascade's window steps either (six, 0.5 m apart), since the
/// blend is tightened by a cell and centred on the camera (003 §7.4).
#[test]
fn cascade_weights_sum_to_one_and_follow_the_camera_without_a_jump() {
    let Some(ctx) = gpu() else { return };
    let mut settings = settings();
    settings.volume.cascades = 3;
    settings.volume.cascade_spacing = 0.5;
    settings.volume.cascade_probes = [8, 8, 8];
    let scene = open_floor();
    let look = |x: f32| Camera::looking_at(Vec3::new(x, 0.8, 0.0), Vec3::new(x, 0.0, -0.3), 150.0);
    let mut s = session(&ctx, &scene, (64, 64), spec(Some(&settings)));
    s.set_probe_view(Some(irradiant::technique::ProbeView::Volumes));
    s.set_camera(look(0.0));
    let mut before = volume_weights(&mut s);
    let mut origins = vec![s.technique_as::<Ddgi>().unwrap().volume().grid.origin];
    let (mut worst_jump, mut worst_sum) = (0.0f32, 0.0f32);
    let mut most = [0.0f32; 3];
    for step in 1..=60 {
        s.set_camera(look(0.05 * step as f32));
        let after = volume_weights(&mut s);
        origins.push(s.technique_as::<Ddgi>().unwrap().volume().grid.origin);
        for (a, b) in before.iter().zip(&after) {
            let (Some(a), Some(b)) = (a, b) else { continue };
            worst_sum = worst_sum.max((b[0] + b[1] + b[2] - 1.0).abs());
            for c in 0..3 {
                worst_jump = worst_jump.max((a[c] - b[c]).abs());
                most[c] = most[c].max(b[c]);
            }
        }
        before = after;
    }
    let steps = origins.windows(2).filter(|o| o[0] != o[1]).count();
    eprintln!(
        "{steps} window steps; largest change of a weight between frames {worst_jump:.3}, of a sum from 1 {worst_sum:.2e}; largest weights {most:?}"
    );
    assert!(steps >= 4, "the finest window stepped only {steps} times");
    assert!(
        most.iter().all(|&w| w > 0.5),
        "the view does not pass through all three cascades: {most:?}"
    );
    assert!(worst_sum < 1e-4, "the weights sum to 1 ± {worst_sum}");
    // 5 cm against a fade of 0.5 m: a tenth; a step that moved the blend by a cell would
    // change a weight by up to 1.
    assert!(
        worst_jump < 0.25,
        "a weight changed by {worst_jump} in one frame"
    );
}
