//! Shared by the GPU tests: one adapter, or a loud skip (never a skip when CI=true).

#![allow(dead_code)]

use std::sync::Arc;

use irradiant::{AdapterChoice, GpuContext};

/// The test adapter: a context of the caller's own (tests that break theirs — destroy the
/// device, starve it of memory — touch no other test's). Without one, tests skip with a message on a developer machine and fail
/// under CI (CI=true), where a missing driver must not pass as green.
pub fn gpu() -> Option<Arc<GpuContext>> {
    match GpuContext::new(&AdapterChoice::from_env()) {
        Ok(ctx) => Some(Arc::new(ctx)),
        Err(e) if std::env::var("CI").is_ok_and(|v| v == "true") => {
            panic!("CI=true and no usable GPU adapter: {e}")
        }
        Err(e) => {
            eprintln!("SKIPPED: no usable GPU adapter ({e})");
            None
        }
    }
}

/// The shared scenes beside the checkout (../shared/scenes).
pub fn shared_scenes() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes")
}

pub fn repo_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

use irradiant::ddgi::DdgiSettings;
use irradiant::frame::{FrameSettings, GBufferSample, Image};
use irradiant::pathtrace::{PathTraceSettings, PathTracer};
use irradiant::{GpuScene, Session, SessionSettings, TechniqueSpec};
use irradiant_scene::{Region, Scene};

/// What a real-time render leaves behind for measuring.
pub struct FrameResult {
    pub total: Image,
    pub direct: Image,
    pub indirect: Image,
    pub gbuffer: Vec<GBufferSample>,
}

/// The technique spec of DDGI with these settings, or direct light only for `None`.
pub fn spec(settings: Option<&DdgiSettings>) -> TechniqueSpec {
    match settings {
        Some(s) => TechniqueSpec::with_settings("ddgi", s),
        None => TechniqueSpec::new("none", irradiant::Preset::Balanced),
    }
}

/// A session of `scene` at `size` with a technique. TAA is off: these tests compare the
/// frame's channels (direct, indirect, emission) pixel by pixel with each other and with the
/// path tracer, which needs every channel sampled at the same point of the pixel; TAA's own
/// tests (taa.rs) turn it on.
pub fn session(
    ctx: &Arc<GpuContext>,
    scene: &Scene,
    size: (u32, u32),
    technique: TechniqueSpec,
) -> Session {
    session_with(
        ctx,
        scene,
        size,
        technique,
        FrameSettings::default().without_taa(),
    )
}

pub fn session_with(
    ctx: &Arc<GpuContext>,
    scene: &Scene,
    size: (u32, u32),
    technique: TechniqueSpec,
    frame: FrameSettings,
) -> Session {
    Session::new(
        ctx.clone(),
        scene.clone(),
        SessionSettings {
            size,
            frame,
            technique,
            ..Default::default()
        },
    )
    .unwrap()
}

/// Renders `frames` frames of a static scene with DDGI (or direct light only, for `None`).
pub fn render_frames(
    ctx: &Arc<GpuContext>,
    scene: &Scene,
    size: (u32, u32),
    settings: Option<&DdgiSettings>,
    frames: u32,
) -> FrameResult {
    let mut session = session(ctx, scene, size, spec(settings));
    for _ in 0..frames {
        session.render().unwrap();
    }
    frame_result(&session)
}

/// The last frame's images and G-buffer.
pub fn frame_result(session: &Session) -> FrameResult {
    FrameResult {
        total: session.image().unwrap(),
        direct: session.direct().unwrap(),
        indirect: session.indirect().unwrap(),
        gbuffer: session.gbuffer().unwrap(),
    }
}

pub fn path_trace(ctx: &GpuContext, scene: &Scene, size: (u32, u32), spp: u32) -> Image {
    path_trace_view(ctx, scene, &scene.camera, size, spp, 64)
}

