//! ssil+ddgi: where its light comes from and that none is counted twice — the screen replaces
//! the probes' light only in the near field, each part keeps the furnace's energy, and the
//! screen takes from a surface only the light it sends every way (docs/ssil.md, "The hybrid").

mod common;

use common::*;
use irradiant::TechniqueSpec;
use irradiant::ddgi::DdgiSettings;
use irradiant::frame::Image;
use irradiant::ssil::{HybridSettings, SsilDdgi, SsilSettings};

fn hybrid_spec(near_field: f32) -> TechniqueSpec {
    let mut settings = HybridSettings::balanced();
    settings.near_field = near_field;
    TechniqueSpec::with_settings("ssil+ddgi", &settings)
}

/// The largest relative difference of any pixel's channel between two images.
fn largest_relative_difference(a: &Image, b: &Image) -> f32 {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs() / (1e-3 + a[c].abs())))
        .fold(0.0f32, f32::max)
}

/// With no near field the screen replaces nothing: the hybrid's image is DDGI's, to the last
/// bit of the probes' light passing through the blend ((1 − C) × probes with C = 0).
#[test]
fn with_no_near_field_the_hybrid_is_ddgi_alone() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (48, 48);
    let image = |spec: TechniqueSpec| {
        let mut s = session(&ctx, &scene, size, spec);
        for _ in 0..8 {
            s.render().unwrap();
        }
        s.image().unwrap()
    };
    let ddgi = image(spec(Some(&DdgiSettings::balanced())));
    let hybrid = image(hybrid_spec(0.0));
    let worst = largest_relative_difference(&ddgi, &hybrid);
    eprintln!("largest relative difference from DDGI: {worst:e}");
    assert!(worst <= 1e-5, "the hybrid changed DDGI's light by {worst}");
}

/// With DDGI's final gather the pixels trace their own near field, and the screen's part steps
/// aside (`HybridSettings::screen_part`): none is built and the image is DDGI's.
#[test]
fn with_the_final_gather_the_hybrid_is_ddgi_alone() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (48, 48);
    let mut settings = HybridSettings::balanced();
    settings.ddgi.gather.rays_per_pixel = 1;
    settings.ddgi.gather.filter_passes = 1;
    let run = |spec: TechniqueSpec| {
        let mut s = session(&ctx, &scene, size, spec);
        for _ in 0..8 {
            s.render().unwrap();
        }
        let screen_part = s
            .technique_as::<SsilDdgi>()
            .is_some_and(|h| h.ssil.is_some());
        (s.image().unwrap(), screen_part)
    };
    let (ddgi, _) = run(spec(Some(&settings.ddgi)));
    let (hybrid, screen_part) = run(TechniqueSpec::with_settings("ssil+ddgi", &settings));
    assert!(
        !screen_part,
        "the hybrid built its screen part beside the gather"
    );
    let worst = largest_relative_difference(&ddgi, &hybrid);
    assert!(worst <= 1e-5, "the hybrid changed DDGI's light by {worst}");
}

