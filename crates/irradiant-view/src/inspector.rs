//! The panel's tools beyond the settings: the truth beside the frame (progress, FLIP, how it
//! is shown), the probes and their states, the scene's lights, the passes' times as a live
//! chart with memory, and the inspector's window of the technique's state as pictures, with
//! the tiles of a probe picked by a click.

use std::collections::VecDeque;

use irradiant::inspect::DebugImage;
use irradiant::technique::ProbeView;

use crate::truth::TruthShow;
use crate::viewer::Viewer;

/// Frame times the chart keeps.
pub const FRAME_HISTORY: usize = 240;

/// What the tools keep between frames: the chart's frame times and the inspector's pictures
/// as egui textures.
#[derive(Default)]
pub struct ToolsState {
    /// Recent frame times, milliseconds, oldest first.
    pub frame_ms: VecDeque<f32>,
    /// The inspection the pictures were made from (its number) and the pictures.
    pictures: Option<(u64, Vec<egui::TextureHandle>)>,
    /// The picked probe's tiles.
    tiles: Option<PickedTiles>,
    /// The picture the inspector shows.
    chosen: usize,
}

/// The picked probe's tiles: (inspection, probe) and each tile's name and picture.
type PickedTiles = ((u64, usize), Vec<(String, egui::TextureHandle)>);

/// The truth: a button, the reference's progress, FLIP, and how it is shown.
pub fn truth(ui: &mut egui::Ui, viewer: &mut Viewer) {
    ui.separator();
    let label = if viewer.truth.is_some() {
        "truth off"
    } else {
        "truth beside the frame"
    };
    if ui
        .button(label)
        .on_hover_text(
            "key: T. The path-traced reference of this view (cached as irradiant compare caches it), against the technique",
        )
        .clicked()
    {
        let result = viewer.press("T");
        crate::ui::report(viewer, result);
    }
    let Some(truth) = &mut viewer.truth else {
        return;
    };
    let (done, all) = truth.progress();
    if truth.rendering() {
        ui.add(
            egui::ProgressBar::new(done as f32 / all.max(1) as f32)
                .text(format!("reference: {done} of {all} samples a pixel")),
        );
        return;
    }
    let Some(verdict) = truth.verdict().cloned() else {
        ui.add(egui::ProgressBar::new(1.0).text("comparing…").animate(true));
        return;
    };
    ui.label(format!(
        "{}: FLIP {:.4} mean, {:.4} at the 95th percentile{}",
        verdict.technique,
        verdict.flip_mean,
        verdict.flip_p95,
        if truth.cached {
            " (cached reference)"
        } else {
            ""
        }
    ));
    ui.horizontal(|ui| {
        for (show, name) in TruthShow::ALL {
            ui.selectable_value(&mut truth.show, show, name);
        }
    });
    if truth.show == TruthShow::Wipe {
        ui.add(egui::Slider::new(&mut truth.split, 0.0..=1.0).text("technique | reference"));
    }
}

/// The probes: how they are drawn, and how many are in each state.
pub fn probes(ui: &mut egui::Ui, viewer: &mut Viewer) {
    let mut view = viewer.probe_view;
    ui.horizontal(|ui| {
        ui.label("probes (P)");
        ui.selectable_value(&mut view, None, "off");
        ui.selectable_value(&mut view, Some(ProbeView::Light), "light")
            .on_hover_text("each probe a sphere lit by what it stores");
        ui.selectable_value(&mut view, Some(ProbeView::States), "states").on_hover_text(
            "vigilant green, awake orange, sleeping blue, off red, newly vigilant pale green, newly awake yellow, tied magenta; a white line from the grid point to where relocation moved the probe",
        );
        ui.selectable_value(&mut view, Some(ProbeView::Volumes), "volumes")
            .on_hover_text("each pixel coloured by the volumes that light it: the finest red, then green, blue; mixed where they blend");
    });
    if view != viewer.probe_view {
        viewer.set_probe_view(view);
    }
    let counter = |name: &str| {
        viewer
            .counters
            .iter()
            .find(|c| c.0 == name)
            .map(|c| c.1 as u64)
    };
    if let (Some(v), Some(a), Some(s), Some(o)) = (
        counter("probes_vigilant"),
        counter("probes_awake"),
        counter("probes_sleeping"),
        counter("probes_off"),
    ) {
        let newly = counter("probes_newly_vigilant").unwrap_or(0)
            + counter("probes_newly_awake").unwrap_or(0);
        ui.label(format!(
            "probes: {v} vigilant, {a} awake, {newly} newly, {s} sleeping, {o} off"
        ));
    }
}

