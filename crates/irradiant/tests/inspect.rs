//! What a person sees of a technique beyond its image (the viewer's panel and inspector): each
//! setting's trade-off, the probe atlases, pyramid levels and voxel grids as pictures, the probes
//! coloured by state, and the scene's lights switched by hand.

mod common;

use common::*;
use glam::Vec3;
use irradiant::ddgi::DdgiSettings;
use irradiant::technique::ProbeView;
use irradiant::{Preset, TechniqueSpec};
use irradiant_scene::Light;

/// Every setting (and group) of every registered technique, at every preset, has a doc comment
/// the panel shows as its tooltip: what it does and what it trades.
#[test]
fn every_setting_of_every_technique_states_its_trade_off() {
    fn walk(
        table: &toml::Table,
        path: &mut Vec<String>,
        missing: &mut Vec<String>,
        kind: &dyn irradiant::technique::TechniqueKind,
        spec: &TechniqueSpec,
    ) {
        for (key, value) in table {
            path.push(key.clone());
            let parts: Vec<&str> = path.iter().map(String::as_str).collect();
            match kind.setting_doc(spec, &parts) {
                Some(doc) if doc.split_whitespace().count() >= 4 => {}
                other => missing.push(format!("{}.{}: {other:?}", spec.name, path.join("."))),
            }
            if let toml::Value::Table(group) = value {
                walk(group, path, missing, kind, spec);
            }
            path.pop();
        }
    }
    let mut missing = Vec::new();
    let mut settings = 0;
    for kind in irradiant::registry::REGISTRY {
        for preset in Preset::ALL {
            let spec = TechniqueSpec::new(kind.name(), preset);
            let table = kind.resolved_settings(&spec).unwrap();
            settings += table.len();
            walk(&table, &mut Vec::new(), &mut missing, *kind, &spec);
        }
    }
    assert!(settings > 20, "only {settings} settings found");
    assert!(
        missing.is_empty(),
        "settings without a trade-off: {missing:#?}"
    );
    let ddgi = irradiant::registry::find("ddgi").unwrap();
    let spec = TechniqueSpec::new("ddgi", Preset::Balanced);
    let doc = ddgi
        .setting_doc(&spec, &["volume", "rays_per_probe"])
        .unwrap();
    assert!(doc.contains("Rays per probe"), "{doc}");
    assert_eq!(
        ddgi.setting_doc(&spec, &["volume", "no_such_setting"]),
        None
    );
}

fn small_ddgi() -> TechniqueSpec {
    let mut settings = DdgiSettings::fast();
    settings.volume.rays_per_probe = 32;
    TechniqueSpec::with_settings("ddgi", &settings)
}

/// DDGI's inspection pictures both atlases and lists every probe with its tiles: a probe's
/// irradiance tile is the atlas's texels at its place, and the probes are the volume's.
#[test]
fn ddgi_inspection_shows_its_atlases_and_each_probes_tiles() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut s = session(&ctx, &scene, (32, 32), small_ddgi());
    for _ in 0..4 {
        s.render().unwrap();
    }
    let inspection = s.technique().inspect(&ctx).unwrap();
    let ddgi = s.technique_as::<irradiant::ddgi::Ddgi>().unwrap();
    let volume = ddgi.volume();
    assert_eq!(inspection.images.len(), 2);
    assert_eq!(inspection.probes.len(), volume.grid.probe_count as usize);
    let atlases = volume.read_atlases(&ctx).unwrap();
    let irradiance = &inspection.images[0];
    assert_eq!(
        (irradiance.width, irradiance.height),
        atlases.irradiance_size
    );
    assert_eq!(
        (inspection.images[1].width, inspection.images[1].height),
        atlases.distance_size
    );
    let centres = volume.read_probe_centres(&ctx).unwrap();
    let side = DdgiSettings::fast().volume.irradiance_texels + 2;
    let mut lit_tiles = 0;
    for (probe, (centre, _)) in inspection.probes.iter().zip(&centres) {
        assert_eq!(probe.position, *centre);
        let tile = irradiance.tile(probe.tile).unwrap();
        assert_eq!((tile.width, tile.height), (side, side));
        let (x0, y0) = (
            probe.tile % volume.atlas.probes_per_row * side,
            probe.tile / volume.atlas.probes_per_row * side,
        );
        let texel = atlases.irradiance[((y0 + 1) * atlases.irradiance_size.0 + x0 + 1) as usize];
        assert_eq!(
            tile.rgba8[4 * (side as usize + 1)..][..4],
            irradiant::inspect::radiance_pixel(texel),
            "probe {}'s first interior texel",
            probe.tile
        );
        lit_tiles += tile.rgba8.chunks(4).any(|p| p[0] > 0) as u32;
    }
    assert!(lit_tiles > 0, "after four frames some probe holds light");
}

