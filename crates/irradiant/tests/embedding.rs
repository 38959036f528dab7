//! Irradiant on a host's own device (issue 40): a context made from a device the host created
//! with the features and limits Irradiant states, a session rendering on it; a device created
//! without them refused by name.

mod common;

use common::*;
use irradiant::{GpuContext, Session, SessionSettings};

fn host_device(
    ctx: &GpuContext,
    features: wgpu::Features,
    limits: wgpu::Limits,
) -> (wgpu::Device, wgpu::Queue) {
    pollster::block_on(ctx.adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("host"),
        required_features: features,
        required_limits: limits,
        ..Default::default()
    }))
    .unwrap()
}

#[test]
fn a_session_renders_on_the_hosts_device() {
    let Some(ours) = gpu() else { return };
    let (features, limits) = GpuContext::requirements(&ours.adapter).unwrap();
    let (device, queue) = host_device(&ours, features, limits);
    let host =
        GpuContext::from_host(ours.instance.clone(), ours.adapter.clone(), device, queue).unwrap();
    assert_eq!(host.info.name, ours.info.name);
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut session = Session::new(
        std::sync::Arc::new(host),
        scene,
        SessionSettings {
            size: (32, 32),
            technique: spec(Some(&irradiant::ddgi::DdgiSettings::fast())),
            ..Default::default()
        },
    )
    .unwrap();
    for _ in 0..3 {
        session.render().unwrap();
    }
    let image = session.image().unwrap();
    let mean: f32 = image.pixels.iter().map(|p| p[0] + p[1] + p[2]).sum::<f32>();
    assert!(mean > 0.0, "the host's device rendered a black frame");
}

#[test]
fn a_host_device_without_what_irradiant_needs_is_refused_by_name() {
    let Some(ours) = gpu() else { return };
    let (features, limits) = GpuContext::requirements(&ours.adapter).unwrap();
    let (device, queue) = host_device(
        &ours,
        features - wgpu::Features::CLEAR_TEXTURE,
        limits.clone(),
    );
    let e = GpuContext::from_host(ours.instance.clone(), ours.adapter.clone(), device, queue)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("CLEAR_TEXTURE") && e.contains("requirements"),
        "{e}"
    );
    let (device, queue) = host_device(&ours, features, wgpu::Limits::default());
    let e = GpuContext::from_host(ours.instance.clone(), ours.adapter.clone(), device, queue)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("max_storage_buffers_per_shader_stage"), "{e}");
}

/// A texture of `format` at `size` filled with `bytes`, as a host would hand it.
fn host_texture(
    ctx: &GpuContext,
    size: (u32, u32),
    format: wgpu::TextureFormat,
    usage: wgpu::TextureUsages,
    bytes: &[u8],
) -> wgpu::Texture {
    let texture = irradiant_gpu::texture_2d(
        &ctx.device,
        "host/test",
        size,
        format,
        1,
        usage | wgpu::TextureUsages::COPY_DST,
    );
    let texel = format.block_copy_size(None).unwrap();
    ctx.queue.write_texture(
        texture.as_image_copy(),
        bytes,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(texel * size.0),
            rows_per_image: None,
        },
        texture.size(),
    );
    texture
}

fn halves(values: impl Iterator<Item = f32>) -> Vec<u8> {
    values
        .flat_map(|v| half::f16::from_f32(v).to_le_bytes())
        .collect()
}

fn read_rgba16(ctx: &GpuContext, texture: &wgpu::Texture) -> Vec<[f32; 4]> {
    let bytes = irradiant_gpu::read_texture(ctx, texture, 8).unwrap();
    bytes
        .chunks_exact(8)
        .map(|c| {
            std::array::from_fn(|i| half::f16::from_le_bytes([c[2 * i], c[2 * i + 1]]).to_f32())
        })
        .collect()
}

