//! The viewer's panel: what is shown and on what, the technique and its preset, every setting
//! of it as the technique resolves it (checkboxes, numbers, text), the animation, the passes'
//! GPU times, and the actions of the keys as buttons. Settings are built from the technique's
//! resolved settings table, so a new setting appears without a line here.

use std::path::PathBuf;

use crate::viewer::{PATH, Viewer};

/// The keys, as the help overlay (F1) lists them.
pub const KEYS: &[(&str, &str)] = &[
    ("W A S D", "fly forward, left, back, right"),
    ("Q E", "down, up"),
    ("Shift", "fly four times faster"),
    ("right mouse button", "look around while held"),
    ("wheel", "fly faster or slower"),
    (
        "1 … 9",
        "switch technique (the panel's list; the last is the path tracer)",
    ),
    (
        "Space",
        "the path-traced reference on and off (accumulates while the camera rests)",
    ),
    (
        "T",
        "the truth beside the frame: the path-traced reference as a wipe, difference or FLIP map",
    ),
    ("F", "frame the whole scene"),
    ("P", "draw the probes: lit, by state, off"),
    (
        "I",
        "inspect the technique's state (atlases, levels); click a probe for its tiles",
    ),
    ("F12", "screenshot (PNG as shown, and linear EXR)"),
    (
        "B",
        "bookmark the view (a camera file for render --camera-from)",
    ),
    (
        "R",
        "restart on a new device, after the GPU device was lost",
    ),
    ("F1", "this help"),
    ("Esc", "quit"),
];

/// What the panel keeps between frames.
#[derive(Default)]
pub struct PanelState {
    /// The path "save settings as…" writes to.
    pub settings_path: String,
    /// The chart's history and the inspector's pictures.
    pub tools: crate::inspector::ToolsState,
}

/// Draws the panel and the help overlay, and applies what the person changed.
pub fn draw(ui: &mut egui::Ui, viewer: &mut Viewer, state: &mut PanelState, frame_ms: f64) {
    // Translucent: the frame stays visible under the panel, at the window's full size.
    let frame = egui::Frame::side_top_panel(ui.style()).fill(egui::Color32::from_black_alpha(170));
    egui::Panel::left("irradiant")
        .resizable(true)
        .default_size(260.0)
        .frame(frame)
        .show(ui, |ui| {
            egui::ScrollArea::vertical().show(ui, |ui| panel(ui, viewer, state, frame_ms));
        });
    crate::inspector::inspector(ui, viewer, &mut state.tools);
    if viewer.show_help {
        egui::Window::new("Keys")
            .collapsible(false)
            .show(ui.ctx(), |ui| {
                egui::Grid::new("keys").striped(true).show(ui, |ui| {
                    for (key, what) in KEYS {
                        ui.strong(*key);
                        ui.label(*what);
                        ui.end_row();
                    }
                });
            });
    }
}