/// The scene's lights, each switched on and off live.
pub fn lights(ui: &mut egui::Ui, viewer: &mut Viewer) {
    let names: Vec<String> = (viewer.session.scene().lights.iter())
        .map(|l| l.name.clone())
        .collect();
    if names.is_empty() {
        return;
    }
    egui::CollapsingHeader::new(format!("lights ({})", names.len())).show(ui, |ui| {
        for (i, name) in names.iter().enumerate() {
            let mut on = viewer.session.light_enabled(i);
            let label = if name.is_empty() {
                format!("light {i}")
            } else {
                name.clone()
            };
            if ui.checkbox(&mut on, label).changed() {
                let result = viewer.set_light(i, on);
                crate::ui::report(viewer, result);
            }
        }
    });
}

/// The passes' GPU times (table and live chart), frame times and memory.
pub fn timings(ui: &mut egui::Ui, viewer: &Viewer, state: &mut ToolsState, frame_ms: f64) {
    state.frame_ms.push_back(frame_ms as f32);
    while state.frame_ms.len() > FRAME_HISTORY {
        state.frame_ms.pop_front();
    }
    ui.separator();
    ui.label(format!(
        "GPU memory: {:.1} MiB (frame, technique{})",
        viewer.memory_bytes as f64 / (1 << 20) as f64,
        if viewer.truth.is_some() {
            ", truth"
        } else {
            ""
        }
    ));
    chart(ui, &state.frame_ms, &viewer.timing_history);
    if viewer.timings.is_empty() {
        return;
    }
    let total: f64 = viewer.timings.iter().map(|t| t.1).sum();
    egui::CollapsingHeader::new(format!("GPU passes: {total:.3} ms"))
        .default_open(true)
        .show(ui, |ui| {
            egui::Grid::new("passes").striped(true).show(ui, |ui| {
                for (label, ms) in &viewer.timings {
                    ui.label(label);
                    ui.label(format!("{ms:.3} ms"));
                    ui.end_row();
                }
            });
        });
}