/// A host's G-buffer in other conventions than Irradiant's — reversed hardware depth, view-space
/// normals, the material in chosen channels, motion in UV — made from the traced G-buffer of the
/// same view: the host's frames' indirect light is the session's own, to f16 rounding.
#[test]
fn a_hosts_gbuffer_in_its_conventions_gives_the_sessions_own_light() {
    use irradiant::host::{
        DepthConvention, HostGBuffer, HostGi, MaterialChannels, MotionConvention, NormalEncoding,
    };
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (32, 32);
    let (w, h) = size;
    let technique = spec(Some(&irradiant::ddgi::DdgiSettings::fast()));
    let mut own = session(&ctx, &scene, size, technique.clone());
    for _ in 0..4 {
        own.render().unwrap();
    }
    // The traced G-buffer, read back, and the camera's frame.
    let frame = own.frame();
    let depth: Vec<f32> = bytemuck::pod_collect_to_vec(
        &irradiant_gpu::read_texture(&ctx, frame.resources.texture("gbuffer_depth"), 4).unwrap(),
    );
    let normal = read_rgba16(&ctx, frame.resources.texture("gbuffer_normal"));
    let albedo = read_rgba16(&ctx, frame.resources.texture("gbuffer_albedo"));
    let emission = read_rgba16(&ctx, frame.resources.texture("gbuffer_emission"));
    let motion: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(
        &irradiant_gpu::read_texture(&ctx, frame.resources.texture("gbuffer_motion"), 16).unwrap(),
    );
    let camera = irradiant::scene::types::GpuCamera::new(&scene.camera, w, h);
    let (forward, right, up) = (
        glam::Vec3::from(camera.forward),
        glam::Vec3::from(camera.right),
        glam::Vec3::from(camera.up),
    );
    let (near, far) = (0.05f32, 50.0f32);
    let reversed: Vec<u8> = (0..(w * h) as usize)
        .flat_map(|i| {
            let pixel = glam::Vec2::new((i as u32 % w) as f32 + 0.5, (i as u32 / w) as f32 + 0.5);
            let d = if depth[i] < 0.0 {
                0.0
            } else {
                let view_z = depth[i] * camera.ray_dir(pixel, w, h).dot(forward);
                (near * far / view_z - near) / (far - near)
            };
            d.to_le_bytes()
        })
        .collect();
    let view_normals = halves(normal.iter().flat_map(|n| {
        let n = irradiant::probes::octahedral::oct_decode(glam::Vec2::new(n[0], n[1]));
        [n.dot(right), n.dot(up), -n.dot(forward), 0.0]
    }));
    let usage = wgpu::TextureUsages::TEXTURE_BINDING;
    let f16 = wgpu::TextureFormat::Rgba16Float;
    let depth_texture = host_texture(&ctx, size, wgpu::TextureFormat::R32Float, usage, &reversed);
    let normal_texture = host_texture(&ctx, size, f16, usage, &view_normals);
    let base = host_texture(
        &ctx,
        size,
        f16,
        usage,
        &halves(albedo.iter().flat_map(|a| [a[0], a[1], a[2], 1.0])),
    );
    // specular in r, roughness in g, metallic in b (the frame keeps metallic in emission.a
    // and the specular scale in motion.z).
    let material = host_texture(
        &ctx,
        size,
        f16,
        usage,
        &halves(
            (0..(w * h) as usize).flat_map(|i| [motion[i][2], albedo[i][3], emission[i][3], 0.0]),
        ),
    );
    let emitted = host_texture(
        &ctx,
        size,
        f16,
        usage,
        &halves(emission.iter().flat_map(|e| [e[0], e[1], e[2], 1.0])),
    );
    let uv_motion: Vec<u8> = bytemuck::cast_slice::<f32, u8>(
        &motion
            .iter()
            .flat_map(|m| [m[0] / w as f32, m[1] / h as f32, 0.0, 0.0])
            .collect::<Vec<f32>>(),
    )
    .to_vec();
    let motion_texture = host_texture(
        &ctx,
        size,
        wgpu::TextureFormat::Rgba32Float,
        usage,
        &uv_motion,
    );
    let gbuffer = HostGBuffer {
        depth: &depth_texture,
        depth_convention: DepthConvention::HardwareReversed { near, far },
        normal: &normal_texture,
        normal_encoding: NormalEncoding::ViewSigned,
        base_colour: &base,
        material: Some(&material),
        material_channels: MaterialChannels {
            roughness: Some(1),
            metallic: Some(2),
            specular: Some(0),
        },
        emission: Some(&emitted),
        motion: Some((&motion_texture, MotionConvention::UvToPrevious)),
    };
    let mut gi = HostGi::new(
        ctx.clone(),
        scene.clone(),
        irradiant::SessionSettings {
            size,
            technique,
            ..Default::default()
        },
    )
    .unwrap();
    for _ in 0..4 {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        gi.record(&mut encoder, &scene.camera, &gbuffer).unwrap();
        ctx.queue.submit([encoder.finish()]);
    }
    let hosted = read_rgba16(&ctx, gi.indirect_texture());
    let reference = own.indirect().unwrap();
    let (mut difference, mut total) = (0.0f64, 0.0f64);
    for (a, b) in hosted.iter().zip(&reference.pixels) {
        for c in 0..3 {
            difference += (a[c] - b[c]).abs() as f64;
            total += b[c].abs() as f64;
        }
    }
    let relative = difference / total;
    eprintln!("host G-buffer against the traced one: indirect differs by {relative:.5} (relative)");
    assert!(total > 0.0, "no indirect light");
    assert!(relative < 0.01, "{relative}");

    // Bad input: each refused with the channel and the fix.
    let small = host_texture(&ctx, (16, 16), f16, usage, &vec![0; 16 * 16 * 8]);
    let unbound = host_texture(
        &ctx,
        size,
        f16,
        wgpu::TextureUsages::COPY_SRC,
        &view_normals,
    );
    let integer = host_texture(
        &ctx,
        size,
        wgpu::TextureFormat::Rgba8Uint,
        usage,
        &vec![0; (w * h * 4) as usize],
    );
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    for (bad, expected) in [
        (
            HostGBuffer {
                normal: &small,
                ..gbuffer
            },
            "gbuffer.normal is 16×16",
        ),
        (
            HostGBuffer {
                emission: Some(&unbound),
                ..gbuffer
            },
            "gbuffer.emission was created without TEXTURE_BINDING",
        ),
        (
            HostGBuffer {
                base_colour: &integer,
                ..gbuffer
            },
            "gbuffer.base_colour has format Rgba8Uint",
        ),
        (
            HostGBuffer {
                depth_convention: DepthConvention::Hardware {
                    near: 0.0,
                    far: 10.0,
                },
                ..gbuffer
            },
            "near plane above 0",
        ),
    ] {
        let e = gi
            .record(&mut encoder, &scene.camera, &bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains(expected), "{e}");
    }
    let mut lost = scene.camera.clone();
    lost.position.x = f32::NAN;
    let e = gi
        .record(&mut encoder, &lost, &gbuffer)
        .unwrap_err()
        .to_string();
    assert!(e.contains("camera"), "{e}");
}