/// The DDGI furnace (`glowing-box`: walls that emit 1 and reflect ½; radiance 2 everywhere):
/// every wall reflects ½ of indirect light, whichever part lights it. The screen's part, its
/// gathered E over the share C of the cosine lobe it covers, must find the radiance every
/// sender sends besides its emission (direct ½ + the probes' ½ = 1), and the hybrid's indirect
/// light the closed form. A sender's light counted twice, or the probes' filled in over what
/// the screen covered, would show as more.
#[test]
fn the_hybrid_keeps_the_furnaces_energy_in_both_parts() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("glowing-box").unwrap().scene;
    let (le, albedo) = (
        irradiant_scene::GLOWING_BOX_EMISSION,
        irradiant_scene::GLOWING_BOX_ALBEDO,
    );
    // A near field of a whole probe spacing, so that the screen covers a fair share.
    let mut s = session(&ctx, &scene, (48, 48), hybrid_spec(1.0));
    for _ in 0..300 {
        s.render().unwrap();
    }
    let light = s
        .technique_as::<SsilDdgi>()
        .unwrap()
        .ssil
        .as_ref()
        .unwrap()
        .read_light(&ctx)
        .unwrap();
    let (mut covered, mut gathered, mut pixels_covered) = (0.0f64, 0.0f64, 0);
    for [r, g, b, c] in &light {
        gathered += f64::from(r + g + b) / 3.0;
        covered += f64::from(*c);
        pixels_covered += (*c > 0.05) as usize;
    }
    let sender = gathered / (std::f64::consts::PI * covered);
    let indirect = s.indirect().unwrap();
    let mean_indirect = indirect
        .pixels
        .iter()
        .map(|p| f64::from(p[0] + p[1] + p[2]) / 3.0)
        .sum::<f64>()
        / indirect.pixels.len() as f64;
    let (sender_expected, indirect_expected) = (
        f64::from(albedo * le / (1.0 - albedo)),
        f64::from(albedo * albedo * le / (1.0 - albedo)),
    );
    eprintln!(
        "glowing box: {pixels_covered} of {} pixels over 5 % covered, mean coverage {:.3}; the screen's senders {sender:.4} (closed form {sender_expected:.4}); indirect {mean_indirect:.4} (closed form {indirect_expected:.4})",
        light.len(),
        covered / light.len() as f64
    );
    assert!(
        pixels_covered * 10 >= light.len(),
        "the screen should cover part of the lobe at a tenth of the pixels or more"
    );
    assert!(
        (sender - sender_expected).abs() <= 0.05 * sender_expected,
        "the screen's senders send {sender:.4}, not {sender_expected:.4}"
    );
    assert!(
        (mean_indirect - indirect_expected).abs() <= 0.05 * indirect_expected,
        "the hybrid's indirect light is {mean_indirect:.4}, not {indirect_expected:.4}"
    );
}

/// The screen takes from each surface its diffuse direct light, the share it sends every way:
/// on a metal Cornell box that is nothing, though the camera sees highlights; on the Lambertian
/// one it is all of the direct light.
#[test]
fn the_screen_gathers_only_the_light_surfaces_send_every_way() {
    let Some(ctx) = gpu() else { return };
    let lambertian = irradiant_scene::load("cornell").unwrap().scene;
    let mut metal = lambertian.clone();
    for m in &mut metal.materials {
        m.metallic = 1.0;
        m.roughness = 0.3;
    }
    let size = (32, 32);
    for (name, scene, diffuse_share) in [("Lambertian", &lambertian, 1.0), ("metal", &metal, 0.0)] {
        let mut s = session(
            &ctx,
            scene,
            size,
            TechniqueSpec::with_settings("ssil", &SsilSettings::fast()),
        );
        s.render().unwrap();
        let direct = s.direct().unwrap();
        let pyramid = read_level(&ctx, s.frame(), "pyramid_radiance", 0);
        let sum = |v: &mut dyn Iterator<Item = [f32; 3]>| -> f64 {
            v.map(|p| f64::from(p[0] + p[1] + p[2])).sum()
        };
        let seen = sum(&mut direct.pixels.iter().copied());
        let sent = sum(&mut pyramid.iter().map(|p| [p[0], p[1], p[2]]));
        eprintln!("{name} Cornell box: direct light {seen:.3}, sent every way {sent:.3}");
        assert!(seen > 1.0, "the {name} box should be lit");
        assert!(
            (sent - diffuse_share * seen).abs() <= 0.01 * seen,
            "the {name} box sends {sent:.3} every way of {seen:.3} direct light"
        );
    }
}

