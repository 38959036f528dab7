//! The GPU traversal finds the same hits as a CPU brute-force intersector, on random rays over
//! several meshes placed as instances (two levels), with alpha-masked triangles skipped.

mod common;

use glam::{Mat4, Vec3, Vec4};
use irradiant::GpuScene;
use irradiant::gpu_types::GpuRay;
use irradiant::raycast::{RayCaster, RayOrder};
use irradiant_bvh::{brute_force_closest_hit, intersect_triangle};
use irradiant_scene::{AlphaMode, Instance, Material, Mesh, Scene, Texture};
use rand::{Rng, SeedableRng, rngs::StdRng};

fn soup(rng: &mut StdRng, name: &str, count: usize, material: u32) -> Mesh {
    let mut mesh = Mesh {
        name: name.into(),
        ..Default::default()
    };
    for _ in 0..count {
        let c = Vec3::new(
            rng.random_range(-2.0..2.0),
            rng.random_range(-2.0..2.0),
            rng.random_range(-2.0..2.0),
        );
        for _ in 0..3 {
            mesh.positions.push(
                c + Vec3::new(
                    rng.random_range(-0.4..0.4),
                    rng.random_range(-0.4..0.4),
                    rng.random_range(-0.4..0.4),
                ),
            );
            mesh.indices.push(mesh.indices.len() as u32);
        }
        mesh.triangle_materials.push(material);
    }
    mesh
}

fn test_scene(rng: &mut StdRng) -> Scene {
    let mut scene = Scene::default();
    scene.materials.push(Material::default());
    scene.meshes.push(soup(rng, "a", 300, 0));
    scene.meshes.push(soup(rng, "b", 150, 0));
    scene.meshes.push(soup(rng, "c", 1, 0));
    let placements = [
        (0, Mat4::IDENTITY),
        (
            1,
            Mat4::from_translation(Vec3::new(3.0, 0.0, 0.0)) * Mat4::from_rotation_y(0.8),
        ),
        (
            0,
            Mat4::from_translation(Vec3::new(-3.0, 1.0, 2.0)) * Mat4::from_scale(Vec3::splat(0.5)),
        ),
        (2, Mat4::from_translation(Vec3::new(0.0, 3.0, 0.0))),
    ];
    for (i, (mesh, transform)) in placements.into_iter().enumerate() {
        scene.instances.push(Instance {
            name: format!("i{i}"),
            mesh,
            transform,
        });
    }
    scene
}

/// World-space triangles of every instance, with (instance, mesh triangle) for each.
fn world_triangles(scene: &Scene) -> (Vec<[Vec3; 3]>, Vec<(u32, u32)>) {
    let mut tris = Vec::new();
    let mut ids = Vec::new();
    for (i, inst) in scene.instances.iter().enumerate() {
        let mesh = &scene.meshes[inst.mesh as usize];
        for t in 0..mesh.triangle_count() {
            tris.push(mesh.triangle(t).map(|p| inst.transform.transform_point3(p)));
            ids.push((i as u32, t as u32));
        }
    }
    (tris, ids)
}

fn random_rays(rng: &mut StdRng, n: usize) -> Vec<GpuRay> {
    (0..n)
        .map(|_| {
            let o = Vec3::new(
                rng.random_range(-6.0..6.0),
                rng.random_range(-4.0..5.0),
                rng.random_range(-6.0..6.0),
            );
            let target = Vec3::new(
                rng.random_range(-4.0..4.0),
                rng.random_range(-2.0..4.0),
                rng.random_range(-3.0..3.0),
            );
            GpuRay {
                origin: o.into(),
                t_max: 1e20,
                dir: (target - o).normalize().into(),
                stop: 0.0,
            }
        })
        .collect()
}

#[test]
fn gpu_hits_match_cpu_brute_force_over_instanced_meshes() {
    use irradiant::BlasLayout;
    // Every bottom-level layout, and the binary one's workgroup-memory stack.
    for (blas_layout, stack_in_workgroup) in [
        (BlasLayout::Wide, false),
        (BlasLayout::Binary, false),
        (BlasLayout::Binary, true),
    ] {
        hits_match_brute_force(irradiant::GpuSceneSettings {
            stack_in_workgroup,
            blas_layout,
            ..Default::default()
        });
    }
}