/// Frame time (white, every frame) and the passes' GPU total (orange, every timed frame) over
/// the last seconds, on one scale.
fn chart(ui: &mut egui::Ui, frames: &VecDeque<f32>, gpu: &VecDeque<f64>) {
    let (rect, _) =
        ui.allocate_exact_size(egui::vec2(ui.available_width(), 60.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, egui::Color32::from_black_alpha(120));
    let top = (frames.iter().copied())
        .chain(gpu.iter().map(|&g| g as f32))
        .fold(1.0f32, f32::max)
        * 1.1;
    let line = |values: Vec<f32>, colour: egui::Color32| {
        if values.len() < 2 {
            return;
        }
        let step = rect.width() / (values.len() - 1) as f32;
        let points = (values.iter().enumerate())
            .map(|(i, v)| {
                egui::pos2(
                    rect.left() + i as f32 * step,
                    rect.bottom() - v / top * rect.height(),
                )
            })
            .collect();
        painter.add(egui::Shape::line(points, egui::Stroke::new(1.5, colour)));
    };
    line(frames.iter().copied().collect(), egui::Color32::WHITE);
    line(
        gpu.iter().map(|&g| g as f32).collect(),
        egui::Color32::from_rgb(255, 160, 40),
    );
    painter.text(
        rect.left_top() + egui::vec2(4.0, 2.0),
        egui::Align2::LEFT_TOP,
        format!("{top:.1} ms  frame (white), GPU passes (orange)"),
        egui::FontId::proportional(11.0),
        egui::Color32::LIGHT_GRAY,
    );
}

fn texture(ctx: &egui::Context, image: &DebugImage) -> egui::TextureHandle {
    let colour = egui::ColorImage::from_rgba_unmultiplied(
        [image.width as usize, image.height as usize],
        &image.rgba8,
    );
    // Nearest: a texel stays a texel when the picture is enlarged.
    ctx.load_texture(&image.name, colour, egui::TextureOptions::NEAREST)
}

/// The inspector's window (`I`): the technique's state as pictures, and the picked probe's
/// tiles (a click on a probe in the frame picks it).
pub fn inspector(ui: &mut egui::Ui, viewer: &mut Viewer, state: &mut ToolsState) {
    let Some(inspection) = &viewer.inspection else {
        return;
    };
    let number = viewer.inspections;
    if state.pictures.as_ref().is_none_or(|(n, _)| *n != number) {
        let pictures = inspection
            .images
            .iter()
            .map(|i| texture(ui.ctx(), i))
            .collect();
        state.pictures = Some((number, pictures));
        state.chosen = 0;
    }
    let picked = viewer
        .picked
        .and_then(|p| inspection.probes.get(p).map(|probe| (p, probe)));
    if let Some((index, probe)) = picked
        && state
            .tiles
            .as_ref()
            .is_none_or(|(k, _)| *k != (number, index))
    {
        let (first, count) = probe.images;
        let tiles = (inspection.images[first..first + count].iter())
            .filter_map(|image| image.tile(probe.tile))
            .map(|tile| (tile.name.clone(), texture(ui.ctx(), &tile)))
            .collect();
        state.tiles = Some(((number, index), tiles));
    }
    let Some((_, pictures)) = &state.pictures else {
        return;
    };
    let mut open = true;
    // At the right, clear of the panel on the left.
    let right = ui.ctx().content_rect().right();
    egui::Window::new("inspector")
        .open(&mut open)
        .default_pos(egui::pos2(right - 380.0, 10.0))
        .default_width(360.0)
        .show(ui.ctx(), |ui| {
            let names: Vec<&str> = inspection.images.iter().map(|i| i.name.as_str()).collect();
            egui::ComboBox::from_label("picture")
                .selected_text(names.get(state.chosen).copied().unwrap_or(""))
                .show_ui(ui, |ui| {
                    for (i, name) in names.iter().enumerate() {
                        ui.selectable_value(&mut state.chosen, i, *name);
                    }
                });
            if let Some(picture) = pictures.get(state.chosen) {
                // Within 360×200 points, at the picture's aspect.
                let [w, h] = picture.size().map(|v| v.max(1) as f32);
                let scale = (360.0 / w).min(200.0 / h);
                ui.add(egui::Image::new(picture).fit_to_exact_size(egui::vec2(w, h) * scale));
            }
            match (picked, &state.tiles) {
                (Some((index, probe)), Some((_, tiles))) => {
                    ui.label(format!(
                        "probe {index} at ({:.2}, {:.2}, {:.2})",
                        probe.position.x, probe.position.y, probe.position.z
                    ));
                    ui.horizontal_wrapped(|ui| {
                        for (name, tile) in tiles {
                            ui.add(
                                egui::Image::new(tile).fit_to_exact_size(egui::vec2(96.0, 96.0)),
                            )
                            .on_hover_text(name);
                        }
                    });
                }
                _ if !inspection.probes.is_empty() => {
                    ui.label("click a probe in the frame (P draws them) to see its tiles");
                }
                _ => {}
            }
        });
    if !open {
        viewer.inspection = None;
        viewer.picked = None;
    }
}