/// SSIL's inspection pictures every level of its gathers and of its voxel grid, each level half
/// the one below.
#[test]
fn ssil_inspection_shows_each_level_of_its_gathers_and_voxels() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut settings = irradiant::ssil::SsilSettings::fast();
    settings.visibility = true;
    let spec = TechniqueSpec::with_settings("ssil", &settings);
    let mut s = session(&ctx, &scene, (64, 64), spec);
    s.render().unwrap();
    s.render().unwrap();
    let images = s.technique().inspect(&ctx).unwrap().images;
    let levels = images
        .iter()
        .filter(|i| i.name.starts_with("ssil/gather"))
        .count();
    assert!(levels >= 2, "{levels} gather levels");
    assert_eq!(
        images.len(),
        2 * levels,
        "a voxel level for each gather level"
    );
    for pair in images[..levels].windows(2) {
        assert_eq!(pair[1].width, pair[0].width.div_ceil(2).max(1));
    }
    // The Cornell box fills the view: the voxel grid has solid slices somewhere.
    let voxels = &images[levels];
    assert!(voxels.rgba8.chunks(4).any(|p| p[0] > 0), "{}", voxels.name);
}

/// The state view colours DDGI's probes by state (the Cornell box's probes are vigilant:
/// green), where the light view shows their irradiance.
#[test]
fn the_state_view_colours_the_probes_by_state() {
    let Some(ctx) = gpu() else { return };
    let scene = irradiant_scene::load("cornell").unwrap().scene;
    let mut s = session(&ctx, &scene, (48, 48), small_ddgi());
    let green = |s: &irradiant::Session| {
        let image = s.image().unwrap();
        image
            .pixels
            .iter()
            .filter(|p| p[1] > 0.5 && p[1] > 3.0 * p[0] && p[1] > 3.0 * p[2])
            .count()
    };
    s.set_probe_view(Some(ProbeView::Light));
    s.render().unwrap();
    let lit = green(&s);
    s.set_probe_view(Some(ProbeView::States));
    s.render().unwrap();
    let states = green(&s);
    assert!(
        states > lit + 10,
        "green pixels: {states} by state, {lit} by light"
    );
}

/// A light switched off by hand leaves the image the scene without it renders, and on again
/// the image with it; the pose says so.
#[test]
fn a_light_switched_off_by_hand_goes_dark() {
    let Some(ctx) = gpu() else { return };
    let bare = irradiant_scene::load("cornell").unwrap().scene;
    let mut lamp = bare.clone();
    lamp.lights.push(Light::point(
        "lamp",
        Vec3::new(0.3, 1.2, 0.3),
        Vec3::ONE,
        3.0,
    ));
    let none = TechniqueSpec::new("none", Preset::Balanced);
    let direct = |s: &mut irradiant::Session| {
        s.render().unwrap();
        s.direct().unwrap()
    };
    let mean = |i: &irradiant::frame::Image| {
        i.pixels.iter().map(|p| p[0] + p[1] + p[2]).sum::<f32>() / i.pixels.len() as f32
    };
    let without = direct(&mut session(&ctx, &bare, (32, 32), none.clone()));
    let mut s = session(&ctx, &lamp, (32, 32), none);
    let with = direct(&mut s);
    let lamp_index = lamp.lights.len() - 1;
    s.set_light_enabled(lamp_index, false);
    assert!(!s.light_enabled(lamp_index) && !s.pose().lights[lamp_index].enabled);
    let off = direct(&mut s);
    assert!(mean(&with) > 1.05 * mean(&without), "the lamp adds light");
    // The emitters are sampled stochastically, and a dark lamp still takes its share of the
    // samples: the means agree to within a tenth of what the lamp adds, not to the bit.
    let lamp_adds = mean(&with) - mean(&without);
    assert!(
        (mean(&off) - mean(&without)).abs() <= 0.1 * lamp_adds,
        "off: {} without the lamp: {} (it adds {lamp_adds})",
        mean(&off),
        mean(&without)
    );
    s.set_light_enabled(lamp_index, true);
    let on = direct(&mut s);
    assert!((mean(&on) - mean(&with)).abs() <= 0.1 * lamp_adds);
    // An index past the lights changes nothing.
    s.set_light_enabled(99, false);
    assert!(!s.light_enabled(99));
}