fn hits_match_brute_force(settings: irradiant::GpuSceneSettings) {
    let mut rng = StdRng::seed_from_u64(11);
    let scene = test_scene(&mut rng);
    hits_in_scene_match_brute_force(&scene, &settings, &mut rng, 500);
}

/// 2 000 random rays over `scene`: the GPU's closest hits are the CPU's, and more than
/// `least_hits` of them hit something. Where the scene is one wide tree, the rays are traced by
/// lanes that fetch them in three runs (bvh_fetch.wgsl) and a ray a thread, with the same hits.
fn hits_in_scene_match_brute_force(
    scene: &Scene,
    settings: &irradiant::GpuSceneSettings,
    rng: &mut StdRng,
    least_hits: usize,
) {
    let Some(ctx) = common::gpu() else { return };
    let gpu_scene = GpuScene::new(&ctx, scene, settings).unwrap();
    let caster = RayCaster::with_fetch_workgroups(&ctx, &gpu_scene, 3).unwrap();
    let rays = random_rays(rng, 2000);
    let hits = caster
        .trace(&ctx, &gpu_scene, &rays, false, RayOrder::Incoherent)
        .unwrap();
    // A ray a thread (RayOrder::Coherent) and lanes that fetch where the scene allows: the
    // same hits.
    let in_order = caster
        .trace(&ctx, &gpu_scene, &rays, false, RayOrder::Coherent)
        .unwrap();
    for (a, b) in hits.iter().zip(&in_order) {
        assert_eq!((a.t, a.triangle, a.instance), (b.t, b.triangle, b.instance));
    }
    let (tris, ids) = world_triangles(scene);
    let mut hit_count = 0;
    for (ray, hit) in rays.iter().zip(&hits) {
        let expected = brute_force_closest_hit(ray.origin.into(), ray.dir.into(), &tris, 1e20);
        match expected {
            None => assert_eq!(
                hit.t, -1.0,
                "GPU hit where the CPU found none: {ray:?} {hit:?}"
            ),
            Some(e) => {
                hit_count += 1;
                assert!(hit.t > 0.0, "GPU missed a hit at t = {}", e.t);
                let instance = gpu_scene.instance_order[hit.instance as usize];
                let (_, mesh_triangle) = gpu_scene.triangle_sources[hit.triangle as usize];
                // The hit names a triangle the ray meets at the hit's distance: a wrong
                // instance or triangle at the right distance fails here.
                let named = ids
                    .iter()
                    .position(|&id| id == (instance, mesh_triangle))
                    .expect("the hit names a triangle the scene places");
                let origin = Vec3::from(ray.origin);
                let t_named = intersect_triangle(origin, ray.dir.into(), &tris[named], 0.0, 1e20);
                assert!(
                    t_named.is_some_and(|t| (t - hit.t).abs() <= 1e-4 * hit.t.max(1.0)),
                    "the hit's instance and triangle {:?} are not met at t = {}: {t_named:?}",
                    (instance, mesh_triangle),
                    hit.t
                );
                // Same triangle, or (in a near tie) one at the same distance.
                let same = ids[e.triangle as usize] == (instance, mesh_triangle);
                assert!(
                    same || (hit.t - e.t).abs() < 1e-4,
                    "different triangle: CPU {:?} at {}, GPU {:?} at {}",
                    ids[e.triangle as usize],
                    e.t,
                    (instance, mesh_triangle),
                    hit.t
                );
                assert!(
                    (hit.t - e.t).abs() <= 1e-4 * e.t.max(1.0),
                    "distance differs: CPU {} GPU {}",
                    e.t,
                    hit.t
                );
            }
        }
    }
    assert!(
        hit_count > least_hits,
        "too few rays hit ({hit_count}) for the test to mean much"
    );
}