/// The path tracer's image of `scene` from `camera`, following at most `max_bounces` bounces
/// (1: direct light only).
pub fn path_trace_view(
    ctx: &GpuContext,
    scene: &Scene,
    camera: &irradiant_scene::Camera,
    size: (u32, u32),
    spp: u32,
    max_bounces: u32,
) -> Image {
    let settings = PathTraceSettings {
        samples_per_pixel: spp,
        samples_per_dispatch: 32,
        max_bounces,
        seed: 7,
        light_sampling: Default::default(),
        schedule: Default::default(),
    };
    // Several tests, in several test binaries, take the same reference: once one has rendered
    // it, the others read it (lossless: 32-bit floats) from the cache under target/tmp, keyed on
    // everything that shapes it, on the sources that draw it and on the adapter.
    let entry = renderer_sources_hash().map(|sources| {
        let build = format!(
            "{sources:016x} {} {} {} {camera:?}",
            ctx.info.name, ctx.info.backend, ctx.info.driver_info
        );
        irradiant::pathtrace::reference_cache::ReferenceEntry::new(
            &std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("test-references"),
            scene,
            &scene.pose_at(0.0),
            size,
            &settings,
            &build,
        )
    });
    if let Some(image) = entry.as_ref().and_then(|e| e.load(size)) {
        return image;
    }
    let gpu_scene = GpuScene::new(ctx, scene, &Default::default()).unwrap();
    let mut tracer = PathTracer::new(ctx, &gpu_scene, size.0, size.1).unwrap();
    let image = tracer
        .render(ctx, &gpu_scene, camera, &settings, |_, _| {})
        .unwrap();
    if let Some(entry) = entry {
        entry.store(&image);
    }
    image
}

/// A hash of the sources a reference is drawn by (the Rust and WGSL of irradiant and the crates
/// under it, and Cargo.lock's versions of wgpu and the rest), read as the tests run: a changed
/// path tracer, tree or scene loader never reads a reference an older one cached. `None` (no
/// caching) where a source is newer than this test binary, which was then built from other
/// sources than those the hash reads.
fn renderer_sources_hash() -> Option<u64> {
    use std::hash::{Hash, Hasher};
    use std::time::SystemTime;
    static HASH: std::sync::OnceLock<Option<u64>> = std::sync::OnceLock::new();
    *HASH.get_or_init(|| {
        fn feed(path: &std::path::Path, h: &mut impl Hasher, newest: &mut SystemTime) {
            if path.is_dir() {
                let mut entries: Vec<_> = std::fs::read_dir(path)
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
                    .map(|e| e.unwrap().path())
                    .collect();
                entries.sort();
                for entry in entries {
                    feed(&entry, h, newest);
                }
            } else {
                path.hash(h);
                std::fs::read(path).unwrap().hash(h);
                let modified = std::fs::metadata(path).and_then(|m| m.modified()).unwrap();
                *newest = (*newest).max(modified);
            }
        }
        let crates = repo_root().join("crates");
        let mut h = std::collections::hash_map::DefaultHasher::new();
        let mut newest = SystemTime::UNIX_EPOCH;
        feed(&repo_root().join("Cargo.lock"), &mut h, &mut newest);
        for name in [
            "irradiant",
            "irradiant-bvh",
            "irradiant-gpu",
            "irradiant-scene",
        ] {
            feed(&crates.join(name).join("src"), &mut h, &mut newest);
        }
        let built = std::env::current_exe()
            .and_then(|exe| std::fs::metadata(exe)?.modified())
            .ok()?;
        (newest <= built).then(|| h.finish())
    })
}

/// Mean FLIP of `test` against `reference`, both tonemapped to sRGB as reports show them.
pub fn flip_mean(reference: &Image, test: &Image) -> f64 {
    irradiant_eval::flip(
        &reference.to_srgb8(1.0, true),
        &test.to_srgb8(1.0, true),
        reference.width,
        reference.height,
    )
    .unwrap()
    .mean as f64
}

/// Pixels whose visible surface lies inside the region.
pub fn region_mask(gbuffer: &[GBufferSample], region: &Region) -> Vec<bool> {
    gbuffer
        .iter()
        .map(|g| {
            let p = glam::Vec3::from(g.position);
            g.depth >= 0.0 && p.cmpge(region.min).all() && p.cmple(region.max).all()
        })
        .collect()
}