fn panel(ui: &mut egui::Ui, viewer: &mut Viewer, state: &mut PanelState, frame_ms: f64) {
    let scene = viewer.session.scene().name.clone();
    let (w, h) = viewer.session.frame().size();
    ui.heading("Irradiant");
    ui.label(format!("{scene} at {w}×{h} on {}", viewer.ctx().info.name));
    ui.label(format!(
        "frame {:.2} ms ({:.0} fps), {} frames",
        frame_ms,
        1e3 / frame_ms.max(1e-3),
        viewer.frames
    ));
    if viewer.path_tracing() {
        ui.label(format!(
            "path tracer: {} samples a pixel",
            viewer.path_samples()
        ));
    }
    ui.separator();
    let mut chosen = viewer.technique().to_owned();
    egui::ComboBox::from_label("technique")
        .selected_text(&chosen)
        .show_ui(ui, |ui| {
            for (i, name) in viewer.techniques.iter().enumerate() {
                ui.selectable_value(&mut chosen, name.clone(), format!("{} {name}", i + 1));
            }
        });
    if chosen != viewer.technique() {
        let result = viewer.switch_to(&chosen);
        report(viewer, result);
    }
    if !viewer.path_tracing() {
        let mut view = viewer.debug_view;
        egui::ComboBox::from_label("show")
            .selected_text(crate::viewer::DEBUG_VIEWS[view].0)
            .show_ui(ui, |ui| {
                for (i, (name, ..)) in crate::viewer::DEBUG_VIEWS.iter().enumerate() {
                    ui.selectable_value(&mut view, i, *name);
                }
            });
        viewer.debug_view = view;
    }
    if !viewer.path_tracing() && viewer.technique() != PATH {
        settings(ui, viewer, state);
    }
    ui.separator();
    ui.horizontal(|ui| {
        for (label, key) in [
            ("path tracer", "Space"),
            ("frame scene", "F"),
            ("inspect", "I"),
            ("screenshot", "F12"),
            ("bookmark", "B"),
        ] {
            if ui
                .button(label)
                .on_hover_text(format!("key: {key}"))
                .clicked()
            {
                let result = viewer.press(key);
                report(viewer, result);
            }
        }
    });
    if !viewer.path_tracing() {
        crate::inspector::truth(ui, viewer);
        crate::inspector::probes(ui, viewer);
    }
    crate::inspector::lights(ui, viewer);
    animation(ui, viewer);
    crate::inspector::timings(ui, viewer, &mut state.tools, frame_ms);
    if !viewer.status.is_empty() {
        ui.separator();
        ui.label(&viewer.status);
    }
}

/// The preset, every resolved setting, and "save settings as…".
fn settings(ui: &mut egui::Ui, viewer: &mut Viewer, state: &mut PanelState) {
    let spec = viewer.session.spec().clone();
    ui.horizontal(|ui| {
        ui.label("preset");
        for preset in irradiant::Preset::ALL {
            if ui
                .selectable_label(spec.preset == preset, preset.name())
                .clicked()
                && spec.preset != preset
            {
                let mut changed = spec.clone();
                changed.preset = preset;
                let result = viewer.apply(changed);
                report(viewer, result);
            }
        }
    });
    let table = match spec.kind().and_then(|k| k.resolved_settings(&spec)) {
        Ok(table) => table,
        Err(e) => {
            ui.colored_label(egui::Color32::RED, e.to_string());
            return;
        }
    };
    let mut edit: Option<(Vec<String>, toml::Value)> = None;
    let kind = spec.kind().ok();
    let doc = |path: &[String]| -> Option<&'static str> {
        let parts: Vec<&str> = path.iter().map(String::as_str).collect();
        kind?.setting_doc(&spec, &parts)
    };
    egui::CollapsingHeader::new("settings")
        .default_open(true)
        .show(ui, |ui| {
            setting_rows(ui, &table, &mut Vec::new(), &doc, &mut edit)
        });
    if let Some((key, value)) = edit {
        let mut changed = spec.clone();
        irradiant::settings::set_path(&mut changed.settings, &key, value);
        let result = viewer.apply(changed);
        report(viewer, result);
    }
    ui.horizontal(|ui| {
        if state.settings_path.is_empty() {
            state.settings_path = viewer.out_dir.join("settings.toml").display().to_string();
        }
        let label = ui.label("file");
        ui.add(egui::TextEdit::singleline(&mut state.settings_path).desired_width(120.0))
            .labelled_by(label.id);
        if ui
            .button("save settings as…")
            .on_hover_text("a settings file for irradiant render --settings")
            .clicked()
        {
            let result = viewer.save_settings(&PathBuf::from(&state.settings_path));
            report(viewer, result);
        }
    });
}