/// The wide layout walks both levels in one loop (bvh.wgsl, `trace_levels_wide`) unless the
/// scene holds one instance for good. One instance with room for a host's more takes that loop
/// with no top level to walk; sixty more overlapping instances give it a deeper top level, its
/// stack and rays that cross many instances. A scene of no instance is refused by name.
#[test]
fn one_loop_over_both_levels_finds_the_closest_hits() {
    let mut rng = StdRng::seed_from_u64(23);
    let with_room = irradiant::GpuSceneSettings {
        instance_headroom: 3,
        ..Default::default()
    };
    let mut one = test_scene(&mut rng);
    one.instances.truncate(1);
    hits_in_scene_match_brute_force(&one, &with_room, &mut rng, 200);

    let mut many = test_scene(&mut rng);
    for i in 0..60 {
        let at = Vec3::new(
            rng.random_range(-5.0..5.0),
            rng.random_range(-3.0..4.0),
            rng.random_range(-5.0..5.0),
        );
        many.instances.push(Instance {
            name: format!("m{i}"),
            mesh: 1 + (i % 2),
            transform: Mat4::from_translation(at)
                * Mat4::from_rotation_y(rng.random_range(0.0..6.0))
                * Mat4::from_scale(Vec3::splat(rng.random_range(0.2..0.6))),
        });
    }
    hits_in_scene_match_brute_force(
        &many,
        &irradiant::GpuSceneSettings::default(),
        &mut rng,
        1000,
    );

    let Some(ctx) = common::gpu() else { return };
    let mut none = test_scene(&mut rng);
    none.instances.clear();
    let error = GpuScene::new(&ctx, &none, &with_room)
        .err()
        .expect("a scene of no instance was accepted");
    assert!(error.to_string().contains("no instance"), "{error}");
}

/// A scene of one wide tree for good hands raycast/trace's workgroups runs of rays whose lanes
/// fetch the next ray as theirs ends (bvh_fetch.wgsl): three runs, the last a short one, and
/// the instance is moved and scaled, so its rays go to object space. Any-hit rays agree.
#[test]
fn lanes_that_fetch_their_next_ray_find_the_closest_and_any_hits() {
    let mut rng = StdRng::seed_from_u64(29);
    let mut one = test_scene(&mut rng);
    one.instances.truncate(1);
    one.instances[0].transform = Mat4::from_translation(Vec3::new(0.5, 0.5, -0.5))
        * Mat4::from_rotation_y(0.6)
        * Mat4::from_scale(Vec3::splat(1.3));
    let settings = irradiant::GpuSceneSettings::default();
    let Some(ctx) = common::gpu() else { return };
    let gpu_scene = GpuScene::new(&ctx, &one, &settings).unwrap();
    assert!(
        gpu_scene.fetches_rays(),
        "the scene does not take the fetching loop"
    );
    hits_in_scene_match_brute_force(&one, &settings, &mut rng, 200);

    let caster = RayCaster::with_fetch_workgroups(&ctx, &gpu_scene, 3).unwrap();
    let mut rays = random_rays(&mut rng, 1000);
    for r in &mut rays {
        r.t_max = 5.0;
    }
    let closest = caster
        .trace(&ctx, &gpu_scene, &rays, false, RayOrder::Incoherent)
        .unwrap();
    let any = caster
        .trace(&ctx, &gpu_scene, &rays, true, RayOrder::Incoherent)
        .unwrap();
    let blocked = closest.iter().filter(|c| c.t > 0.0).count();
    assert!(blocked > 100, "too few rays blocked ({blocked})");
    for (c, a) in closest.iter().zip(&any) {
        assert_eq!(c.t < 0.0, a.t < 0.0, "{c:?} {a:?}");
        if c.t > 0.0 {
            assert!(a.t >= c.t - 1e-5 && a.t <= 5.0, "{c:?} {a:?}");
        }
    }
}

