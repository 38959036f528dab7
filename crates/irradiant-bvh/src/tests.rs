use glam::Vec3;
use rand::{Rng, SeedableRng, rngs::StdRng};

use super::*;

fn random_soup(rng: &mut StdRng, count: usize) -> Vec<[Vec3; 3]> {
    (0..count)
        .map(|_| {
            let c = Vec3::new(
                rng.random_range(-5.0..5.0),
                rng.random_range(-5.0..5.0),
                rng.random_range(-5.0..5.0),
            );
            let mut v = || {
                c + Vec3::new(
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-0.5..0.5),
                    rng.random_range(-0.5..0.5),
                )
            };
            [v(), v(), v()]
        })
        .collect()
}

fn random_direction(rng: &mut StdRng) -> Vec3 {
    loop {
        let d = Vec3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        if d.length_squared() > 0.01 && d.length_squared() <= 1.0 {
            return d.normalize();
        }
    }
}

#[test]
fn packed_tree_finds_the_same_hits_as_brute_force() {
    let mut rng = StdRng::seed_from_u64(7);
    for quality in [
        BuildQuality::Fast,
        BuildQuality::Balanced,
        BuildQuality::Quality,
    ] {
        let tris = random_soup(&mut rng, 2000);
        let blas = build_blas(&tris, quality);
        let mut hits = 0;
        for _ in 0..500 {
            let o = Vec3::new(
                rng.random_range(-6.0..6.0),
                rng.random_range(-6.0..6.0),
                rng.random_range(-6.0..6.0),
            );
            let d = random_direction(&mut rng);
            let expected = brute_force_closest_hit(o, d, &tris, f32::INFINITY);
            let got = traverse_packed(&blas.nodes, &blas.triangle_order, o, d, &tris);
            assert_eq!(
                expected.map(|h| h.triangle),
                got.map(|h| h.triangle),
                "{quality:?}"
            );
            hits += expected.is_some() as u32;
        }
        assert!(hits > 100, "the test rays should mostly hit ({hits})");
    }
}

#[test]
fn every_triangle_is_referenced_and_boxes_nest() {
    let mut rng = StdRng::seed_from_u64(3);
    let tris = random_soup(&mut rng, 777);
    let blas = build_blas(&tris, BuildQuality::Balanced);
    let mut seen = vec![false; tris.len()];
    for &t in &blas.triangle_order {
        seen[t as usize] = true;
    }
    assert!(seen.iter().all(|&s| s));
    // Every leaf box contains its triangles.
    for n in &blas.nodes {
        for (lo, hi, first, count) in [
            (n.a_min, n.a_max, n.a_first, n.a_count),
            (n.b_min, n.b_max, n.b_first, n.b_count),
        ] {
            for slot in first..first + count {
                for v in tris[blas.triangle_order[slot as usize] as usize] {
                    assert!(
                        v.cmpge(Vec3::from(lo) - 1e-5).all()
                            && v.cmple(Vec3::from(hi) + 1e-5).all()
                    );
                }
            }
        }
    }
    assert!(blas.depth >= 8 && blas.depth < 64, "depth {}", blas.depth);
}

#[test]
fn a_single_triangle_packs_into_one_node_with_an_absent_sibling() {
    let tri = [[Vec3::ZERO, Vec3::X, Vec3::Y]];
    let blas = build_blas(&tri, BuildQuality::Balanced);
    assert_eq!(blas.nodes.len(), 1);
    assert_eq!(blas.nodes[0].a_count, 1);
    assert_eq!((blas.nodes[0].b_first, blas.nodes[0].b_count), (ABSENT, 0));
    let hit = traverse_packed(
        &blas.nodes,
        &blas.triangle_order,
        Vec3::new(0.2, 0.2, 1.0),
        -Vec3::Z,
        &tri,
    );
    assert!((hit.unwrap().t - 1.0).abs() < 1e-6);
}

