//! `compare --over-time`: each technique follows the scene's animation; per frame the flicker
//! (mean change of luminance from the frame before), every --every frames the FLIP against a
//! path-traced reference of that frame, and the lag after a light switches.

use irradiant::frame::{Image, LightingChange, SceneChange};
use irradiant::{GpuScene, GpuSceneSettings};
use irradiant_eval::report::TimeSeries;

use irradiant::Session;
use irradiant::ddgi::Ddgi;
use irradiant::ssil::SsilDdgi;

use crate::CliError;
use crate::compare::Setup;
use crate::reference::reference;

pub fn follow_animation(setup: &Setup) -> Result<Vec<TimeSeries>, CliError> {
    let args = setup.args;
    let (width, height) = args.size;
    let scene = setup.scene;
    let ctx = &setup.ctx;
    let time = |i: u32| i as f32 / args.fps;
    let poses: Vec<irradiant_scene::Pose> = (0..args.over_time)
        .map(|i| scene.pose_at(time(i)))
        .collect();
    let change_frame = (1..poses.len())
        .find(|&i| SceneChange::between(&poses[i - 1], &poses[i]).lighting == LightingChange::Large)
        .map(|i| i as u32);
    // The references of the sampled frames, each cached under its own pose.
    let mut reference_scene = GpuScene::new(ctx, scene, &GpuSceneSettings::default())?;
    let settings = setup.reference_settings(args.sequence_spp);
    let mut references = Vec::new();
    for i in (0..args.over_time).step_by(args.every.max(1) as usize) {
        reference_scene.update(ctx, &poses[i as usize]);
        let (image, _) = reference(
            ctx,
            &reference_scene,
            scene,
            &poses[i as usize],
            &args.scene,
            args.size,
            &settings,
            args.cache.as_deref(),
        )?;
        references.push((i, image.to_srgb8(1.0, true)));
    }
    drop(reference_scene);
    let mut series = Vec::new();
    for (label, spec) in setup.specs {
        let mut session = setup.session(spec, 0.0)?;
        let (mut error, mut flicker, mut window_steps) = (Vec::new(), Vec::new(), Vec::new());
        let mut previous: Option<Image> = None;
        for i in 0..args.over_time {
            session.seek(time(i));
            let steps_before = steps_taken(&session);
            session.render()?;
            if steps_taken(&session) > steps_before {
                window_steps.push(i);
            }
            let image = session.image()?;
            if let Some(p) = &previous {
                let lum = |c: &[f32; 3]| (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]) as f64;
                let change = image
                    .pixels
                    .iter()
                    .zip(&p.pixels)
                    .map(|(a, b)| (lum(a) - lum(b)).abs())
                    .sum::<f64>()
                    / image.pixels.len() as f64;
                flicker.push((i, change));
            }
            if let Some((_, reference)) = references.iter().find(|(f, _)| *f == i) {
                let flip =
                    irradiant_eval::flip(reference, &image.to_srgb8(1.0, true), width, height)
                        .map_err(|e| CliError::Usage(e.to_string()))?;
                error.push((i, flip.mean));
            }
            previous = Some(image);
        }
        let lag_bound = args.lag_bound;
        let lag_frames = change_frame.and_then(|c| {
            error
                .iter()
                .find(|(f, e)| *f >= c && *e <= lag_bound)
                .map(|(f, _)| f - c)
        });
        series.push(TimeSeries {
            technique: label.clone(),
            error,
            flicker,
            change_frame,
            lag_frames,
            lag_bound,
            window_steps,
        });
    }
    Ok(series)
}

/// The probe windows' steps so far, where the technique's probes follow (DDGI's, alone or in
/// `ssil+ddgi`); 0 for every other technique.
fn steps_taken(session: &Session) -> u64 {
    session
        .technique_as::<Ddgi>()
        .or_else(|| session.technique_as::<SsilDdgi>().map(|h| &h.ddgi))
        .map_or(0, Ddgi::window_steps)
}