#[test]
fn any_hit_agrees_with_closest_hit_on_occlusion() {
    let Some(ctx) = common::gpu() else { return };
    let mut rng = StdRng::seed_from_u64(12);
    let scene = test_scene(&mut rng);
    let gpu_scene = GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    let caster = RayCaster::new(&ctx, &gpu_scene).unwrap();
    let mut rays = random_rays(&mut rng, 1000);
    for r in &mut rays {
        r.t_max = 5.0;
    }
    let closest = caster
        .trace(&ctx, &gpu_scene, &rays, false, RayOrder::Incoherent)
        .unwrap();
    let any = caster
        .trace(&ctx, &gpu_scene, &rays, true, RayOrder::Incoherent)
        .unwrap();
    for (c, a) in closest.iter().zip(&any) {
        assert_eq!(c.t < 0.0, a.t < 0.0);
        if c.t > 0.0 {
            assert!(a.t >= c.t - 1e-5 && a.t <= 5.0);
        }
    }
}

#[test]
fn moving_an_instance_moves_its_hits_without_rebuilding_meshes() {
    let Some(ctx) = common::gpu() else { return };
    let mut rng = StdRng::seed_from_u64(13);
    let scene = test_scene(&mut rng);
    let mut gpu_scene = GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    let caster = RayCaster::new(&ctx, &gpu_scene).unwrap();
    let mut pose = scene.pose_at(0.0);
    let shift = Mat4::from_translation(Vec3::new(0.0, 0.0, 40.0));
    pose.instance_transforms[0] = shift * pose.instance_transforms[0];
    gpu_scene.update(&ctx, &pose);
    let mut moved = scene.clone();
    moved.instances[0].transform = pose.instance_transforms[0];
    let rays = random_rays(&mut rng, 500);
    let hits = caster
        .trace(&ctx, &gpu_scene, &rays, false, RayOrder::Incoherent)
        .unwrap();
    let (tris, _) = world_triangles(&moved);
    for (ray, hit) in rays.iter().zip(&hits) {
        let expected = brute_force_closest_hit(ray.origin.into(), ray.dir.into(), &tris, 1e20);
        assert_eq!(expected.is_some(), hit.t > 0.0);
        if let Some(e) = expected {
            assert!((hit.t - e.t).abs() <= 1e-4 * e.t.max(1.0));
        }
    }
}

#[test]
fn alpha_masked_holes_let_rays_through() {
    let Some(ctx) = common::gpu() else { return };
    let mut scene = Scene::default();
    // A 2×2 texture: left column opaque, right column transparent.
    scene.textures.push(Texture {
        name: "mask".into(),
        width: 2,
        height: 2,
        rgba8: [
            [255, 255, 255, 255],
            [255, 255, 255, 0],
            [255, 255, 255, 255],
            [255, 255, 255, 0],
        ]
        .concat(),
    });
    scene.materials.push(Material {
        base_color: Vec4::ONE,
        base_color_texture: Some(0),
        alpha_mode: AlphaMode::Mask { cutoff: 0.5 },
        ..Default::default()
    });
    scene.materials.push(Material::default());
    let mut mesh = Mesh {
        name: "quads".into(),
        ..Default::default()
    };
    // Masked quad at z = 0 (uv x follows world x), opaque backstop at z = -1.
    for (z, material) in [(0.0, 0u32), (-1.0, 1u32)] {
        let base = mesh.positions.len() as u32;
        mesh.positions.extend([
            Vec3::new(0.0, 0.0, z),
            Vec3::new(1.0, 0.0, z),
            Vec3::new(1.0, 1.0, z),
            Vec3::new(0.0, 1.0, z),
        ]);
        mesh.uvs.extend([
            glam::Vec2::new(0.0, 1.0),
            glam::Vec2::new(1.0, 1.0),
            glam::Vec2::new(1.0, 0.0),
            glam::Vec2::new(0.0, 0.0),
        ]);
        mesh.indices
            .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
        mesh.triangle_materials.extend([material, material]);
    }
    scene.meshes.push(mesh);
    scene.instances.push(Instance {
        name: "quads".into(),
        mesh: 0,
        transform: Mat4::IDENTITY,
    });
    let settings = irradiant::GpuSceneSettings {
        texture_size: 2,
        ..Default::default()
    };
    let gpu_scene = GpuScene::new(&ctx, &scene, &settings).unwrap();
    let caster = RayCaster::new(&ctx, &gpu_scene).unwrap();
    let ray = |x: f32| GpuRay {
        origin: [x, 0.5, 1.0],
        t_max: 1e20,
        dir: [0.0, 0.0, -1.0],
        stop: 0.0,
    };
    let hits = caster
        .trace(
            &ctx,
            &gpu_scene,
            &[ray(0.1), ray(0.9)],
            false,
            RayOrder::Incoherent,
        )
        .unwrap();
    assert!(
        (hits[0].t - 1.0).abs() < 1e-5,
        "opaque texel must stop the ray: {:?}",
        hits[0]
    );
    assert!(
        (hits[1].t - 2.0).abs() < 1e-5,
        "transparent texel must let the ray through: {:?}",
        hits[1]
    );
}

