//! DDGI's probes saved and loaded (issue 40): a session started from a file a warmed-up one
//! saved lights its first frame as the warmed-up one lights its next, within the frame-to-frame
//! noise of converged probes; a file for other settings, a damaged one and a technique without
//! probes are refused by name.

mod common;

use common::*;
use irradiant::ddgi::DdgiSettings;
use irradiant::frame::Image;

fn settings() -> DdgiSettings {
    let mut s = DdgiSettings::fast();
    s.volume.rays_per_probe = 64;
    s
}

/// Mean absolute difference of two images' indirect light, over the mean of the first.
fn relative_difference(a: &Image, b: &Image) -> f64 {
    let sum = |f: &dyn Fn(usize) -> f32| (0..a.pixels.len()).map(|i| f(i) as f64).sum::<f64>();
    let difference = sum(&|i| {
        (0..3)
            .map(|c| (a.pixels[i][c] - b.pixels[i][c]).abs())
            .sum()
    });
    let mean = sum(&|i| a.pixels[i].iter().sum());
    difference / mean.max(1e-9)
}

#[test]
fn loaded_probes_light_the_first_frame_as_300_frames_of_warm_up_do() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (48, 48);
    let spec = spec(Some(&settings()));
    let file = std::env::temp_dir().join(format!("irradiant-probes-{}.bin", std::process::id()));
    let mut warm = session(&ctx, &scene, size, spec.clone());
    for _ in 0..300 {
        warm.render().unwrap();
    }
    warm.save_probes(&file).unwrap();
    let before = warm.indirect().unwrap();
    warm.render().unwrap();
    let warmed = warm.indirect().unwrap();
    let mut loaded = session(&ctx, &scene, size, spec.clone());
    loaded.load_probes(&file).unwrap();
    loaded.render().unwrap();
    let mut cold = session(&ctx, &scene, size, spec.clone());
    cold.render().unwrap();
    let noise = relative_difference(&warmed, &before);
    let from_file = relative_difference(&warmed, &loaded.indirect().unwrap());
    let from_scratch = relative_difference(&warmed, &cold.indirect().unwrap());
    eprintln!(
        "indirect light against frame 301: frame 300 {noise:.4}, loaded {from_file:.4}, cold {from_scratch:.4}"
    );
    // The loaded frame's light is the warmed-up probes' plus one blend of new rays, whose
    // rotation follows the volume's frame count, which the file restores: frame 301 itself
    // (on lavapipe to the bit), within the frame-to-frame noise of converged probes wherever
    // it is not, and far from a cold start.
    assert!(
        from_file <= 2.0 * noise + 1e-3,
        "{from_file} against noise {noise}"
    );
    assert!(
        from_file * 5.0 < from_scratch,
        "{from_file} against a cold start's {from_scratch}"
    );

    // Other settings: refused, with the file and the reason.
    let mut other = settings();
    other.update.hysteresis = 0.9;
    let mut refused = session(
        &ctx,
        &scene,
        size,
        irradiant::TechniqueSpec::with_settings("ddgi", &other),
    );
    let e = refused.load_probes(&file).unwrap_err().to_string();
    assert!(
        e.contains(&file.display().to_string()) && e.contains("other settings"),
        "{e}"
    );
    // A damaged file: refused.
    let bytes = std::fs::read(&file).unwrap();
    std::fs::write(&file, &bytes[..bytes.len() / 2]).unwrap();
    let mut damaged = session(&ctx, &scene, size, spec);
    let e = damaged.load_probes(&file).unwrap_err().to_string();
    assert!(e.contains("truncated"), "{e}");
    // No probes to load.
    let mut none = session(&ctx, &scene, size, common::spec(None));
    let e = none.load_probes(&file).unwrap_err().to_string();
    assert!(e.contains("no DDGI probes"), "{e}");
    let _ = std::fs::remove_file(&file);
}

/// A file saved where ddgi/trace's lanes fetch their rays (the box is one wide tree, and one
/// workgroup a dispatch makes every run longer than 64 rays) loads into a session whose scene
/// leaves room for a host's instances, where each thread traces a ray: the list headers' trace
/// dispatch is rebuilt for the loading session's kernels, so its first frame is the saving
/// session's next (every probe ray traced), not one with part of the rays left out.
#[test]
fn probes_saved_by_fetching_lanes_load_where_each_thread_traces_a_ray() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (32, 32);
    let mut fetching = settings();
    fetching.speed.fetch_workgroups = 1;
    let spec = spec(Some(&fetching));
    let file = std::env::temp_dir().join(format!(
        "irradiant-probes-fetching-{}.bin",
        std::process::id()
    ));
    let mut warm = session(&ctx, &scene, size, spec.clone());
    for _ in 0..40 {
        warm.render().unwrap();
    }
    warm.save_probes(&file).unwrap();
    let before = warm.indirect().unwrap();
    warm.render().unwrap();
    let warmed = warm.indirect().unwrap();
    let mut loaded = irradiant::Session::new(
        ctx.clone(),
        scene.clone(),
        irradiant::SessionSettings {
            size,
            frame: irradiant::frame::FrameSettings::default().without_taa(),
            technique: spec,
            scene: irradiant::GpuSceneSettings {
                instance_headroom: 1,
                ..Default::default()
            },
            ..Default::default()
        },
    )
    .unwrap();
    loaded.load_probes(&file).unwrap();
    loaded.render().unwrap();
    let _ = std::fs::remove_file(&file);
    let noise = relative_difference(&warmed, &before);
    let from_file = relative_difference(&warmed, &loaded.indirect().unwrap());
    eprintln!("against the next frame: the frame before {noise:.5}, loaded {from_file:.5}");
    assert!(
        from_file <= 0.5 * noise + 1e-4,
        "{from_file} against noise {noise}"
    );
}
