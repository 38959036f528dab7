//! Direct light from many small emitters by reservoir resampling (frame/direct,
//! frame/direct_reuse, shaders/resampling.wgsl) on the many-lights hall (120 glowing tiles,
//! walls between them): the mean over frames is the path tracer's direct light, picks along
//! each pixel's sequence lower a still view's error, reservoirs carried through a moving view
//! lower its error, so do the neighbours' in a single frame, and both together stay clean
//! through a long moving view.

mod common;

use common::*;
use irradiant::frame::{FrameSettings, Image, ResamplingSettings};
use irradiant_scene::{Camera, Scene};

const SIZE: (u32, u32) = (48, 36);

/// The path tracer limited to direct light (emission seen, and one bounce off it).
fn direct_reference(
    ctx: &irradiant::GpuContext,
    scene: &Scene,
    camera: &Camera,
    spp: u32,
) -> Image {
    path_trace_view(ctx, scene, camera, SIZE, spp, 1)
}

/// Direct light only along `path` (a frame a camera), pixel centres (no TAA), as the path
/// tracer's pixels are compared one by one: the last frame, and which of its pixels are lit
/// surfaces away from any emitter. The reference averages a pixel's footprint, which catches
/// far tiles smaller than a pixel that a pixel centre misses: a G-buffer of eight times the
/// resolution finds them, and a pixel within one of a glowing subpixel is left out.
fn direct_light(
    ctx: &std::sync::Arc<irradiant::GpuContext>,
    scene: &Scene,
    resampling: ResamplingSettings,
    path: &[Camera],
) -> (Image, Vec<bool>) {
    let frame = FrameSettings {
        resampling,
        ..FrameSettings::default().without_taa()
    };
    let mut session = session_with(ctx, scene, SIZE, spec(None), frame.clone());
    for camera in path {
        session.set_camera(camera.clone());
        session.render().unwrap();
    }
    const FINE: u32 = 8;
    let mut fine = session_with(
        ctx,
        scene,
        (SIZE.0 * FINE, SIZE.1 * FINE),
        spec(None),
        frame,
    );
    fine.set_camera(path.last().unwrap().clone());
    fine.render().unwrap();
    let fine = fine.gbuffer().unwrap();
    let mut glows = vec![false; (SIZE.0 * SIZE.1) as usize];
    for (i, g) in fine.iter().enumerate() {
        let (x, y) = (
            i as u32 % (SIZE.0 * FINE) / FINE,
            i as u32 / (SIZE.0 * FINE) / FINE,
        );
        glows[(y * SIZE.0 + x) as usize] |= g.emission != [0.0; 3];
    }
    let gbuffer = session.gbuffer().unwrap();
    let near_glow = |x: i64, y: i64| {
        (-1..=1).any(|dy| {
            (-1..=1).any(|dx| {
                let (x, y) = (x + dx, y + dy);
                (0..SIZE.0 as i64).contains(&x)
                    && (0..SIZE.1 as i64).contains(&y)
                    && glows[(y * SIZE.0 as i64 + x) as usize]
            })
        })
    };
    let lit_surface = (0..SIZE.1 as i64)
        .flat_map(|y| (0..SIZE.0 as i64).map(move |x| (x, y)))
        .map(|(x, y)| gbuffer[(y * SIZE.0 as i64 + x) as usize].depth >= 0.0 && !near_glow(x, y))
        .collect();
    (session.image().unwrap(), lit_surface)
}

fn luminance_sum(image: &Image) -> f64 {
    let [r, g, b] = image.mean();
    0.2126 * r + 0.7152 * g + 0.0722 * b
}

/// The scene's camera moved `centimetres` sideways (along x, looking the same way).
fn sideways(scene: &Scene, centimetres: u32) -> Camera {
    let mut camera = scene.camera.clone();
    let step = glam::Vec3::new(0.01 * centimetres as f32, 0.0, 0.0);
    camera.position += step;
    camera.target += step;
    camera
}

/// The brightest pixel's luminance in `expected`, and each pixel's luminance difference
/// between the two images.
fn luminance_differences(expected: &Image, test: &Image) -> (f64, Vec<f64>) {
    let brightest = expected
        .pixels
        .iter()
        .map(pixel_luminance)
        .fold(0.0f64, f64::max);
    let differences = (expected.pixels.iter().zip(&test.pixels))
        .map(|(a, b)| (pixel_luminance(a) - pixel_luminance(b)).abs())
        .collect();
    (brightest, differences)
}