/// The counting variant (`irradiant bench`'s work a ray) finds the same hits as the timed
/// pass, and its counts follow the traversal: a ray that hits visited a node and tested the
/// triangle it hit; a ray pointed away from the scene stops at the root; no ray passes every
/// node and triangle; any-hit does no more work than closest-hit; and the 8-wide layout visits
/// fewer nodes a ray than the binary one over the same triangles.
#[test]
fn the_counting_variant_counts_the_traversals_work() {
    use irradiant::raycast::RayWork;
    use irradiant::{BlasLayout, GpuSceneSettings};
    let Some(ctx) = common::gpu() else { return };
    let mut rng = StdRng::seed_from_u64(14);
    let scene = test_scene(&mut rng);
    let mut rays = random_rays(&mut rng, 1000);
    // Rays from far outside, pointing away from everything.
    let away: Vec<GpuRay> = (0..64)
        .map(|i| GpuRay {
            origin: [100.0 + i as f32, 100.0, 100.0],
            t_max: 1e20,
            dir: [1.0, 0.0, 0.0],
            stop: 0.0,
        })
        .collect();
    rays.extend_from_slice(&away);
    let mut mean_nodes = Vec::new();
    for layout in [BlasLayout::Binary, BlasLayout::Wide] {
        let settings = GpuSceneSettings {
            blas_layout: layout,
            ..Default::default()
        };
        let gpu_scene = GpuScene::new(&ctx, &scene, &settings).unwrap();
        let timed = RayCaster::new(&ctx, &gpu_scene).unwrap();
        let counting = RayCaster::counting(&ctx, &gpu_scene).unwrap();
        let closest = counting
            .trace(&ctx, &gpu_scene, &rays, false, RayOrder::Incoherent)
            .unwrap();
        let any = counting
            .trace(&ctx, &gpu_scene, &rays, true, RayOrder::Incoherent)
            .unwrap();
        let plain = timed
            .trace(&ctx, &gpu_scene, &rays, false, RayOrder::Incoherent)
            .unwrap();
        for (c, p) in closest.iter().zip(&plain) {
            assert_eq!((c.t, c.triangle, c.instance), (p.t, p.triangle, p.instance));
            assert_eq!(p.work, 0, "the timed pass counts nothing");
            assert!(c.node_visits() as usize <= gpu_scene.stats.bvh_nodes);
            assert!(c.triangle_tests() as usize <= gpu_scene.stats.triangles);
            if c.t > 0.0 {
                assert!(c.node_visits() >= 1 && c.triangle_tests() >= 1, "{c:?}");
            }
        }
        for h in &closest[closest.len() - away.len()..] {
            assert!(
                h.t < 0.0 && h.node_visits() <= 1 && h.triangle_tests() == 0,
                "{h:?}"
            );
        }
        let (closest, any) = (RayWork::of(&closest), RayWork::of(&any));
        eprintln!("{layout:?}: closest hit {closest:?}, any hit {any:?}");
        assert!(any.node_visits <= closest.node_visits);
        assert!(any.triangle_tests <= closest.triangle_tests);
        mean_nodes.push(closest.node_visits);
    }
    assert!(
        mean_nodes[1] < mean_nodes[0],
        "wide nodes a ray {} should be fewer than binary {}",
        mean_nodes[1],
        mean_nodes[0]
    );
}

