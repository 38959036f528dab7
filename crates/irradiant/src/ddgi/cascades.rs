//! Cascades (issue 39): nested volumes that follow the camera at doubling spacing, from one
//! setting (`technique.volume.cascades`), and the schedule that keeps their rays a frame at two
//! cascades' worth.

use irradiant_scene::{ProbeVolumeDesc, Scene};

use super::settings::DdgiVolumeSettings;

/// `cascades` volumes following the camera, centred on `eye` to start with: cascade i at
/// `cascade_spacing` × 2^i, each on its own lattice of whole cells (so a coarser cascade's
/// probes sit on finer ones').
pub fn descs(eye: glam::Vec3, v: &DdgiVolumeSettings) -> Vec<ProbeVolumeDesc> {
    let counts = glam::UVec3::from(v.cascade_probes);
    (0..v.cascades)
        .map(|i| {
            let spacing = v.cascade_spacing * (1u32 << i) as f32;
            let extent = (counts.as_vec3() - 1.0) * spacing;
            let min = ((eye - extent * 0.5) / spacing).round() * spacing;
            ProbeVolumeDesc {
                follow: Some(irradiant_scene::Follow::Camera),
                ..ProbeVolumeDesc::new(&format!("cascade{i}"), min, min + extent, v.cascade_probes)
            }
        })
        .collect()
}

/// Whether cascade `index` (0: the finest) of `cascades` updates on frame `frame` (from 0):
/// the finest every frame; with n = frame + 1, cascade i ≥ 1 where n's lowest set bit is i − 1
/// (every 2^i frames), and the coarsest wherever it is i − 1 or higher. Each frame updates the
/// finest and exactly one other.
pub fn updates(index: u32, cascades: u32, frame: u64) -> bool {
    if index == 0 {
        return true;
    }
    let lowest_bit = (frame + 1).trailing_zeros();
    if index + 1 == cascades {
        lowest_bit >= index - 1
    } else {
        lowest_bit == index - 1
    }
}

/// Refuses a volume that follows an instance the scene lacks: from the settings
/// (`technique.volume.follow`; a manifest's own is refused when the scene loads).
pub fn check_follow(scene: &Scene, descs: &[ProbeVolumeDesc]) -> Result<(), crate::RenderError> {
    for d in descs {
        if let Some(irradiant_scene::Follow::Instance(name)) = &d.follow
            && !scene.instances.iter().any(|i| &i.name == name)
        {
            let names: Vec<&str> = scene.instances.iter().map(|i| i.name.as_str()).collect();
            return Err(crate::RenderError::Settings(format!(
                "technique.volume.follow = \"{name}\" is neither \"camera\" nor an instance of the scene (its instances: {}): write \"camera\", an instance's name, or \"\" for volumes that stay",
                names.join(", ")
            )));
        }
    }
    Ok(())
}

/// Warnings for volumes that follow the camera yet already span the whole scene (they would
/// only step, paying for entering planes, to light what they cover anyway).
pub fn window_warnings(scene: &Scene, descs: &[ProbeVolumeDesc], cascades: u32) -> Vec<String> {
    let (lo, hi) = scene.bounds();
    let scene_extent = hi - lo;
    let covers = |d: &ProbeVolumeDesc| (d.max - d.min).cmpge(scene_extent).all();
    if cascades > 0 {
        return descs
            .first()
            .filter(|finest| covers(finest))
            .map(|finest| {
                format!(
                    "technique.volume.cascades = {cascades}: the finest cascade ({}) already spans the whole scene ({}); fewer cascade_probes, a finer cascade_spacing, or the scene's own volumes (cascades = 0) light it at less cost",
                    extent_text(finest.max - finest.min),
                    extent_text(scene_extent)
                )
            })
            .into_iter()
            .collect();
    }
    descs
        .iter()
        .filter(|d| d.follow.is_some() && covers(d))
        .map(|d| {
            format!(
                "probe volume '{}' follows the camera but spans the whole scene ({} against {}): it would only step; leave out `follow` (technique.volume.follow = \"\")",
                d.name,
                extent_text(d.max - d.min),
                extent_text(scene_extent)
            )
        })
        .collect()
}

/// A warning for each pair of the scene's volumes that overlap at the same spacing: where they
/// do, the one listed first lights alone (volumes resolve finest first, 003 §7.4), so the
/// other's probes there trace for nothing — usually two boxes meant to meet, not overlap.
pub fn overlap_warnings(descs: &[ProbeVolumeDesc]) -> Vec<String> {
    let spacing = |d: &ProbeVolumeDesc| {
        (d.max - d.min) / (glam::UVec3::from(d.counts).as_vec3() - 1.0).max(glam::Vec3::ONE)
    };
    let mut warnings = Vec::new();
    for (i, a) in descs.iter().enumerate() {
        for b in &descs[i + 1..] {
            let overlap = a.min.max(b.min).cmplt(a.max.min(b.max)).all();
            let same = (spacing(a) - spacing(b))
                .abs()
                .cmple(spacing(a) * 0.01)
                .all();
            if overlap && same && a.follow.is_none() && b.follow.is_none() {
                warnings.push(format!(
                    "probe volumes '{}' and '{}' overlap at the same spacing: where they do, '{}' lights alone and the probes of '{}' there trace for nothing; let their boxes meet instead (the manifest's [[probe_volume]] min and max)",
                    a.name, b.name, a.name, b.name
                ));
            }
        }
    }
    warnings
}