/// Mean luminance over the pixels of `mask`.
fn masked_luminance(image: &Image, mask: &[bool]) -> f64 {
    let lit = (image.pixels.iter().zip(mask)).filter(|(_, m)| **m);
    let (sum, count) = lit.fold((0.0, 0), |(s, n), (p, _)| (s + pixel_luminance(p), n + 1));
    sum / count.max(1) as f64
}

/// Relative MSE over the pixels of `mask`.
fn relative_mse(reference: &Image, (test, mask): &(Image, Vec<bool>)) -> f64 {
    let keep = |image: &Image| -> Vec<[f32; 3]> {
        (image.pixels.iter().zip(mask))
            .filter(|(_, m)| **m)
            .map(|(p, _)| *p)
            .collect()
    };
    irradiant_eval::relative_mse(&keep(reference), &keep(test)).unwrap()
}

/// The running mean of resampled frames (reservoirs, neighbours' reuse with its shadow rays)
/// has the path tracer's mean, over the image and block by block: reuse across pixels adds no
/// bias that a 6×6 block of a hall's walls and floor would show (blocks by the tiles' edges
/// left out).
#[test]
fn resampled_direct_light_converges_to_the_path_tracers() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("many-lights").unwrap().scene;
    let reference = direct_reference(&ctx, &scene, &scene.camera, 1024);
    let still = vec![scene.camera.clone(); 64];
    let (resampled, mask) = direct_light(&ctx, &scene, ResamplingSettings::default(), &still);
    let (m_ref, m_res) = (luminance_sum(&reference), luminance_sum(&resampled));
    // Blocks of 6×6 lit pixels that the reference sees at a tenth of the image's mean or more
    // (darker ones are a few noisy samples of light through a gap).
    let mut blocks = Vec::new();
    for by in 0..SIZE.1 / 6 {
        for bx in 0..SIZE.0 / 6 {
            let (mut t, mut r, mut n) = (0.0, 0.0, 0);
            for y in by * 6..by * 6 + 6 {
                for x in bx * 6..bx * 6 + 6 {
                    let i = (y * SIZE.0 + x) as usize;
                    if mask[i] {
                        t += pixel_luminance(&resampled.pixels[i]);
                        r += pixel_luminance(&reference.pixels[i]);
                        n += 1;
                    }
                }
            }
            if n == 36 && r / 36.0 > 0.1 * m_ref {
                blocks.push(t / r);
            }
        }
    }
    let worst = blocks
        .iter()
        .map(|r| (r - 1.0).abs())
        .fold(0.0f64, f64::max);
    let median = {
        let mut sorted = blocks.clone();
        sorted.sort_by(f64::total_cmp);
        sorted[sorted.len() / 2]
    };
    eprintln!(
        "resampled direct light over 64 frames: mean {m_res:.5} against the path tracer's {m_ref:.5} ({:+.2} %); {} 6×6 blocks: median ratio {median:.3}, worst {worst:.3} off",
        100.0 * (m_res / m_ref - 1.0),
        blocks.len()
    );
    assert!(
        (m_res / m_ref - 1.0).abs() < 0.03,
        "resampled mean {m_res} against the path tracer's {m_ref}"
    );
    assert!(
        (median - 1.0).abs() < 0.03,
        "the median block reads {median} of the path tracer's"
    );
    assert!(worst < 0.15, "a block reads {worst} off the path tracer's");
}

/// A still view's candidates picked along each pixel's golden-ratio sequence through its frames
/// (`pick_sequence`) leave its running mean closer to the path tracer's than independent picks
/// every frame, after 16 and after 64 frames; the first frame, which shares reservoirs, is the
/// same either way.
#[test]
fn a_still_views_picks_along_a_sequence_lower_its_error() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("many-lights").unwrap().scene;
    let reference = direct_reference(&ctx, &scene, &scene.camera, 4096);
    let along = ResamplingSettings::default();
    let independent = ResamplingSettings {
        pick_sequence: false,
        ..along.clone()
    };
    for frames in [1, 16, 64] {
        let still = vec![scene.camera.clone(); frames];
        let apart = relative_mse(
            &reference,
            &direct_light(&ctx, &scene, independent.clone(), &still),
        );
        let walked = relative_mse(
            &reference,
            &direct_light(&ctx, &scene, along.clone(), &still),
        );
        eprintln!(
            "{frames} still frames, relative MSE: independent picks {apart:.5}, along the sequence {walked:.5}"
        );
        if frames == 1 {
            assert_eq!(
                walked, apart,
                "the first frame shares reservoirs and draws independently"
            );
        } else {
            assert!(
                walked < 0.9 * apart,
                "{frames} frames: along the sequence {walked} against independent {apart}"
            );
        }
    }
}