/// An emitter's shadow ray asks only whether the closest hit lies at or past a distance
/// (`trace_ray_until`): its search ends at the first hit nearer than that. It must still find a
/// blocker wherever the closest hit is nearer, the closest hit itself wherever it is not, and do
/// less work than a closest-hit search where it stops early.
#[test]
fn a_search_stopped_short_finds_a_blocker_or_the_closest_hit() {
    use irradiant::raycast::RayWork;
    let Some(ctx) = common::gpu() else { return };
    let mut rng = StdRng::seed_from_u64(15);
    let scene = test_scene(&mut rng);
    let (tris, _) = world_triangles(&scene);
    let gpu_scene = GpuScene::new(&ctx, &scene, &Default::default()).unwrap();
    let counting = RayCaster::counting(&ctx, &gpu_scene).unwrap();
    let mut rays = random_rays(&mut rng, 1000);
    let closest: Vec<_> = rays
        .iter()
        .map(|r| brute_force_closest_hit(r.origin.into(), r.dir.into(), &tris, 1e20))
        .collect();
    // Half the rays stop past their closest hit (as an emitter's ray stops short of a point
    // behind a blocker), half short of it (as one reaching the point does).
    for (i, (ray, hit)) in rays.iter_mut().zip(&closest).enumerate() {
        let t = hit.map_or(10.0, |h| h.t);
        ray.stop = if i % 2 == 0 { t * 1.5 } else { t * 0.9 };
    }
    let stopped = counting
        .trace(&ctx, &gpu_scene, &rays, false, RayOrder::Incoherent)
        .unwrap();
    let full_rays: Vec<GpuRay> = rays.iter().map(|r| GpuRay { stop: 0.0, ..*r }).collect();
    let full = counting
        .trace(&ctx, &gpu_scene, &full_rays, false, RayOrder::Incoherent)
        .unwrap();
    let (mut blocked_stopped, mut blocked_full) = (Vec::new(), Vec::new());
    for (i, ((ray, expected), (s, f))) in rays
        .iter()
        .zip(&closest)
        .zip(stopped.iter().zip(&full))
        .enumerate()
    {
        let Some(e) = expected else {
            assert!(s.t < 0.0, "ray {i}: no triangle, yet {s:?}");
            continue;
        };
        let tolerance = 1e-4 * e.t.max(1.0);
        if e.t < ray.stop {
            // A blocker: any hit nearer than the stop, never one nearer than the closest.
            assert!(
                s.t > 0.0 && s.t < ray.stop && s.t >= e.t - tolerance,
                "ray {i}: closest {} before stop {}, found {s:?}",
                e.t,
                ray.stop
            );
            blocked_stopped.push(*s);
            blocked_full.push(*f);
        } else {
            assert!(
                (s.t - e.t).abs() <= tolerance
                    && (s.triangle, s.instance) == (f.triangle, f.instance),
                "ray {i}: closest {} at or past stop {}, found {s:?} against {f:?}",
                e.t,
                ray.stop
            );
        }
        assert!(
            s.node_visits() <= f.node_visits(),
            "ray {i}: {s:?} against {f:?}"
        );
    }
    let (stopped_work, full_work) = (RayWork::of(&blocked_stopped), RayWork::of(&blocked_full));
    eprintln!(
        "{} blocked rays: {stopped_work:?} stopping short, {full_work:?} searching on",
        blocked_stopped.len()
    );
    // Seeded rays over the seeded soups: 203 of them have a blocker before their stop.
    assert!(
        blocked_stopped.len() > 100,
        "{} blocked rays",
        blocked_stopped.len()
    );
    assert!(
        stopped_work.node_visits < full_work.node_visits,
        "stopping short should visit fewer nodes: {stopped_work:?} against {full_work:?}"
    );
}