/// A linear-RGB pixel's luminance (Rec. 709 weights).
pub fn pixel_luminance(p: &[f32; 3]) -> f64 {
    0.2126 * p[0] as f64 + 0.7152 * p[1] as f64 + 0.0722 * p[2] as f64
}

/// Mean luminance of an image over the masked pixels.
pub fn masked_mean(image: &Image, mask: &[bool]) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    for (p, &m) in image.pixels.iter().zip(mask) {
        if m {
            sum += pixel_luminance(p);
            n += 1;
        }
    }
    assert!(n > 0, "the region covers no pixel");
    sum / n as f64
}

/// The path tracer's indirect light: its total minus the frame's direct light and emission.
pub fn path_traced_indirect(total: &Image, frame: &FrameResult) -> Image {
    let pixels = total
        .pixels
        .iter()
        .zip(&frame.direct.pixels)
        .zip(&frame.gbuffer)
        .map(|((t, d), g)| {
            [0, 1, 2].map(|c| {
                if g.depth < 0.0 {
                    0.0
                } else {
                    t[c] - d[c] - g.emission[c]
                }
            })
        })
        .collect();
    Image {
        width: total.width,
        height: total.height,
        pixels,
    }
}

/// Ratio of two images' mean luminance over each `block`×`block` tile of the masked pixels
/// (tiles at least half inside the mask): where a technique is locally too dark or too bright.
pub fn block_ratios(test: &Image, reference: &Image, mask: &[bool], block: u32) -> Vec<f64> {
    let mut ratios = Vec::new();
    for by in 0..test.height / block {
        for bx in 0..test.width / block {
            let (mut t, mut r, mut n) = (0.0, 0.0, 0);
            for y in by * block..(by + 1) * block {
                for x in bx * block..(bx + 1) * block {
                    let i = (y * test.width + x) as usize;
                    if mask[i] {
                        t += pixel_luminance(&test.pixels[i]);
                        r += pixel_luminance(&reference.pixels[i]);
                        n += 1;
                    }
                }
            }
            if n * 2 >= (block * block) as usize && r > 1e-4 {
                ratios.push(t / r);
            }
        }
    }
    ratios
}

/// The Cornell box with a red half-metre cube, the instance "block", centred at `at`.
pub fn cornell_with_block(at: glam::Vec3) -> Scene {
    use glam::{Mat4, Vec3};
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    let block = scene.meshes.len() as u32;
    let mut mesh = irradiant_scene::Mesh {
        name: "block".into(),
        ..Default::default()
    };
    let red = scene
        .materials
        .iter()
        .position(|m| m.name == "red")
        .unwrap() as u32;
    let corners: Vec<Vec3> = (0..8)
        .map(|c| Vec3::new((c & 1) as f32, ((c >> 1) & 1) as f32, ((c >> 2) & 1) as f32) - 0.5)
        .collect();
    let order = [0, 1, 3, 2, 4, 5, 7, 6];
    for face in [
        [0, 1, 2, 3],
        [5, 4, 7, 6],
        [4, 0, 3, 7],
        [1, 5, 6, 2],
        [3, 2, 6, 7],
        [4, 5, 1, 0],
    ] {
        let base = mesh.positions.len() as u32;
        mesh.positions
            .extend(face.iter().map(|&k| corners[order[k]] * 0.5));
        mesh.indices
            .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
        mesh.triangle_materials.extend([red, red]);
    }
    scene.meshes.push(mesh);
    scene.instances.push(irradiant_scene::Instance {
        name: "block".into(),
        mesh: block,
        transform: Mat4::from_translation(at),
    });
    scene
}

/// Two-rooms with nine probes across instead of ten: the middle layer of probes stands on the
/// dividing wall's middle plane (x = 0), where every probe outside the door has two opposite
/// exits, one into each room.
pub fn two_rooms_with_probes_in_the_wall() -> Scene {
    let mut scene = irradiant_scene::load("two-rooms").unwrap().scene;
    scene.probe_volumes[0].counts[0] = 9;
    scene
}