/// While the view moves (here a slow sideways drift, every frame a new camera, so no running
/// mean), last frame's reservoir where the surface was seen carries its candidates on: the
/// error of the drift's last frame falls well below the same frame without temporal reuse.
/// Seen on lavapipe: 0.0078 against 0.054 (neighbours' radius scaled to the image as below).
#[test]
fn reservoirs_carried_through_a_moving_view_lower_its_error() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("many-lights").unwrap().scene;
    let path: Vec<Camera> = (0..12).map(|i| sideways(&scene, i)).collect();
    let reference = direct_reference(&ctx, &scene, path.last().unwrap(), 1024);
    let temporal = ResamplingSettings {
        radius: 4.0,
        ..ResamplingSettings::default()
    };
    let without = ResamplingSettings {
        history: 0,
        ..temporal.clone()
    };
    let fresh = relative_mse(&reference, &direct_light(&ctx, &scene, without, &path));
    let carried = relative_mse(&reference, &direct_light(&ctx, &scene, temporal, &path));
    eprintln!(
        "the drift's last frame, relative MSE: without temporal reuse {fresh:.4}, with {carried:.4}"
    );
    assert!(
        carried < 0.4 * fresh,
        "temporal reuse {carried} against none {fresh}"
    );
}

/// In a single frame (the first after a cut: nothing to reuse from earlier frames) the
/// neighbours' reservoirs lower the error against the path tracer below the pixel's own
/// candidates alone. The radius is scaled to this small image (4 of its 36 rows, as 24 pixels
/// are of 240). Seen on lavapipe, both drawing `cut_candidates` in this frame: 0.0245 against
/// 0.0500 (the own candidates alone share no reservoir, so they pick along the sequence; 0.058
/// with independent picks).
#[test]
fn reuse_across_pixels_lowers_a_single_frames_error() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("many-lights").unwrap().scene;
    let reference = direct_reference(&ctx, &scene, &scene.camera, 1024);
    let reused = ResamplingSettings {
        radius: 4.0,
        ..ResamplingSettings::default()
    };
    let own_only = ResamplingSettings {
        neighbours: 0,
        cut_neighbours: 0,
        ..reused.clone()
    };
    let first = [scene.camera.clone()];
    let alone = relative_mse(&reference, &direct_light(&ctx, &scene, own_only, &first));
    let shared = relative_mse(&reference, &direct_light(&ctx, &scene, reused, &first));
    eprintln!("one frame's relative MSE: own candidates {alone:.4}, with neighbours {shared:.4}");
    assert!(
        shared < 0.7 * alone,
        "neighbours' reuse {shared} against own candidates {alone}"
    );
}

