//! GI in glossy reflections (003 §4.4, `[technique.reflections]`): a mirror against the path
//! tracer.

mod common;

use common::*;
use irradiant::ddgi::{DdgiReflectionSettings, DdgiSettings};

/// The mirror Cornell box's tall box (metal, roughness 0.05) has no diffuse term: without
/// reflections it shows only what frame/direct gives it (the lamp's highlight, out of view),
/// with them the lit room, as the path tracer does.
#[test]
fn a_mirror_reflects_the_lit_room() {
    let Some(ctx) = gpu() else { return };
    let path = repo_root().join("scenes/cornell-box/mirror.toml");
    let scene = irradiant_scene::load(path.to_str().unwrap()).unwrap().scene;
    let (width, height) = (64, 64);
    let reference = path_trace(&ctx, &scene, (width, height), 256);
    let mut settings = DdgiSettings::fast();
    settings.reflections = DdgiReflectionSettings::half();
    let with = render_frames(&ctx, &scene, (width, height), Some(&settings), 30);
    settings.reflections.enabled = false;
    let without = render_frames(&ctx, &scene, (width, height), Some(&settings), 30);
    // The mirror's pixels, those at its silhouette left out (the path tracer's pixels there
    // mix the mirror with what lies behind it): surfaces that reflect no diffuse light and emit
    // none, with four such neighbours.
    let mirror = interior(width as usize, height as usize, |i| {
        let g = &with.gbuffer[i];
        g.depth >= 0.0 && g.diffuse.iter().all(|&c| c < 0.01) && g.emission == [0.0; 3]
    });
    assert!(
        mirror.iter().filter(|&&m| m).count() > 100,
        "the camera sees the mirror"
    );
    let truth = masked_mean(&reference, &mirror);
    // One bounce off the mirror: what its reflections show lit directly.
    let one_bounce = masked_mean(
        &path_trace_view(&ctx, &scene, &scene.camera, (width, height), 256, 2),
        &mirror,
    );
    let (lit, dark) = (
        masked_mean(&with.total, &mirror),
        masked_mean(&without.total, &mirror),
    );
    let (flip_with, flip_without) = (
        flip_mean(&reference, &with.total),
        flip_mean(&reference, &without.total),
    );
    eprintln!(
        "the mirror: path tracer {truth:.4} (one bounce off it {one_bounce:.4}), with \
         reflections {lit:.4}, without {dark:.4}; FLIP of the view {flip_with:.4} against \
         {flip_without:.4}"
    );
    // The reflections' hits take their direct light and the probes' indirect light, which
    // here reads a little low (the probes' rays see the mirror reflect only the probes' light
    // about its mirror direction, `probes_reflected`), so the mirror lies between the path
    // tracer's one bounce off it and every bounce. Seen on lavapipe: 0.0163 < 0.0289 < 0.0320
    // (0.0259 before `probes_reflected`, when the probes' rays saw the mirror black).
    assert!(
        lit > 1.2 * one_bounce,
        "{lit} against one bounce's {one_bounce}"
    );
    assert!(lit < 1.05 * truth, "{lit} against {truth}");
    assert!(
        dark < 0.1 * truth,
        "without reflections {dark} against {truth}"
    );
    assert!(
        flip_with < flip_without,
        "{flip_with} against {flip_without}"
    );
}

/// The glossy-floor Cornell box's ceiling is lit mostly by what its metal floor mirrors: the
/// lit walls, and the lamp through the floor's sharp lobe. The traced bounce's rays and the
/// final gather's meet that floor and must bring both back. A ray traced on from a surface
/// stands for its diffuse layer only, so its specular layer's share of the probes' light is
/// added (`probes_mirrored`): without it the traced bounce read the ceiling 9 % darker than the
/// query (lavapipe: 0.0630 against 0.0691; with it 0.0693). A gather ray's hit on the floor
/// finds the lamp by a BRDF-sampled ray as well as by its emitter sample
/// (`emitter_light_both_ways`): the same mean, less speckle (the mean difference between
/// neighbouring ceiling pixels 0.0196 → 0.0141, 30 → 21 % of the light). Such rare bright
/// gathers must also survive the filter (ddgi/gather_filter weighs a neighbour by both pixels'
/// errors): a one-ray gather, filtered, read the ceiling 13.7 % dark when only the centre's
/// error counted, 6.3 % now (0.0605 and 0.0657 against 0.0701).
#[test]
fn the_room_a_metal_floor_mirrors_lights_the_ceiling() {
    let Some(ctx) = gpu() else { return };
    let path = repo_root().join("scenes/cornell-box/glossy-floor.toml");
    let scene = irradiant_scene::load(path.to_str().unwrap()).unwrap().scene;
    let size = (64, 64);
    let reference = path_trace(&ctx, &scene, size, 1024);
    let mut settings = DdgiSettings::balanced();
    settings.update.hysteresis = 0.9;
    settings.reflections.enabled = false;
    let query = render_frames(&ctx, &scene, size, Some(&settings), 120);
    settings.update.traced_bounce = true;
    let traced = render_frames(&ctx, &scene, size, Some(&settings), 120);
    // Four rays a pixel and no filter: the mean and the speckle of the gathers themselves.
    settings.gather.rays_per_pixel = 4;
    settings.gather.filter_passes = 0;
    let gathered = render_frames(&ctx, &scene, size, Some(&settings), 120);
    // `quality`'s gather: one ray a pixel, filtered.
    settings.gather.rays_per_pixel = 1;
    settings.gather.filter_passes = 3;
    let filtered = render_frames(&ctx, &scene, size, Some(&settings), 120);
    // The ceiling's pixels whose four neighbours are ceiling too: the path tracer's pixels at
    // the lamp's edge take some of its emission.
    let (width, height) = (size.0 as usize, size.1 as usize);
    let ceiling = interior(width, height, |i| {
        let g = &query.gbuffer[i];
        g.depth >= 0.0 && g.normal[1] < -0.9 && g.emission == [0.0; 3]
    });
    let truth = masked_mean(&path_traced_indirect(&reference, &query), &ceiling);
    // The mean difference between horizontally neighbouring ceiling pixels.
    let light = |i: usize| pixel_luminance(&gathered.indirect.pixels[i]);
    let steps: Vec<f64> = (0..width * height - 1)
        .filter(|&i| ceiling[i] && ceiling[i + 1])
        .map(|i| (light(i) - light(i + 1)).abs())
        .collect();
    let speckle = steps.iter().sum::<f64>() / steps.len() as f64;
    let [query, traced, gathered, filtered] =
        [&query, &traced, &gathered, &filtered].map(|f| masked_mean(&f.indirect, &ceiling));
    eprintln!(
        "the ceiling's indirect light: path tracer {truth:.4}, the probes {query:.4}, with the \
         traced bounce {traced:.4}, the gather {gathered:.4} (speckle {speckle:.4}), one ray \
         filtered {filtered:.4}"
    );
    assert!(
        (query / truth - 1.0).abs() < 0.05,
        "the probes: {query} against the path tracer's {truth}"
    );
    assert!(
        (traced / query - 1.0).abs() < 0.05,
        "the traced bounce: {traced} against the query's {query}"
    );
    assert!(
        (gathered / truth - 1.0).abs() < 0.1,
        "the gather: {gathered} against the path tracer's {truth}"
    );
    assert!(
        (filtered / truth - 1.0).abs() < 0.1,
        "the filtered gather: {filtered} against the path tracer's {truth}"
    );
    assert!(
        speckle < 0.25 * gathered,
        "the gather's speckle: {speckle} against its light {gathered}"
    );
}