/// The screen covers a direction by the share of what its sender reflects that the sender
/// sends every way, and leaves the rest to the probes: it knows a sender's diffuse light, not
/// the light a glossy sender reflects toward the receiver. In a Cornell box whose white
/// surfaces are metal (roughness 0.3, their reflections traced by DDGI), the red and green
/// walls' near field holds only metal senders, which send nothing every way: the screen covers
/// nearly nothing, and the hybrid's light is DDGI's within 2 % at every pixel (0.8 % here: the
/// coarse levels' texels mix a wall's share with the metal's at the corners). Covered by the
/// senders' full cosine weight, the screen put their zero in the probes' place: 71 % from
/// DDGI here, and the glossy-floor Cornell box read FLIP 0.1078 against DDGI's 0.1032 (lavapipe,
/// 96×72; 0.1030 with the share).
#[test]
fn a_glossy_sender_leaves_its_direction_to_the_probes() {
    let Some(ctx) = gpu() else { return };
    let mut scene = irradiant_scene::load("cornell").unwrap().scene;
    for m in scene.materials.iter_mut().filter(|m| m.name == "white") {
        m.metallic = 1.0;
        m.roughness = 0.3;
    }
    let size = (48, 48);
    let indirect = |spec: TechniqueSpec| {
        let mut s = session(&ctx, &scene, size, spec);
        for _ in 0..8 {
            s.render().unwrap();
        }
        s.indirect().unwrap()
    };
    let ddgi = indirect(spec(Some(&DdgiSettings::balanced())));
    let hybrid = indirect(TechniqueSpec::with_settings(
        "ssil+ddgi",
        &HybridSettings::balanced(),
    ));
    let lit: f64 = ddgi
        .pixels
        .iter()
        .map(|p| f64::from(p[0] + p[1] + p[2]))
        .sum();
    let worst = largest_relative_difference(&ddgi, &hybrid);
    eprintln!(
        "white metal: DDGI's indirect light {lit:.3}; the hybrid's differs by at most {worst:e}"
    );
    assert!(lit > 1.0, "DDGI should light the metal box");
    assert!(
        worst <= 0.02,
        "the screen covered metal senders: {worst} from DDGI"
    );
}

/// The hybrid on the Cornell box, after 60 frames against the path tracer: far under SSIL alone,
/// and within 1 % of DDGI alone (at 64×64 the screen's coarse near field still costs 0.7 % of
/// FLIP; at 160×120 it gains 2.5 %, docs/ssil.md). The probes fill what the screen leaves
/// uncovered with their light around those directions' mean (`bent_fill`): the floor's screen
/// sees the bright walls beside it and its uncovered directions lean to the dim ceiling, so the
/// bent fill is nearer the path tracer than the probes' light taken as it is, which counts the
/// walls' light again (1.7 % more FLIP here).
#[test]
fn the_hybrid_stays_with_ddgi_on_the_cornell_box() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let reference = path_trace(&ctx, &scene, size, 512);
    let flip = |spec: TechniqueSpec| {
        let mut s = session(&ctx, &scene, size, spec);
        for _ in 0..60 {
            s.render().unwrap();
        }
        flip_mean(&reference, &s.image().unwrap())
    };
    let ddgi = flip(spec(Some(&DdgiSettings::balanced())));
    let ssil = flip(TechniqueSpec::with_settings(
        "ssil",
        &SsilSettings::balanced(),
    ));
    let hybrid = flip(TechniqueSpec::with_settings(
        "ssil+ddgi",
        &HybridSettings::balanced(),
    ));
    let mut even = HybridSettings::balanced();
    even.bent_fill = false;
    let even = flip(TechniqueSpec::with_settings("ssil+ddgi", &even));
    eprintln!(
        "Cornell box, FLIP: ddgi {ddgi:.4}, ssil {ssil:.4}, ssil+ddgi {hybrid:.4} \
         (the probes' light as it is: {even:.4})"
    );
    assert!(
        hybrid <= 1.01 * ddgi && hybrid < ssil,
        "ssil+ddgi {hybrid:.4} against ddgi {ddgi:.4} and ssil {ssil:.4}"
    );
    assert!(
        hybrid < even,
        "the bent fill {hybrid:.4} against the probes' light as it is {even:.4}"
    );
}

