//! `irradiant view --script FILE`: the viewer's event loop run without a person, step by step —
//! for tests, for captures and for measuring the viewer on a machine with no display.
//!
//! ```toml
//! [[step]]
//! technique = "ddgi{preset = \"quality\"}"   # switch technique (a spec, as on the command line)
//! [[step]]
//! camera = { position = [0, 1, 3.4], target = [0, 1, 0] }   # jump to a view
//! [[step]]
//! move = { forward = 1.0, seconds = 0.5 }   # fly, as WASD/QE would
//! [[step]]
//! key = "Space"                             # press a key: Space, T, I, F, P, B, R, F1, F12, 1…9
//! [[step]]
//! show = "normal"                            # a debug view: final, direct, indirect, normal, …
//! [[step]]
//! light = { index = 0, on = false }          # switch one of the scene's lights
//! [[step]]
//! truth = "flip"                             # how the truth (T) is shown: wipe, difference, flip
//! [[step]]
//! wait = "truth"                             # render until the truth is compared
//! [[step]]
//! click = [320, 180]                         # click a pixel: picks a probe in the inspector (I)
//! [[step]]
//! lose_device = true                         # destroy the device, as a driver reset would
//! [[step]]
//! frames = 30                                # render this many frames
//! [[step]]
//! screenshot = "ddgi.png"                    # the frame as shown (.png) or linear (.exr)
//! [[step]]
//! capture = "panel.png"                      # the frame with the panel over it (--offscreen)
//! [[step]]
//! quit = true
//! ```
//!
//! Each step does one thing; a script ends with a quit, or quits after its last step.

use std::path::{Path, PathBuf};

use irradiant_scene::{Camera, CameraDesc};
use serde::Deserialize;

use crate::ViewError;

/// Frames a `frames` step may ask for: a script is for tests and captures, not soaks.
pub const MAX_SCRIPT_FRAMES: u32 = 100_000;