fn extent_text(e: glam::Vec3) -> String {
    format!("{:.1} × {:.1} × {:.1} m", e.x, e.y, e.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// Every frame updates the finest cascade and exactly one other; cascade i ≥ 1 (not the
    /// coarsest) every 2^i frames, the coarsest every 2^(n−2).
    #[test]
    fn each_frame_updates_the_finest_cascade_and_one_other() {
        for n in 2..=8u32 {
            let mut counts = vec![0u64; n as usize];
            for frame in 0..1024u64 {
                let updated: Vec<u32> = (0..n).filter(|&i| updates(i, n, frame)).collect();
                assert_eq!(updated.len(), 2, "{n} cascades, frame {frame}: {updated:?}");
                assert_eq!(updated[0], 0);
                for i in updated {
                    counts[i as usize] += 1;
                }
            }
            for (i, &count) in counts.iter().enumerate().skip(1) {
                let interval = if i + 1 == n as usize {
                    1 << (n - 2)
                } else {
                    1 << i
                };
                assert_eq!(count, 1024 / interval, "{n} cascades, cascade {i}");
            }
        }
    }

    /// Each cascade is centred on the eye within half a cell, twice the spacing of the last, on
    /// a lattice of its own spacing: a coarser cascade's probes sit on finer ones' lattice.
    #[test]
    fn cascades_nest_around_the_eye_at_doubling_spacing() {
        let settings = DdgiVolumeSettings {
            cascades: 3,
            cascade_spacing: 0.5,
            cascade_probes: [8, 4, 8],
            ..super::super::DdgiSettings::balanced().volume
        };
        let eye = Vec3::new(13.3, 1.7, -42.1);
        let descs = descs(eye, &settings);
        assert_eq!(descs.len(), 3);
        for (i, d) in descs.iter().enumerate() {
            let spacing = 0.5 * (1 << i) as f32;
            let grid = crate::probes::ProbeGrid::new(d);
            assert!((grid.spacing - Vec3::splat(spacing)).abs().max_element() < 1e-4);
            let (lo, hi) = grid.bounds();
            assert!(((lo + hi) * 0.5 - eye).abs().max_element() <= spacing * 0.5 + 1e-4);
            let on_lattice = grid.origin / 0.5;
            assert!((on_lattice - on_lattice.round()).abs().max_element() < 1e-3);
            assert_eq!(d.follow, Some(irradiant_scene::Follow::Camera));
        }
    }

    /// A window or a finest cascade that spans the whole scene is warned about, naming the
    /// setting; one that spans part of it is not.
    #[test]
    fn a_window_larger_than_the_scene_is_warned_about() {
        let scene = irradiant_scene::load("cornell").unwrap().scene;
        let mut settings = super::super::DdgiSettings::balanced().volume;
        settings.cascades = 2;
        settings.cascade_spacing = 0.5;
        let big = descs(Vec3::ONE, &settings);
        let warnings = window_warnings(&scene, &big, 2);
        assert!(
            warnings.len() == 1 && warnings[0].contains("technique.volume.cascades"),
            "{warnings:?}"
        );
        settings.cascade_spacing = 0.05;
        assert!(window_warnings(&scene, &descs(Vec3::ONE, &settings), 2).is_empty());
        let mut window = scene.probe_volumes[0].clone();
        window.min -= Vec3::splat(5.0);
        window.max += Vec3::splat(5.0);
        window.follow = Some(irradiant_scene::Follow::Camera);
        let warnings = window_warnings(&scene, &[window.clone()], 0);
        assert!(
            warnings[0].contains("'box' follows the camera"),
            "{warnings:?}"
        );
        window.follow = None;
        assert!(window_warnings(&scene, &[window], 0).is_empty());
    }

    /// Two volumes of one spacing that overlap are warned of by name; nested volumes of
    /// different spacing, and volumes that only meet, are not.
    #[test]
    fn volumes_that_overlap_at_one_spacing_are_warned_of() {
        let v = |name: &str, min: f32, max: f32, counts: u32| {
            ProbeVolumeDesc::new(name, Vec3::splat(min), Vec3::splat(max), [counts; 3])
        };
        let warned = overlap_warnings(&[v("a", 0.0, 4.0, 5), v("b", 2.0, 6.0, 5)]);
        assert_eq!(warned.len(), 1);
        assert!(warned[0].contains("'a' and 'b'"), "{warned:?}");
        assert!(overlap_warnings(&[v("fine", 1.0, 3.0, 9), v("coarse", 0.0, 8.0, 5)]).is_empty());
        assert!(overlap_warnings(&[v("a", 0.0, 4.0, 5), v("b", 4.0, 8.0, 5)]).is_empty());
    }
}