/// One row a setting, its doc comment (what it does, what it trades) as its tooltip; a
/// group's settings under its name. A change is applied when a drag ends or a field is left,
/// so that a setting that rebuilds the technique rebuilds once.
fn setting_rows(
    ui: &mut egui::Ui,
    table: &toml::Table,
    path: &mut Vec<String>,
    doc: &dyn Fn(&[String]) -> Option<&'static str>,
    edit: &mut Option<(Vec<String>, toml::Value)>,
) {
    for (key, value) in table {
        path.push(key.clone());
        let id = path.join(".");
        let tooltip = doc(path).unwrap_or("");
        match value {
            toml::Value::Table(group) => {
                egui::CollapsingHeader::new(key)
                    .id_salt(&id)
                    .show(ui, |ui| setting_rows(ui, group, path, doc, edit))
                    .header_response
                    .on_hover_text(tooltip);
            }
            toml::Value::Boolean(b) => {
                let mut v = *b;
                if ui.checkbox(&mut v, key).on_hover_text(tooltip).changed() {
                    *edit = Some((path.clone(), v.into()));
                }
            }
            toml::Value::Integer(i) => {
                if let Some(v) = number(ui, key, &id, *i as f64, 1.0, tooltip) {
                    *edit = Some((path.clone(), (v.round() as i64).into()));
                }
            }
            toml::Value::Float(f) => {
                let speed = (f.abs() * 0.01).max(1e-3);
                if let Some(v) = number(ui, key, &id, *f, speed, tooltip) {
                    *edit = Some((path.clone(), v.into()));
                }
            }
            other => {
                let id = ui.make_persistent_id(("setting", &id));
                let mut text = ui
                    .data(|d| d.get_temp::<String>(id))
                    .unwrap_or_else(|| other.to_string());
                let r = ui
                    .horizontal(|ui| {
                        let label = ui.label(key).on_hover_text(tooltip);
                        ui.text_edit_singleline(&mut text)
                            .labelled_by(label.id)
                            .on_hover_text(tooltip)
                    })
                    .inner;
                if r.lost_focus() {
                    ui.data_mut(|d| d.remove::<String>(id));
                    if let Ok(t) = toml::from_str::<toml::Table>(&format!("v = {text}"))
                        && let Some(v) = t.get("v")
                        && v != other
                    {
                        *edit = Some((path.clone(), v.clone()));
                    }
                } else {
                    ui.data_mut(|d| d.insert_temp(id, text));
                }
            }
        }
        path.pop();
    }
}

/// A number's drag field. While it is dragged the value lives in egui's memory; the new value
/// is returned once, when the drag ends or a typed value is entered.
fn number(
    ui: &mut egui::Ui,
    key: &str,
    id: &str,
    value: f64,
    speed: f64,
    tooltip: &str,
) -> Option<f64> {
    let id = ui.make_persistent_id(("setting", id));
    let mut v = ui.data(|d| d.get_temp::<f64>(id)).unwrap_or(value);
    let r = ui
        .add(
            egui::DragValue::new(&mut v)
                .speed(speed)
                .prefix(format!("{key}: ")),
        )
        .on_hover_text(tooltip);
    if r.dragged() {
        ui.data_mut(|d| d.insert_temp(id, v));
        return None;
    }
    ui.data_mut(|d| d.remove::<f64>(id));
    (v != value).then_some(v)
}

fn animation(ui: &mut egui::Ui, viewer: &mut Viewer) {
    let end = viewer.session.scene().animation_end();
    if end <= 0.0 {
        return;
    }
    ui.separator();
    ui.horizontal(|ui| {
        ui.checkbox(&mut viewer.playing, "play");
        ui.add(egui::Slider::new(&mut viewer.speed, 0.0..=4.0).text("speed"));
    });
    let mut time = viewer.session.time();
    if ui
        .add(egui::Slider::new(&mut time, 0.0..=end + 1.0).text("time, s"))
        .changed()
    {
        viewer.session.seek(time);
    }
}

/// An action's error into the status line, in words: the panel never panics on bad input.
pub fn report(viewer: &mut Viewer, result: Result<(), crate::ViewError>) {
    if let Err(e) = result {
        viewer.status = format!("error: {e}");
    }
}
