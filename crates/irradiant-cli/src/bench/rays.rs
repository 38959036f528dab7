//! The rays `bench` times: primary rays through each pixel centre, and incoherent diffuse rays
//! from their hits (what path-tracing and probe rays look like).

use glam::{Vec2, Vec3};
use irradiant::GpuScene;
use irradiant::gpu_types::{GpuCamera, GpuRay};
use rand::{Rng, SeedableRng, rngs::StdRng};

/// One ray through each pixel centre.
pub fn primary_rays(scene: &irradiant_scene::Scene, (w, h): (u32, u32)) -> Vec<GpuRay> {
    let cam = GpuCamera::new(&scene.camera, w, h);
    let mut rays = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            rays.push(GpuRay {
                origin: cam.position,
                t_max: 1e20,
                dir: cam
                    .ray_dir(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), w, h)
                    .into(),
                stop: 0.0,
            });
        }
    }
    rays
}

/// Incoherent secondary rays: from each primary hit, a cosine-distributed direction about the
/// surface normal (what a path tracer's or DDGI's bounce rays look like). Pixels whose primary
/// ray missed shoot a uniformly random ray from the camera instead, keeping the count.
pub fn diffuse_rays(
    scene: &irradiant_scene::Scene,
    gpu_scene: &GpuScene,
    primary: &[GpuRay],
    hits: &[irradiant::gpu_types::GpuRayHit],
) -> Vec<GpuRay> {
    let mut rng = StdRng::seed_from_u64(1);
    let mut unit = || loop {
        let v = Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let l = v.length_squared();
        if l > 1e-4 && l <= 1.0 {
            break v / l.sqrt();
        }
    };
    primary
        .iter()
        .zip(hits)
        .map(|(ray, hit)| {
            let o = Vec3::from(ray.origin);
            let d = Vec3::from(ray.dir);
            if hit.t < 0.0 {
                return GpuRay {
                    origin: ray.origin,
                    t_max: 1e20,
                    dir: unit().into(),
                    stop: 0.0,
                };
            }
            let instance =
                &scene.instances[gpu_scene.instance_order[hit.instance as usize] as usize];
            let (mesh, t) = gpu_scene.triangle_sources[hit.triangle as usize];
            let [a, b, c] = scene.meshes[mesh as usize]
                .triangle(t as usize)
                .map(|p| instance.transform.transform_point3(p));
            let mut n = (b - a).cross(c - a).normalize();
            if n.dot(d) > 0.0 {
                n = -n;
            }
            let p = o + d * hit.t;
            // Cosine distribution: normal plus a uniform point on the unit sphere.
            let dir = (n + unit()).normalize_or(n);
            let origin = p + n * 1e-4 * p.abs().max_element().max(1.0);
            GpuRay {
                origin: origin.into(),
                t_max: 1e20,
                dir: dir.into(),
                stop: 0.0,
            }
        })
        .collect()
}

/// `bench --dump-rays DIR`: the scene's world-space triangles and the rays timed, with the hit
/// distance Irradiant found for each, as little-endian f32 files for a peer renderer to trace
/// the very same rays (`tools/mitsuba/rays.py`):
/// `<scene>.triangles.f32` (9 floats a triangle: three corners), `<scene>.<set>.rays.f32`
/// (6 a ray: origin, direction) and `<scene>.<set>.t.f32` (1 a ray: the hit's t, -1 on a miss).
pub fn dump(
    dir: &std::path::Path,
    scene: &irradiant_scene::Scene,
    sets: &[(&str, &[GpuRay], &[irradiant::gpu_types::GpuRayHit])],
) -> Result<(), crate::CliError> {
    let write = |name: String, floats: Vec<f32>| {
        let bytes: Vec<u8> = floats.iter().flat_map(|f| f.to_le_bytes()).collect();
        crate::write_file(&dir.join(name), bytes)
    };
    std::fs::create_dir_all(dir).map_err(|e| {
        crate::CliError::Usage(format!(
            "--dump-rays {}: cannot create the folder: {e}",
            dir.display()
        ))
    })?;
    let mut triangles = Vec::new();
    for instance in &scene.instances {
        let mesh = &scene.meshes[instance.mesh as usize];
        for t in 0..mesh.triangle_count() {
            for corner in mesh.triangle(t) {
                triangles.extend(instance.transform.transform_point3(corner).to_array());
            }
        }
    }
    write(format!("{}.triangles.f32", scene.name), triangles)?;
    for (set, rays, hits) in sets {
        let floats = rays
            .iter()
            .flat_map(|r| r.origin.into_iter().chain(r.dir))
            .collect();
        write(format!("{}.{set}.rays.f32", scene.name), floats)?;
        write(
            format!("{}.{set}.t.f32", scene.name),
            hits.iter().map(|h| h.t).collect(),
        )?;
    }
    Ok(())
}