/// DDGI's traced reflections are added to the hybrid whole, after the screen's light: on the
/// glossy-floor Cornell box (`balanced`, reflections at half resolution) what turning them on
/// adds to the hybrid's indirect light is, at every pixel, what it adds to DDGI's. The screen's
/// coverage C is a share of the diffuse lobe; the fill used to scale the reflections by
/// (1 − C) with the probes' diffuse light (the lent GPU: relative MSE 0.01769 against DDGI's
/// 0.00369, docs/ssil.md). The screen's glossy gather is off in both hybrids here, so that
/// only the reflections differ.
#[test]
fn the_hybrid_adds_ddgis_reflections_whole() {
    let Some(ctx) = gpu() else { return };
    let path = repo_root().join("scenes/cornell-box/glossy-floor.toml");
    let scene = irradiant_scene::load(path.to_str().unwrap()).unwrap().scene;
    let size = (64, 64);
    let indirect = |spec: TechniqueSpec| {
        let mut s = session(&ctx, &scene, size, spec);
        for _ in 0..40 {
            s.render().unwrap();
        }
        s.indirect().unwrap()
    };
    let ddgi_alone = |reflections: bool| {
        let mut settings = DdgiSettings::balanced();
        settings.reflections.enabled = reflections;
        indirect(spec(Some(&settings)))
    };
    let hybrid = |reflections: bool| {
        let mut settings = HybridSettings::balanced();
        settings.ddgi.reflections.enabled = reflections;
        settings.ssil.glossy = false;
        indirect(TechniqueSpec::with_settings("ssil+ddgi", &settings))
    };
    let (ddgi_with, ddgi_without) = (ddgi_alone(true), ddgi_alone(false));
    let (hybrid_with, hybrid_without) = (hybrid(true), hybrid(false));
    let (mut reflected, mut largest) = (0.0f64, 0.0f32);
    for i in 0..ddgi_with.pixels.len() {
        for c in 0..3 {
            let by_ddgi = ddgi_with.pixels[i][c] - ddgi_without.pixels[i][c];
            let by_hybrid = hybrid_with.pixels[i][c] - hybrid_without.pixels[i][c];
            reflected += f64::from(by_ddgi);
            let apart = (by_hybrid - by_ddgi).abs() / (1e-3 + ddgi_with.pixels[i][c].abs());
            largest = largest.max(apart);
        }
    }
    eprintln!(
        "glossy floor: DDGI's reflections add {reflected:.3} in all; the hybrid's differ by at \
         most {largest:e} of a pixel's light"
    );
    assert!(reflected > 1.0, "the reflections should add light");
    assert!(
        largest <= 1e-3,
        "the hybrid adds DDGI's reflections {largest} apart from DDGI"
    );
}

/// While the probes' light is provisional (their first five frames, as they are placed) every
/// sender on screen counts (`far_field_while_young`): the mean FLIP of frames 0, 5 and 10 (TAA
/// off) is under DDGI's and under the near field's alone, which follows DDGI there; once the
/// probes have settled the reach is the near field's again, and so is the image after 120
/// frames (the screen's history restarts, so it holds no far field).
#[test]
fn the_screen_reaches_farther_while_the_probes_are_young() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let size = (64, 64);
    let reference = path_trace(&ctx, &scene, size, 512);
    // The mean FLIP of frames 0, 5 and 10, and the image after 120 frames.
    let run = |spec: TechniqueSpec| {
        let mut s = session(&ctx, &scene, size, spec);
        let mut early = Vec::new();
        for frame in 0..120 {
            s.render().unwrap();
            if frame < 30 && frame % 5 == 0 {
                early.push(flip_mean(&reference, &s.image().unwrap()));
            }
        }
        eprintln!("FLIP at frames 0, 5, …, 25: {early:.4?}");
        (early[..3].iter().sum::<f64>() / 3.0, s.image().unwrap())
    };
    let mut near_only = HybridSettings::balanced();
    near_only.far_field_while_young = false;
    let (ddgi, _) = run(spec(Some(&DdgiSettings::balanced())));
    let (young, settled) = run(TechniqueSpec::with_settings(
        "ssil+ddgi",
        &HybridSettings::balanced(),
    ));
    let (near, near_settled) = run(TechniqueSpec::with_settings("ssil+ddgi", &near_only));
    let apart = largest_relative_difference(&near_settled, &settled);
    eprintln!(
        "Cornell box, mean FLIP of frames 0, 5 and 10: ddgi {ddgi:.4}, ssil+ddgi {young:.4}, \
         near field only {near:.4}; after 120 frames the two hybrids differ by {apart:e}"
    );
    assert!(
        young < 0.95 * ddgi && young < 0.95 * near,
        "the first frames: ssil+ddgi {young:.4}, ddgi {ddgi:.4}, near field only {near:.4}"
    );
    assert!(
        apart <= 5e-3,
        "settled, the hybrid is {apart} from the near field's"
    );
}