#[test]
fn offset_shifts_inner_and_leaf_indices_separately() {
    let mut rng = StdRng::seed_from_u64(5);
    let tris = random_soup(&mut rng, 100);
    let blas = build_blas(&tris, BuildQuality::Fast);
    let mut shifted = blas.clone();
    shifted.offset(1000, 50_000);
    for (a, b) in blas.nodes.iter().zip(&shifted.nodes) {
        let expect = |first: u32, count: u32| {
            if count == 0 {
                first + 1000
            } else {
                first + 50_000
            }
        };
        assert_eq!(b.a_first, expect(a.a_first, a.a_count));
        assert_eq!(b.b_first, expect(a.b_first, a.b_count));
    }
}

#[test]
fn tlas_covers_every_instance() {
    let boxes: Vec<(Vec3, Vec3)> = (0..37)
        .map(|i| (Vec3::splat(i as f32), Vec3::splat(i as f32 + 0.5)))
        .collect();
    let tlas = build_tlas(&boxes, tlas_depth_bound(boxes.len()));
    let mut order = tlas.instance_order.clone();
    order.sort();
    assert_eq!(order, (0..37).collect::<Vec<_>>());
}

#[test]
fn transformed_bounds_contain_rotated_corners() {
    let m = Mat4::from_rotation_y(0.7) * Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0));
    let (lo, hi) = transform_bounds((Vec3::ZERO, Vec3::ONE), &m);
    for corner in [Vec3::ZERO, Vec3::ONE, Vec3::X, Vec3::new(1.0, 0.0, 1.0)] {
        let w = m.transform_point3(corner);
        assert!(w.cmpge(lo - 1e-5).all() && w.cmple(hi + 1e-5).all());
    }
}

#[test]
fn wide_tree_leaves_cover_every_triangle_and_contain_it() {
    let mut rng = StdRng::seed_from_u64(9);
    for quality in [BuildQuality::Fast, BuildQuality::Balanced] {
        let tris = random_soup(&mut rng, 3000);
        let mut blas = build_wide_blas(&tris, quality);
        // Shifting indices (several meshes share the GPU arrays) moves every leaf slot.
        blas.offset(5, 100);
        let leaves = blas.leaves();
        let mut seen = vec![false; tris.len()];
        for &(slot, (lo, hi)) in &leaves {
            let triangle = blas.triangle_order[(slot - 100) as usize] as usize;
            seen[triangle] = true;
            for v in tris[triangle] {
                // Quantised boxes are rounded outwards, so each contains its exact box.
                assert!(
                    v.cmpge(lo - 1e-4).all() && v.cmple(hi + 1e-4).all(),
                    "{quality:?}: triangle {triangle} pokes out of its leaf box {lo}…{hi}"
                );
            }
        }
        assert!(
            seen.iter().all(|&s| s),
            "{quality:?}: a triangle no leaf holds"
        );
        for node in &blas.nodes {
            for slot in 0..8 {
                if node.imask() & (1 << slot) != 0 {
                    let child = node.inner_child(slot);
                    assert!((5..5 + blas.nodes.len() as u32).contains(&child));
                }
            }
        }
        assert!(blas.depth >= 3 && blas.depth < 20, "depth {}", blas.depth);
    }
}

/// Triangles shrinking by a tenth towards one corner, each inside the last: SAH peels them off
/// one a level, so the unbounded tree is as deep as there are triangles.
fn nested_shrinking_triangles(count: usize) -> Vec<[Vec3; 3]> {
    (0..count)
        .map(|k| {
            let s = 0.9f32.powi(k as i32);
            [Vec3::ZERO, Vec3::new(s, 0.0, 0.0), Vec3::new(0.0, s, s)]
        })
        .collect()
}