/// DDGI at its fast preset on a host's device `ctx`, for `scene` at `size`.
fn fast_host_gi(
    ctx: std::sync::Arc<GpuContext>,
    scene: &irradiant_scene::Scene,
    size: (u32, u32),
) -> irradiant::host::HostGi {
    irradiant::host::HostGi::new(
        ctx,
        scene.clone(),
        irradiant::SessionSettings {
            size,
            technique: spec(Some(&irradiant::ddgi::DdgiSettings::fast())),
            ..Default::default()
        },
    )
    .unwrap()
}

/// A host's G-buffer of a grey wall facing the camera `distance` away (view-space depth and
/// normals): the least a host can hand.
struct Wall {
    depth: wgpu::Texture,
    normal: wgpu::Texture,
    grey: wgpu::Texture,
}

impl Wall {
    fn new(ctx: &GpuContext, size: (u32, u32), distance: f32) -> Self {
        let texels = (size.0 * size.1) as usize;
        let usage = wgpu::TextureUsages::TEXTURE_BINDING;
        let f16 = wgpu::TextureFormat::Rgba16Float;
        let depth = vec![distance; texels];
        Self {
            depth: host_texture(
                ctx,
                size,
                wgpu::TextureFormat::R32Float,
                usage,
                bytemuck::cast_slice(&depth),
            ),
            normal: host_texture(
                ctx,
                size,
                f16,
                usage,
                &halves((0..texels).flat_map(|_| [0.0, 0.0, 1.0, 0.0])),
            ),
            grey: host_texture(
                ctx,
                size,
                f16,
                usage,
                &halves((0..texels).flat_map(|_| [0.5, 0.5, 0.5, 1.0])),
            ),
        }
    }

    fn gbuffer(&self) -> irradiant::host::HostGBuffer<'_> {
        use irradiant::host::{DepthConvention, MaterialChannels, NormalEncoding};
        irradiant::host::HostGBuffer {
            depth: &self.depth,
            depth_convention: DepthConvention::ViewZ,
            normal: &self.normal,
            normal_encoding: NormalEncoding::ViewSigned,
            base_colour: &self.grey,
            material: None,
            material_channels: MaterialChannels::GLTF,
            emission: None,
            motion: None,
        }
    }
}