/// What one step of a script does.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    /// Switch to a technique spec (`name{key = value}`) or `path`.
    Technique(String),
    /// Jump to a view.
    Camera(Camera),
    /// Fly for some seconds with keys held.
    Move(crate::camera::Movement, f32),
    /// Press a key, as a person would.
    Key(String),
    /// Show one of the frame's debug views (`final`, `direct`, `indirect`, `normal`, …).
    Show(String),
    /// Render this many frames.
    Frames(u32),
    /// Save the frame as shown.
    Screenshot(PathBuf),
    /// Save the next frame with the panel over it (offscreen only).
    Capture(PathBuf),
    /// Switch the scene's light `index` on or off.
    Light(usize, bool),
    /// Show the truth this way.
    Truth(crate::truth::TruthShow),
    /// Render frames until the truth is compared.
    WaitTruth,
    /// Click the frame at a pixel (picks a probe in the inspector).
    Click(f32, f32),
    /// Destroy the device (tests the lost-device restart).
    LoseDevice,
    /// Close the viewer.
    Quit,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    step: Vec<StepDesc>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct StepDesc {
    technique: Option<String>,
    camera: Option<CameraDesc>,
    #[serde(rename = "move")]
    movement: Option<MoveDesc>,
    key: Option<String>,
    show: Option<String>,
    frames: Option<u32>,
    screenshot: Option<PathBuf>,
    capture: Option<PathBuf>,
    quit: Option<bool>,
    light: Option<LightDesc>,
    truth: Option<String>,
    wait: Option<String>,
    click: Option<[f32; 2]>,
    lose_device: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightDesc {
    index: usize,
    on: bool,
}

/// What a step can be, for the messages.
const STEP_KINDS: &str = "technique, camera, move, key, show, frames, screenshot, capture, light, truth, wait, click, lose_device or quit";

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct MoveDesc {
    #[serde(default)]
    forward: f32,
    #[serde(default)]
    right: f32,
    #[serde(default)]
    up: f32,
    #[serde(default)]
    fast: bool,
    seconds: f32,
}

/// The keys a script may press.
pub const SCRIPT_KEYS: &[&str] = &[
    "Space", "T", "I", "F", "P", "B", "R", "F1", "F12", "1", "2", "3", "4", "5", "6", "7", "8", "9",
];

/// Reads and checks a script; relative screenshot paths are relative to the script's folder.
pub fn read_script(path: &Path) -> Result<Vec<Step>, ViewError> {
    let text = std::fs::read_to_string(path).map_err(|e| ViewError::Script {
        path: path.to_owned(),
        problem: format!("cannot read it: {e}"),
    })?;
    parse_script(&text, path)
}

/// Parses a script's text; `path` names it in errors and anchors relative screenshot paths.
pub fn parse_script(text: &str, path: &Path) -> Result<Vec<Step>, ViewError> {
    let error = |problem: String| ViewError::Script {
        path: path.to_owned(),
        problem,
    };
    let file: File = toml::from_str(text).map_err(|e| {
        error(format!(
            "{}; write [[step]] tables, each with one of {STEP_KINDS}",
            e.message()
        ))
    })?;
    let folder = path.parent().unwrap_or(Path::new("."));
    let mut steps = Vec::new();
    for (i, s) in file.step.into_iter().enumerate() {
        let n = i + 1;
        let given = [
            s.technique.is_some(),
            s.camera.is_some(),
            s.movement.is_some(),
            s.key.is_some(),
            s.show.is_some(),
            s.frames.is_some(),
            s.screenshot.is_some(),
            s.capture.is_some(),
            s.quit.is_some(),
            s.light.is_some(),
            s.truth.is_some(),
            s.wait.is_some(),
            s.click.is_some(),
            s.lose_device.is_some(),
        ]
        .iter()
        .filter(|g| **g)
        .count();
        if given != 1 {
            return Err(error(format!(
                "step {n} does {given} things: give each [[step]] exactly one of {STEP_KINDS}"
            )));
        }
        let step = if let Some(t) = s.technique {
            Step::Technique(t)
        } else if let Some(c) = s.camera {
            Step::Camera(
                irradiant_scene::camera_from_desc(&c, path)
                    .map_err(|e| error(format!("step {n}: {e}")))?,
            )
        } else if let Some(m) = s.movement {
            if !(m.seconds.is_finite() && (0.0..=600.0).contains(&m.seconds)) {
                return Err(error(format!(
                    "step {n}: move.seconds = {} is out of range: use 0 to 600",
                    m.seconds
                )));
            }
            let axis = |v: f32| {
                if v.is_finite() {
                    v.clamp(-1.0, 1.0)
                } else {
                    0.0
                }
            };
            Step::Move(
                crate::camera::Movement {
                    forward: axis(m.forward),
                    right: axis(m.right),
                    up: axis(m.up),
                    fast: m.fast,
                },
                m.seconds,
            )
        } else if let Some(k) = s.key {
            if !SCRIPT_KEYS.contains(&k.as_str()) {
                return Err(error(format!(
                    "step {n}: key \"{k}\" is not one a script can press: use one of {}",
                    SCRIPT_KEYS.join(", ")
                )));
            }
            Step::Key(k)
        } else if let Some(v) = s.show {
            if !crate::viewer::DEBUG_VIEWS.iter().any(|d| d.0 == v) {
                let names: Vec<&str> = crate::viewer::DEBUG_VIEWS.iter().map(|d| d.0).collect();
                return Err(error(format!(
                    "step {n}: show = \"{v}\" is not a view: use one of {}",
                    names.join(", ")
                )));
            }
            Step::Show(v)
        } else if let Some(f) = s.frames {
            if !(1..=MAX_SCRIPT_FRAMES).contains(&f) {
                return Err(error(format!(
                    "step {n}: frames = {f} is out of range: use 1 to {MAX_SCRIPT_FRAMES}"
                )));
            }
            Step::Frames(f)
        } else if let Some(p) = s.screenshot {
            let ext = p
                .extension()
                .map(|e| e.to_string_lossy().to_lowercase())
                .unwrap_or_default();
            if ext != "png" && ext != "exr" {
                return Err(error(format!(
                    "step {n}: screenshot {} must end in .png (as shown) or .exr (linear)",
                    p.display()
                )));
            }
            Step::Screenshot(folder.join(p))
        } else if let Some(p) = s.capture {
            if p.extension().is_none_or(|e| !e.eq_ignore_ascii_case("png")) {
                return Err(error(format!(
                    "step {n}: capture {} must end in .png",
                    p.display()
                )));
            }
            Step::Capture(folder.join(p))
        } else if let Some(l) = s.light {
            Step::Light(l.index, l.on)
        } else if let Some(t) = s.truth {
            let show = crate::truth::TruthShow::ALL
                .iter()
                .find(|(_, name)| name.eq_ignore_ascii_case(&t))
                .ok_or_else(|| {
                    error(format!(
                        "step {n}: truth = \"{t}\" is not a way to show it: use wipe, difference or flip"
                    ))
                })?;
            Step::Truth(show.0)
        } else if let Some(w) = s.wait {
            if w != "truth" {
                return Err(error(format!(
                    "step {n}: wait = \"{w}\": a script can wait for \"truth\" only"
                )));
            }
            Step::WaitTruth
        } else if let Some([x, y]) = s.click {
            if !(x.is_finite() && y.is_finite() && x >= 0.0 && y >= 0.0) {
                return Err(error(format!(
                    "step {n}: click = [{x}, {y}] is not a pixel: give two coordinates of 0 or more"
                )));
            }
            Step::Click(x, y)
        } else if s.lose_device.is_some() {
            Step::LoseDevice
        } else {
            Step::Quit
        };
        steps.push(step);
    }
    Ok(steps)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_script_reads_step_by_step() {
        let text = r#"
[[step]]
technique = "ddgi{preset = \"quality\"}"
[[step]]
camera = { position = [0, 1, 3], target = [0, 1, 0] }
[[step]]
move = { forward = 1, seconds = 0.5 }
[[step]]
key = "Space"
[[step]]
frames = 30
[[step]]
screenshot = "shots/a.png"
[[step]]
quit = true
"#;
        let steps = parse_script(text, Path::new("/tmp/s/script.toml")).unwrap();
        assert_eq!(steps.len(), 7);
        assert_eq!(
            steps[0],
            Step::Technique("ddgi{preset = \"quality\"}".into())
        );
        assert!(matches!(&steps[1], Step::Camera(c) if c.position.z == 3.0));
        assert!(matches!(steps[2], Step::Move(m, s) if m.forward == 1.0 && s == 0.5));
        assert_eq!(steps[4], Step::Frames(30));
        assert_eq!(steps[5], Step::Screenshot("/tmp/s/shots/a.png".into()));
        assert_eq!(steps[6], Step::Quit);
    }

    #[test]
    fn a_bad_script_names_the_step_and_the_fix() {
        for (text, expected) in [
            ("[[step]]\nframes = 0\n", "step 1: frames = 0"),
            ("[[step]]\nkey = \"Z\"\n", "not one a script can press"),
            ("[[step]]\nframes = 2\nquit = true\n", "does 2 things"),
            ("[[step]]\nscreenshot = \"a.jpg\"\n", "must end in .png"),
            ("[[step]]\nmove = { seconds = -1 }\n", "move.seconds"),
            ("[[step]]\nteleport = 1\n", "write [[step]] tables"),
            (
                "[[step]]\ntruth = \"sideways\"\n",
                "use wipe, difference or flip",
            ),
            ("[[step]]\nwait = \"godot\"\n", "\"truth\" only"),
            ("[[step]]\nclick = [-1, 2]\n", "not a pixel"),
            (
                "[[step]]\ncamera = { position = [0, 0, 0], target = [0, 0, 0] }\n",
                "step 1",
            ),
        ] {
            let e = parse_script(text, Path::new("s.toml"))
                .unwrap_err()
                .to_string();
            assert!(e.contains(expected) && e.contains("s.toml"), "{text}: {e}");
        }
    }
}
