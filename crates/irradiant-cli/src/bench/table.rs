//! `bench`'s printed table.

use super::{BenchRecord, FrameRecord};

pub fn print_table(r: &BenchRecord) {
    println!(
        "adapter: {} ({}, driver {}); timing: {}; commit {}",
        r.adapter, r.backend, r.driver, r.timing, r.commit
    );
    println!(
        "{:<22} {:>10} {:>9} {:>12} {:>10} {:>9} {:>8} {:>12} {:>10} {:>12} {:>13}",
        "scene",
        "triangles",
        "instances",
        "in world",
        "BVH nodes",
        "BVH depth",
        "BVH SAH",
        "BVH build ms",
        "load ms",
        "GPU scene MiB",
        "peak host MiB"
    );
    for s in &r.scenes {
        println!(
            "{:<22} {:>10} {:>9} {:>12} {:>10} {:>9} {:>8.1} {:>12.1} {:>10.1} {:>12.1} {:>13}",
            s.scene,
            s.triangles,
            s.instances,
            s.world_triangles,
            s.bvh_nodes,
            s.max_blas_depth,
            s.bvh_sah_cost,
            s.bvh_build_ms,
            s.scene_load_ms,
            s.gpu_scene_mib,
            s.peak_host_mib.map_or("-".into(), |m| format!("{m:.0}"))
        );
    }
    println!(
        "\n{:<22} {:<44} {:>10} {:>10} {:>12} {:>10} {:>10} {:>10} {:>12}",
        "scene",
        "pass",
        "median ms",
        "min ms",
        "rays",
        "Mrays/s",
        "nodes/ray",
        "tris/ray",
        "Gnodes/s"
    );
    for p in &r.passes {
        let rays = p.rays.map_or("-".into(), |n| n.to_string());
        let rate = p.mrays_per_s.map_or("-".into(), |m| format!("{m:.1}"));
        let (nodes, tris, node_rate) = p.work.map_or(("-".into(), "-".into(), "-".into()), |w| {
            (
                format!("{:.1}", w.node_visits_per_ray),
                format!("{:.1}", w.triangle_tests_per_ray),
                format!("{:.2}", w.g_node_visits_per_s),
            )
        });
        println!(
            "{:<22} {:<44} {:>10.3} {:>10.3} {:>12} {:>10} {:>10} {:>10} {:>12}",
            p.scene, p.label, p.median_ms, p.min_ms, rays, rate, nodes, tris, node_rate
        );
    }
    frame_table(&r.techniques);
    let ssil: Vec<&FrameRecord> = r
        .techniques
        .iter()
        .filter(|f| f.technique == "ssil")
        .collect();
    super::ssil::print_table(&ssil);
}

/// One row a timed frame configuration, one column a pass (any record's, in the order first
/// seen: variants lack some passes).
fn frame_table(records: &[FrameRecord]) {
    if records.is_empty() {
        return;
    }
    let mut full_labels: Vec<&str> = Vec::new();
    for d in records {
        for (l, _) in &d.passes {
            if !full_labels.contains(&l.as_str()) {
                full_labels.push(l);
            }
        }
    }
    let labels: Vec<&str> = full_labels
        .iter()
        .map(|l| l.split_once('/').map_or(*l, |(_, stage)| stage))
        .collect();
    if records.iter().any(|r| r.camera == "moving") {
        println!("\n(timed with the camera moving every frame)");
    }
    if records.iter().any(|r| r.camera == "path") {
        println!(
            "\n(timed along the scene's camera path; GI ms is the sum of the passes' medians)"
        );
    }
    print!(
        "\n{:<10} {:<14} {:<10} {:>5} {:<28} {:>9}",
        "scene", "technique", "probes", "rays", "variant", "Mrays"
    );
    for l in &labels {
        print!(" {:>12}", l);
    }
    println!(
        " {:>10} {:>12} {:>10} {:>12} {:>9} {:>9}",
        "update ms", "update Mr/s", "trace Mr/s", "GI ms", "frame ms", "updating"
    );
    for d in records {
        print!(
            "{:<10} {:<14} {:<10} {:>5} {:<28} {:>9.2}",
            d.scene,
            d.technique,
            format!("{}x{}x{}", d.probes[0], d.probes[1], d.probes[2]),
            d.rays_per_probe,
            d.variant,
            d.rays as f64 / 1e6
        );
        for label in &full_labels {
            let ms = d
                .passes
                .iter()
                .find(|(l, _)| l == label)
                .map_or(0.0, |p| p.1);
            print!(" {:>12.3}", ms);
        }
        println!(
            " {:>10.3} {:>12.0} {:>10.0} {:>12.3} {:>9.3} {:>9}",
            d.update_ms,
            d.update_mrays_per_s,
            d.trace_mrays_per_s,
            d.gi_ms,
            d.frame_ms,
            d.updating_probes
        );
    }
    for d in records.iter().filter(|d| d.camera == "path") {
        println!(
            "{} {} {}: GI in the worst frame of the path {:.3} ms",
            d.scene, d.technique, d.variant, d.gi_worst_ms
        );
    }
    // What the techniques reported (bake time and memory, agreement, probe states).
    for d in records.iter().filter(|d| !d.counters.is_empty()) {
        let counters: Vec<String> = d
            .counters
            .iter()
            .map(|(name, value)| format!("{name} {value:.4}"))
            .collect();
        println!(
            "{} {} {}: {}, memory {:.1} MiB",
            d.scene,
            d.technique,
            d.variant,
            counters.join(", "),
            d.technique_mib
        );
    }
}