/// `compose_into` adds the indirect light into the host's HDR target, leaving what the host
/// drew there; a target of another size or a format that cannot be blended is refused.
#[test]
fn the_indirect_light_is_added_into_the_hosts_target() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (16, 16);
    let texels = (size.0 * size.1) as usize;
    let f16 = wgpu::TextureFormat::Rgba16Float;
    let wall = Wall::new(&ctx, size, 1.0);
    let gbuffer = wall.gbuffer();
    let mut gi = fast_host_gi(ctx.clone(), &scene, size);
    let target_usage = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
    let target = host_texture(
        &ctx,
        size,
        f16,
        target_usage,
        &halves((0..texels).flat_map(|_| [0.25, 0.25, 0.25, 1.0])),
    );
    for _ in 0..3 {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        gi.record(&mut encoder, &scene.camera, &gbuffer).unwrap();
        ctx.queue.submit([encoder.finish()]);
    }
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    gi.compose_into(&mut encoder, &target).unwrap();
    ctx.queue.submit([encoder.finish()]);
    let indirect = read_rgba16(&ctx, gi.indirect_texture());
    let composed = read_rgba16(&ctx, &target);
    assert!(
        indirect.iter().any(|p| p[0] > 0.0),
        "no indirect light on the wall"
    );
    for (c, i) in composed.iter().zip(&indirect) {
        for k in 0..3 {
            assert!(
                (c[k] - (0.25 + i[k])).abs() <= 2e-3 * (1.0 + i[k]),
                "{c:?} against 0.25 + {i:?}"
            );
        }
        assert_eq!(c[3], 1.0, "the target's alpha stays");
    }
    let small = host_texture(&ctx, (8, 8), f16, target_usage, &vec![0; 8 * 8 * 8]);
    let integer = host_texture(
        &ctx,
        size,
        wgpu::TextureFormat::Rgba8Uint,
        target_usage,
        &vec![0; texels * 4],
    );
    for (bad, expected) in [(&small, "is 8×8"), (&integer, "cannot be blended")] {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let e = gi.compose_into(&mut encoder, bad).unwrap_err().to_string();
        assert!(e.contains(expected), "{e}");
    }
}

/// Every registered technique runs on a host's G-buffer (the light fields with a small bake):
/// its indirect light is finite, and some technique's is not all black.
#[test]
fn every_registered_technique_runs_on_a_hosts_gbuffer() {
    use irradiant::host::HostGi;
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    // SSIL's pyramid needs an image of a few levels.
    let size = (64, 64);
    let wall = Wall::new(&ctx, size, 1.5);
    let gbuffer = wall.gbuffer();
    let small_bake: toml::Table = toml::from_str(
        "bake = { probe_counts = [2, 2, 2], resolution = 32, prefilter_resolution = 16, bounces = 1, emitter_samples = 2 }",
    )
    .unwrap();
    let mut lit = Vec::new();
    for name in irradiant::registry::names() {
        let mut technique = irradiant::TechniqueSpec::new(name, irradiant::Preset::Fast);
        if name.starts_with("lightfield") {
            technique.settings = small_bake.clone();
        }
        let cache = std::env::temp_dir().join(format!("irradiant-host-{}", std::process::id()));
        let mut gi = HostGi::new(
            ctx.clone(),
            scene.clone(),
            irradiant::SessionSettings {
                size,
                technique,
                cache_dir: Some(cache),
                ..Default::default()
            },
        )
        .unwrap_or_else(|e| panic!("{name}: {e}"));
        for _ in 0..2 {
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            gi.record(&mut encoder, &scene.camera, &gbuffer)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            ctx.queue.submit([encoder.finish()]);
        }
        let indirect = read_rgba16(&ctx, gi.indirect_texture());
        assert!(
            indirect.iter().all(|p| p.iter().all(|c| c.is_finite())),
            "{name}: light that is not finite"
        );
        if indirect.iter().any(|p| p[0] > 0.0) {
            lit.push(name);
        }
    }
    assert!(lit.contains(&"ddgi"), "lit: {lit:?}");
}

/// frame/direct runs for a host only once it asks (a host lights its own surfaces): the direct
/// light stays black before, and a wall inside the box is lit by its lamp after.
#[test]
fn the_direct_light_is_computed_for_a_host_only_when_asked() {
    use irradiant::host::HostGi;
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (8, 8);
    // The camera stands 3.5 m before the box's middle: a wall 0.1 m short of its back.
    let wall = Wall::new(&ctx, size, 4.4);
    let mut gi = fast_host_gi(ctx.clone(), &scene, size);
    let direct_sum = |gi: &mut HostGi| {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        gi.record(&mut encoder, &scene.camera, &wall.gbuffer())
            .unwrap();
        ctx.queue.submit([encoder.finish()]);
        let direct = gi.session().direct().unwrap();
        direct
            .pixels
            .iter()
            .map(|p| p[0] + p[1] + p[2])
            .sum::<f32>()
    };
    assert_eq!(direct_sum(&mut gi), 0.0, "frame/direct ran unasked");
    gi.set_direct_light(true);
    let lit = direct_sum(&mut gi);
    assert!(lit > 0.0, "the lamp does not light the wall: {lit}");
}