/// Through a long moving view (the camera stepping 1 cm sideways and back every frame, so that
/// each frame takes last frame's reservoirs through the motion vectors), the neighbours' reuse
/// adds little to reservoirs carried from frame to frame: over the last 100 of 200 frames the
/// error stays within 3× that of temporal reuse alone, and the unbiased reuse moves the mean
/// of lit surfaces by less than 0.3 % from temporal reuse alone's. Seen on lavapipe: temporal
/// alone 0.0027; with neighbours 0.0044, unbiased 0.0047; means 0.55 %, 1.15 % and 0.73 % under
/// the path tracer's (the pixel centres against its footprints, as a still view's). When the
/// neighbours' winner was next frame's history and weighed by 1/Z, the same read 0.0186 and
/// 0.0174, means 4.6 % and 4.4 % under: what one pixel overrated spread through its
/// neighbours' histories.
#[test]
fn reuse_across_pixels_and_frames_stays_clean_through_a_long_moving_view() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("many-lights").unwrap().scene;
    let poses: Vec<Camera> = (0..2).map(|i| sideways(&scene, i)).collect();
    let references: Vec<Image> = (poses.iter())
        .map(|camera| direct_reference(&ctx, &scene, camera, 1024))
        .collect();
    let masks: Vec<Vec<bool>> = (poses.iter())
        .map(|camera| {
            let still = ResamplingSettings::default();
            direct_light(&ctx, &scene, still, std::slice::from_ref(camera)).1
        })
        .collect();
    // The mean relative MSE of the last 100 frames, and the mean luminance of those at the
    // first pose against the path tracer's there (lit surfaces only, as the error).
    let moving = |resampling: ResamplingSettings| -> (f64, f64) {
        let frame = FrameSettings {
            resampling,
            ..FrameSettings::default().without_taa()
        };
        let mut session = session_with(&ctx, &scene, SIZE, spec(None), frame);
        let (mut error, mut mean) = (0.0, 0.0);
        for f in 0..200 {
            let pose = f % 2;
            session.set_camera(poses[pose].clone());
            session.render().unwrap();
            if f < 100 {
                continue;
            }
            let image = session.image().unwrap();
            error += relative_mse(&references[pose], &(image.clone(), masks[pose].clone())) / 100.0;
            if pose == 0 {
                mean += masked_luminance(&image, &masks[0]) / 50.0;
            }
        }
        (
            error,
            mean / masked_luminance(&references[0], &masks[0]) - 1.0,
        )
    };
    let neighbours = |unbiased| ResamplingSettings {
        radius: 4.0,
        unbiased,
        ..ResamplingSettings::default()
    };
    let (alone, alone_mean) = moving(ResamplingSettings {
        neighbours: 0,
        cut_neighbours: 0,
        ..ResamplingSettings::default()
    });
    let (with, with_mean) = moving(neighbours(false));
    let (unbiased, unbiased_mean) = moving(neighbours(true));
    eprintln!(
        "the last 100 of 200 moving frames, relative MSE: temporal reuse alone {alone:.4}, with neighbours {with:.4}, unbiased {unbiased:.4}; lit surfaces' mean against the path tracer's {:+.2} %, {:+.2} %, {:+.2} %",
        100.0 * alone_mean,
        100.0 * with_mean,
        100.0 * unbiased_mean
    );
    assert!(with < 3.0 * alone, "with neighbours {with} against {alone}");
    assert!(
        unbiased < 3.0 * alone,
        "unbiased with neighbours {unbiased} against {alone}"
    );
    assert!(
        (unbiased_mean - alone_mean).abs() < 0.003,
        "the unbiased reuse's mean is {unbiased_mean} off the path tracer's, temporal reuse alone's {alone_mean}"
    );
}

/// A camera cut (the view turned around after a few still frames, so that no surface it now
/// sees was seen before): every pixel finds no history and draws `cut_candidates` and takes
/// `cut_neighbours`, and the cut frame's error falls well below the same frame drawn with the
/// steady counts (16 candidates, 4 neighbours).
#[test]
fn a_cut_draws_more_where_no_history_is_found() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("many-lights").unwrap().scene;
    let mut turned = scene.camera.clone();
    turned.target = turned.position * 2.0 - turned.target;
    let mut path = vec![scene.camera.clone(); 4];
    path.push(turned.clone());
    let reference = direct_reference(&ctx, &scene, &turned, 1024);
    let cut = ResamplingSettings {
        radius: 4.0,
        ..ResamplingSettings::default()
    };
    let steady = ResamplingSettings {
        cut_candidates: cut.candidates,
        cut_neighbours: cut.neighbours,
        ..cut.clone()
    };
    let boosted = relative_mse(&reference, &direct_light(&ctx, &scene, cut, &path));
    let plain = relative_mse(&reference, &direct_light(&ctx, &scene, steady, &path));
    eprintln!("the cut frame's relative MSE: steady counts {plain:.4}, the cut's {boosted:.4}");
    assert!(
        boosted < 0.8 * plain,
        "the cut's counts {boosted} against the steady ones {plain}"
    );
}