/// Built-in scene `name` with its probe volume's box set to `lo`–`hi`, the room's inside: a
/// volume fitted to a room's walls, as a user who gives the room's bounds places it, puts its
/// outer layers of probes in the walls' planes.
pub fn fitted_to_the_walls(name: &str, lo: glam::Vec3, hi: glam::Vec3) -> Scene {
    let mut scene = irradiant_scene::load(name).unwrap().scene;
    scene.probe_volumes[0].min = lo;
    scene.probe_volumes[0].max = hi;
    scene
}

/// One mip level of a frame texture (rgba32float or rgba16float) as rgba f32 texels.
pub fn read_level(
    ctx: &GpuContext,
    frame: &irradiant::frame::Frame,
    name: &str,
    level: u32,
) -> Vec<[f32; 4]> {
    use irradiant_gpu::read_texture_level;
    let texture = frame.resources.texture(name);
    if texture.format() == irradiant_gpu::wgpu::TextureFormat::Rgba32Float {
        return bytemuck::pod_collect_to_vec(&read_texture_level(ctx, texture, level, 16).unwrap());
    }
    let halves: Vec<half::f16> =
        bytemuck::pod_collect_to_vec(&read_texture_level(ctx, texture, level, 8).unwrap());
    halves
        .chunks_exact(4)
        .map(|c| [c[0].to_f32(), c[1].to_f32(), c[2].to_f32(), c[3].to_f32()])
        .collect()
}

/// The built-in Cornell box's probes after relocation (DDGI's or the light field's, on the
/// scene's 4×4×4 grid): none past the grid's outer layers by more than a surface step, and the
/// probe in each box, 0.1 m above the box's bottom on the floor, gone out through a side and
/// on. DDGI's tall box probe once crossed that bottom, the closest
/// backface, into the void under the floor (lavapipe); the others ended off (docs/ddgi.md,
/// "A probe pushed out of the volume").
pub fn assert_cornell_box_probes_left_through_a_side(
    scene: &Scene,
    positions: &[glam::Vec3],
    on: impl Fn(usize) -> bool,
) {
    let volume = &scene.probe_volumes[0];
    assert_eq!(volume.counts, [4, 4, 4], "the Cornell box's own grid");
    let (lo, hi) = (volume.min, volume.max);
    let spacing = (hi - lo) / 3.0;
    let slack = irradiant::probes::constants::RELOCATION_SURFACE_STEP * spacing + 1e-4;
    for (probe, at) in positions.iter().enumerate() {
        assert!(
            at.cmpge(lo - slack).all() && at.cmple(hi + slack).all(),
            "probe {probe} relocated to {at}, outside the volume {lo} … {hi}"
        );
    }
    // Grid (1, 0, 1) in the tall box, (2, 0, 2) in the short one.
    for (probe, box_name) in [(1 + 16, "tall"), (2 + 2 * 16, "short")] {
        let coord = glam::Vec3::new((probe % 4) as f32, 0.0, (probe / 16) as f32);
        let moved = positions[probe] - (lo + coord * spacing);
        eprintln!("the {box_name} box's probe {probe}: moved by {moved}");
        assert!(on(probe), "the {box_name} box's probe {probe} turned off");
        assert!(
            moved.with_y(0.0).length() > 0.2,
            "the {box_name} box's probe {probe} should leave through a side: moved by {moved}"
        );
    }
}

/// The pixels of a `width`-wide image where `inside` holds at the pixel and its four
/// neighbours: a region without its edge, where a path tracer's pixels mix it with what lies
/// beside it.
pub fn interior(width: usize, height: usize, inside: impl Fn(usize) -> bool) -> Vec<bool> {
    (0..width * height)
        .map(|i| {
            let (x, y) = (i % width, i / width);
            (1..width.saturating_sub(1)).contains(&x)
                && (1..height.saturating_sub(1)).contains(&y)
                && [i, i - 1, i + 1, i - width, i + width]
                    .into_iter()
                    .all(&inside)
        })
        .collect()
}