#[test]
fn degenerate_meshes_are_bounded_in_depth_and_lose_no_hit() {
    let mut rng = StdRng::seed_from_u64(11);
    let mut cluster = random_soup(&mut rng, 2000);
    // A dense cluster of tiny triangles inside an ordinary mesh.
    for t in cluster.iter_mut().take(1500) {
        for v in t.iter_mut() {
            *v = Vec3::splat(1.0) + (*v - Vec3::splat(1.0)) * 1e-6;
        }
    }
    // (name, triangles, whether the unbounded tree is deeper than the bound)
    for (name, tris, too_deep) in [
        ("nested", nested_shrinking_triangles(240), true),
        ("cluster", cluster, false),
    ] {
        // Without the bound, the nested mesh's tree reaches past it: the bound does the work.
        let unbounded = obvhs::bvh2::builder::build_bvh2_from_tris(
            &obvhs_triangles(&tris),
            BuildQuality::Balanced.params(),
            &mut Duration::default(),
        );
        let unbounded_depth = depth::tree_height(&unbounded);
        let blas = build_blas(&tris, BuildQuality::Balanced);
        let wide = build_wide_blas(&tris, BuildQuality::Balanced);
        println!(
            "{name}: unbounded {unbounded_depth}, bounded binary {} wide {}",
            blas.depth, wide.depth
        );
        assert_eq!(
            unbounded_depth > MAX_BLAS_DEPTH,
            too_deep,
            "{name}: {unbounded_depth}"
        );
        assert!(blas.depth <= MAX_BLAS_DEPTH && wide.depth <= MAX_BLAS_DEPTH);
        assert_eq!(
            wide.leaves().len(),
            tris.len(),
            "{name}: a triangle no leaf holds"
        );
        for _ in 0..400 {
            let o = Vec3::new(
                rng.random_range(-1.0..2.0),
                rng.random_range(-1.0..2.0),
                rng.random_range(-1.0..2.0),
            );
            let [a, b, c] = tris[rng.random_range(0..tris.len())];
            let target = (a + b + c) / 3.0;
            let d = (target - o).normalize();
            let expected = brute_force_closest_hit(o, d, &tris, f32::INFINITY);
            let got = traverse_packed(&blas.nodes, &blas.triangle_order, o, d, &tris);
            // Triangles share a plane here: another one may be hit at the same point.
            match (expected, got) {
                (Some(e), Some(g)) => assert!((e.t - g.t).abs() <= 1e-5 * e.t, "{name}"),
                (e, g) => assert_eq!(e.is_some(), g.is_some(), "{name}: a hit lost"),
            }
        }
    }
}

#[test]
fn a_top_level_tree_never_outgrows_its_bound() {
    // Instances in a geometric series of sizes: the same shape as the nested triangles.
    let boxes: Vec<(Vec3, Vec3)> = (0..300)
        .map(|k| (Vec3::ZERO, Vec3::splat(0.9f32.powi(k))))
        .collect();
    let bound = tlas_depth_bound(boxes.len());
    let tlas = build_tlas(&boxes, bound);
    assert!(tlas.depth <= bound, "{} > {bound}", tlas.depth);
    let mut order = tlas.instance_order.clone();
    order.sort();
    assert_eq!(order, (0..300).collect::<Vec<_>>());
}

/// The SAH cost: a one-triangle tree costs its one test; triangles spread apart cost far less
/// than testing all of them; the same triangle n times cannot be split and costs about n.
#[test]
fn sah_cost_counts_the_expected_work() {
    let one = build_blas(&[[Vec3::ZERO, Vec3::X, Vec3::Y]], BuildQuality::Balanced);
    assert!((one.sah_cost - 1.0).abs() < 1e-6, "{}", one.sah_cost);
    let mut rng = StdRng::seed_from_u64(3);
    let soup = random_soup(&mut rng, 1000);
    let spread = build_blas(&soup, BuildQuality::Balanced);
    let wide = build_wide_blas(&soup, BuildQuality::Balanced);
    assert!(
        spread.sah_cost > 1.0 && spread.sah_cost < 100.0,
        "{}",
        spread.sah_cost
    );
    assert!(
        wide.sah_cost > 1.0 && wide.sah_cost < 100.0,
        "{}",
        wide.sah_cost
    );
    let stacked = build_blas(
        &vec![[Vec3::ZERO, Vec3::X, Vec3::Y]; 16],
        BuildQuality::Balanced,
    );
    assert!(stacked.sah_cost >= 16.0, "{}", stacked.sah_cost);
}