/// In a still view's frames after its first, no pixel takes another's reservoir or last
/// frame's, so frame/direct_reuse draws each pixel's candidates and frame/direct does not run;
/// the first frame, a moved view's frame and every frame with unbiased reuse run both. The
/// one pass draws what the two would (the same random stream, the reservoir packed as
/// frame/direct's texture holds it): the direct light after several still frames is the
/// same with one-pass frames switched off (`Session::set_one_pass_direct`), pixel by pixel.
/// (On lavapipe to the bit; another driver compiling the two passes apart might flip a rare
/// pixel's choice, which the 1 % allowed covers.)
#[test]
fn a_still_views_later_frames_draw_the_candidates_in_one_pass() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("many-lights").unwrap().scene;
    let passes = |unbiased: bool| {
        let frame = FrameSettings {
            resampling: ResamplingSettings {
                unbiased,
                ..ResamplingSettings::default()
            },
            ..FrameSettings::default().without_taa()
        };
        let mut session = session_with(&ctx, &scene, SIZE, spec(None), frame);
        [
            scene.camera.clone(),
            scene.camera.clone(),
            sideways(&scene, 5),
        ]
        .into_iter()
        .map(|camera| {
            session.set_camera(camera);
            let timed = session.render_profiled().unwrap();
            let ran = |label: &str| timed.iter().any(|t| t.label == label);
            (ran("frame/direct"), ran("frame/direct_reuse"))
        })
        .collect::<Vec<_>>()
    };
    let plain = passes(false);
    if plain.iter().all(|&(direct, reuse)| !direct && !reuse) {
        eprintln!("skipped the passes' check: the adapter times no passes");
    } else {
        assert_eq!(
            plain,
            [(true, true), (false, true), (true, true)],
            "(frame/direct, frame/direct_reuse) ran in the first, the second still and a moved frame"
        );
        assert_eq!(passes(true), [(true, true); 3], "unbiased reuse");
    }

    let direct_after_still_frames = |one_pass: bool| {
        let mut session = session_with(&ctx, &scene, SIZE, spec(None), FrameSettings::default());
        session.set_one_pass_direct(one_pass);
        for _ in 0..6 {
            session.render().unwrap();
        }
        session.direct().unwrap()
    };
    let (one, two) = (
        direct_after_still_frames(true),
        direct_after_still_frames(false),
    );
    let (brightest, differences) = luminance_differences(&two, &one);
    let differing = differences
        .iter()
        .filter(|&&d| d > 1e-5 * brightest)
        .count();
    eprintln!("6 still frames in one pass against two: {differing} pixels differ");
    assert!(brightest > 0.0, "the tiles light nothing");
    assert!(
        differing * 100 <= one.pixels.len(),
        "{differing} of {} pixels differ between one pass and two",
        one.pixels.len()
    );
}

/// With room for emitters but none placed (the one glowing instance removed), a still view's
/// later frames leave frame/direct out all the same, and frame/direct_reuse keeps the punctual
/// lights' running mean: the direct light over several still frames (TAA's jitter moving each
/// frame's sample) is the one the scene keeps without that room.
#[test]
fn room_for_emitters_without_any_keeps_the_punctual_lights_mean() {
    let Some(ctx) = gpu() else { return };
    let plain = irradiant_scene::load("two-rooms").unwrap().scene;
    let mut with_room = plain.clone();
    with_room.materials.push(irradiant_scene::Material {
        name: "glow".into(),
        emission: glam::Vec3::splat(5.0),
        ..Default::default()
    });
    let glow = with_room.materials.len() as u32 - 1;
    with_room.meshes.push(irradiant_scene::Mesh {
        name: "glowing card".into(),
        positions: [(-0.2, 0.8), (0.2, 0.8), (0.2, 1.2), (-0.2, 1.2)]
            .map(|(x, y)| glam::Vec3::new(x, y, 0.5))
            .to_vec(),
        indices: vec![0, 1, 2, 0, 2, 3],
        triangle_materials: vec![glow; 2],
        ..Default::default()
    });
    with_room.instances.push(irradiant_scene::Instance {
        name: "glowing card".into(),
        mesh: with_room.meshes.len() as u32 - 1,
        transform: glam::Mat4::IDENTITY,
    });
    let frame = FrameSettings::default();
    let direct_after_still_frames = |scene: &Scene, remove_last: bool| {
        let mut session = session_with(&ctx, scene, SIZE, spec(None), frame.clone());
        if remove_last {
            let card = *session.instance_ids().last().unwrap();
            session.remove_instance(card).unwrap();
        }
        for _ in 0..6 {
            session.render().unwrap();
        }
        session.direct().unwrap()
    };
    let expected = direct_after_still_frames(&plain, false);
    let kept = direct_after_still_frames(&with_room, true);
    let (brightest, differences) = luminance_differences(&expected, &kept);
    let worst = differences.into_iter().fold(0.0f64, f64::max);
    eprintln!(
        "direct light after 6 still frames: largest difference {worst:.2e} of {brightest:.3}"
    );
    assert!(brightest > 0.0, "the point light lights nothing");
    assert!(
        worst <= 1e-4 * brightest,
        "with room for emitters but none, a pixel's direct light is {worst} off (brightest {brightest})"
    );
}