/// A technique that bakes (the light field) is built on a host's worker thread while the
/// host's frames go on, telling its progress; the finished `HostGi` is handed back and lights
/// the host's G-buffer.
#[test]
fn a_bake_runs_on_a_hosts_worker_thread_with_progress() {
    use irradiant::host::HostGi;
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (16, 16);
    let mut technique = irradiant::TechniqueSpec::new("lightfield", irradiant::Preset::Fast);
    technique.settings = toml::from_str(
        "bake = { probe_counts = [2, 2, 2], resolution = 32, prefilter_resolution = 16, bounces = 1, emitter_samples = 2 }",
    )
    .unwrap();
    let (sender, progress) = std::sync::mpsc::channel();
    let report = irradiant::technique::Progress(std::sync::Arc::new(
        move |what: &str, done: u32, all: u32| {
            let _ = sender.send((what.to_owned(), done, all));
        },
    ));
    let settings = irradiant::SessionSettings {
        size,
        technique,
        progress: Some(report),
        ..Default::default()
    };
    let worker = {
        let (ctx, scene) = (ctx.clone(), scene.clone());
        std::thread::spawn(move || HostGi::new(ctx, scene, settings))
    };
    // The host's loop: frames go on while the worker bakes (the session keeps the callback,
    // so the channel stays open: poll until the worker is done).
    let mut steps: Vec<(String, u32, u32)> = Vec::new();
    while !worker.is_finished() {
        steps.extend(progress.recv_timeout(std::time::Duration::from_millis(50)));
    }
    steps.extend(progress.try_iter());
    let mut gi = worker.join().unwrap().unwrap();
    let last = steps.last().expect("the bake told no progress");
    assert_eq!(last.1, last.2, "the bake ended at {last:?}");
    assert!(
        steps
            .windows(2)
            .all(|w| w[0].0 != w[1].0 || w[0].1 <= w[1].1),
        "{steps:?}"
    );
    let wall = Wall::new(&ctx, size, 4.4);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    gi.record(&mut encoder, &scene.camera, &wall.gbuffer())
        .unwrap();
    ctx.queue.submit([encoder.finish()]);
    let indirect = read_rgba16(&ctx, gi.indirect_texture());
    assert!(
        indirect.iter().any(|p| p[0] > 0.0),
        "the baked light field lit nothing"
    );
}

/// Drawing into Irradiant's G-buffer needs 44 bytes a sample of colour targets: a host's device
/// made with wgpu's default 32 is told which limit to ask for; one made with Irradiant's
/// requirements gets the five targets, in their formats.
#[test]
fn the_native_gbuffer_names_the_limit_it_needs() {
    let Some(ours) = gpu() else { return };
    let (features, limits) = GpuContext::requirements(&ours.adapter).unwrap();
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let gi_on = |limits: wgpu::Limits| {
        let (device, queue) = host_device(&ours, features, limits);
        let ctx = GpuContext::from_host(ours.instance.clone(), ours.adapter.clone(), device, queue);
        fast_host_gi(std::sync::Arc::new(ctx.unwrap()), &scene, (8, 8))
    };
    let narrow = gi_on(wgpu::Limits {
        max_color_attachment_bytes_per_sample: 32,
        ..limits.clone()
    });
    let e = narrow.native_gbuffer().err().unwrap().to_string();
    assert!(e.contains("max_color_attachment_bytes_per_sample"), "{e}");
    let wide = gi_on(limits);
    let native = wide.native_gbuffer().unwrap();
    assert_eq!(native.formats[0], wgpu::TextureFormat::R32Float);
    assert_eq!(native.formats[4], wgpu::TextureFormat::Rgba32Float);
}

/// A host's scene is checked as a loaded file is: a mesh whose indices run past its vertices
/// is refused by name, before anything reaches the GPU.
#[test]
fn a_hosts_mesh_with_indices_out_of_range_is_refused_by_name() {
    use irradiant::host::HostGi;
    let Some(ctx) = gpu() else { return };
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    scene.meshes[0].indices[4] = 100_000;
    let e = HostGi::new(ctx, scene, irradiant::SessionSettings::default())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("the host's scene") && e.contains("refers to vertex 100000"),
        "{e}"
    );
}