/// The screen's glossy gather reflects only what nothing else does. In a Cornell box whose
/// white surfaces are metal (roughness 0.3, nothing sent every way), `ssil` with `glossy` off
/// gathers nothing on the metal: its light is the same as where the metal is black. On, it
/// reflects the red and green walls. In the hybrid it runs only on surfaces rougher than
/// DDGI's traced reflections reach (`reflections.max_roughness`): at 0.5 the rays reflect the
/// metal, and the hybrid's light is the same with the screen's glossy gather on or off; at
/// 0.2 they reflect none, and the screen's gather adds its reflections of the near field (the
/// senders within the hybrid's reach: about 2 % of what `ssil` alone reflects here).
#[test]
fn the_screens_glossy_gather_leaves_ddgis_reflections_alone() {
    let Some(ctx) = gpu() else { return };
    let box_with_white = |metal: bool| {
        let mut scene = irradiant_scene::load("cornell").unwrap().scene;
        for m in scene.materials.iter_mut().filter(|m| m.name == "white") {
            if metal {
                m.metallic = 1.0;
                m.roughness = 0.3;
            } else {
                m.base_color = glam::Vec4::new(0.0, 0.0, 0.0, 1.0);
            }
        }
        scene
    };
    let (metal, black) = (box_with_white(true), box_with_white(false));
    let size = (48, 48);
    let indirect = |scene: &irradiant_scene::Scene, spec: TechniqueSpec| {
        let mut s = session(&ctx, scene, size, spec);
        for _ in 0..6 {
            s.render().unwrap();
        }
        s.indirect().unwrap()
    };
    let total = |image: &Image| -> f64 {
        let sum = |p: &[f32; 3]| f64::from(p[0] + p[1] + p[2]);
        image.pixels.iter().map(sum).sum()
    };
    let ssil = |scene: &irradiant_scene::Scene, glossy: bool| {
        let mut settings = SsilSettings::balanced();
        settings.glossy = glossy;
        indirect(scene, TechniqueSpec::with_settings("ssil", &settings))
    };
    let (metal_on, metal_off) = (ssil(&metal, true), ssil(&metal, false));
    let as_black = largest_relative_difference(&ssil(&black, false), &metal_off);
    let reflected = total(&metal_on) - total(&metal_off);
    eprintln!(
        "metal box, ssil: glossy off differs from the black box by at most {as_black:e}; on, \
         it reflects {reflected:.3} of {:.3}",
        total(&metal_on)
    );
    assert!(
        as_black <= 1e-5,
        "with glossy off the screen gathered on the metal, {as_black} from the black box"
    );
    assert!(
        reflected > 0.05 * total(&metal_off),
        "the glossy gather should reflect the walls"
    );

    let hybrid = |glossy: bool, reflected_up_to: f32| {
        let mut settings = HybridSettings::balanced();
        settings.ssil.glossy = glossy;
        settings.ddgi.reflections.enabled = true;
        settings.ddgi.reflections.max_roughness = reflected_up_to;
        indirect(&metal, TechniqueSpec::with_settings("ssil+ddgi", &settings))
    };
    let traced = largest_relative_difference(&hybrid(false, 0.5), &hybrid(true, 0.5));
    let added = total(&hybrid(true, 0.2)) - total(&hybrid(false, 0.2));
    eprintln!(
        "ssil+ddgi: with the metal's reflections traced the glossy gather changes the light by \
         at most {traced:e}; with none traced it adds {added:.3}"
    );
    assert!(
        traced <= 1e-5,
        "the screen reflected surfaces DDGI traces, by {traced}"
    );
    assert!(
        added > 0.01 * reflected,
        "the screen's glossy gather added {added:.3} where DDGI traces no reflection"
    );
}
