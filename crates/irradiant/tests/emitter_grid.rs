//! The emitter grid (scene::emitter_grid) on the many-lights hall, 120 glowing tiles with walls
//! between them: the path tracer's noise at equal samples against picking emitters by power
//! alone (`GpuSceneSettings::emitter_grid` off), and the same mean.

mod common;

use common::*;
use irradiant::frame::Image;
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{GpuScene, GpuSceneSettings};

const SIZE: (u32, u32) = (48, 36);
const SEEDS: u32 = 8;

/// `SEEDS` path-traced images of 4 samples a pixel (two bounces), with or without the grid.
fn renders(ctx: &irradiant::GpuContext, scene: &irradiant_scene::Scene, grid: bool) -> Vec<Image> {
    let settings = GpuSceneSettings {
        emitter_grid: grid,
        ..GpuSceneSettings::default()
    };
    let gpu_scene = GpuScene::new(ctx, scene, &settings).unwrap();
    let mut tracer = PathTracer::new(ctx, &gpu_scene, SIZE.0, SIZE.1).unwrap();
    (0..SEEDS)
        .map(|seed| {
            let settings = PathTraceSettings {
                samples_per_pixel: 4,
                samples_per_dispatch: 4,
                max_bounces: 2,
                seed: 1 + seed,
                light_sampling: Default::default(),
                schedule: Default::default(),
            };
            tracer
                .render(ctx, &gpu_scene, &scene.camera, &settings, |_, _| {})
                .unwrap()
        })
        .collect()
}

/// Per pixel and channel, the variance across the images over the squared mean (+ 0.01, as
/// relative MSE keeps black pixels from dominating), averaged; and the images' mean luminance.
fn relative_variance(images: &[Image]) -> (f64, f64) {
    let n = images.len() as f64;
    let pixels = images[0].pixels.len();
    let (mut sum, mut luminance) = (0.0, 0.0);
    for i in 0..pixels {
        for c in 0..3 {
            let values: Vec<f64> = images.iter().map(|im| im.pixels[i][c] as f64).collect();
            let mean = values.iter().sum::<f64>() / n;
            let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
            sum += variance / (mean * mean + 0.01);
        }
        luminance += images
            .iter()
            .map(|im| pixel_luminance(&im.pixels[i]))
            .sum::<f64>()
            / n;
    }
    (sum / (3 * pixels) as f64, luminance / pixels as f64)
}

/// The grid's picks find the tiles that light each point: the path tracer's variance at equal
/// samples falls well under power alone's (1.87× lower on lavapipe), with the same mean. Against
/// the path tracer before resampling and the grid (one power-picked sample), 4.9× lower
/// (docs/pathtrace.md, "Cost").
#[test]
fn the_emitter_grid_lowers_the_path_tracers_noise_under_many_emitters() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("many-lights").unwrap().scene;
    let (by_power, power_mean) = relative_variance(&renders(&ctx, &scene, false));
    let (by_grid, grid_mean) = relative_variance(&renders(&ctx, &scene, true));
    eprintln!(
        "relative variance: power alone {by_power:.4}, grid {by_grid:.4} ({:.2}× lower); \
         mean luminance {power_mean:.4} and {grid_mean:.4}",
        by_power / by_grid
    );
    assert!(
        by_grid * 1.5 <= by_power,
        "the grid's relative variance {by_grid} is not 1.5× under power alone's {by_power}"
    );
    assert!(
        (grid_mean / power_mean - 1.0).abs() < 0.03,
        "the grid's mean {grid_mean} is not power alone's {power_mean}"
    );
}
