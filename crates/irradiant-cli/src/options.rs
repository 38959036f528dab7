//! Parsing and checking of the options commands share: sizes, outputs, cameras, and how a
//! command's flags, a `--settings` file and a manifest's tables combine into the frame's and
//! the technique's settings.

use std::path::{Path, PathBuf};

use clap::Args;
use irradiant::frame::FrameSettings;
use irradiant::settings::merge_tables;
use irradiant::{Preset, SettingsFile, TechniqueSpec};
use irradiant_scene::Scene;

use crate::CliError;

/// Largest image side: 16384 is the common GPU texture limit; what fits in memory at a given
/// size is checked against the adapter before anything is allocated.
pub const MAX_SIDE: u32 = 16384;

/// `WxH`, e.g. `1280x720`.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{text}' is not a size: write WIDTHxHEIGHT, e.g. 640x480"))?;
    let side = |s: &str| {
        s.trim().parse::<u32>().map_err(|_| {
            format!("'{text}' is not a size: write WIDTHxHEIGHT with whole numbers, e.g. 640x480")
        })
    };
    let (w, h) = (side(w)?, side(h)?);
    if w == 0 || h == 0 {
        return Err(format!("size {w}x{h} has no pixels: use at least 1x1"));
    }
    if w > MAX_SIDE || h > MAX_SIDE {
        return Err(format!(
            "size {w}x{h} is too large: each side at most {MAX_SIDE}"
        ));
    }
    Ok((w, h))
}

/// "px,py,pz,tx,ty,tz[,fov]": a view instead of the scene's camera.
pub fn parse_camera(text: &str) -> Result<irradiant_scene::Camera, String> {
    let numbers: Vec<f32> = text
        .split(',')
        .map(|n| n.trim().parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("'{text}' is not a camera: write px,py,pz,tx,ty,tz[,fov_degrees]"))?;
    if !(numbers.len() == 6 || numbers.len() == 7) || numbers.iter().any(|n| !n.is_finite()) {
        return Err(format!(
            "'{text}' is not a camera: write six or seven finite numbers, px,py,pz,tx,ty,tz[,fov_degrees]"
        ));
    }
    let camera = irradiant_scene::Camera {
        position: glam::Vec3::new(numbers[0], numbers[1], numbers[2]),
        target: glam::Vec3::new(numbers[3], numbers[4], numbers[5]),
        up: glam::Vec3::Y,
        fov_y_degrees: numbers.get(6).copied().unwrap_or(45.0),
    };
    if camera.position == camera.target
        || !(camera.fov_y_degrees > 0.5 && camera.fov_y_degrees < 179.0)
    {
        return Err(format!(
            "'{text}': the position must differ from the target and the field of view lie in 0.5…179°"
        ));
    }
    Ok(camera)
}

/// The view a command renders, instead of the scene's camera: given as numbers or read from a
/// camera file.
#[derive(Args, Clone, Debug)]
pub struct CameraArgs {
    /// The view, instead of the scene's camera: "px,py,pz,tx,ty,tz" (position, target) or
    /// with a seventh number, the vertical field of view in degrees.
    #[arg(long, value_parser = parse_camera, conflicts_with = "camera_from")]
    pub camera: Option<irradiant_scene::Camera>,
    /// The view from a camera file's [camera] table (`render --save-camera` writes one; a scene
    /// manifest is one too).
    #[arg(long)]
    pub camera_from: Option<PathBuf>,
}

impl CameraArgs {
    /// Puts the chosen view, if any, in place of the scene's camera.
    pub fn apply(&self, scene: &mut Scene) -> Result<(), CliError> {
        if let Some(camera) = &self.camera {
            scene.camera = camera.clone();
        }
        if let Some(path) = &self.camera_from {
            scene.camera = irradiant_scene::read_camera_file(path)?;
        }
        Ok(())
    }
}

/// A technique as a command line names it: a registered name, optionally with settings over
/// its preset in braces, as a TOML inline table (`ssil{visibility = false}`), so that one
/// comparison can hold several variants of one technique.
#[derive(Clone, Debug, PartialEq)]
pub struct TechniqueChoice {
    /// The text as given (spaces dropped): what reports call it.
    pub label: String,
    /// The registered name (or `path`).
    pub name: String,
    /// `preset = "…"` in the braces: this technique's preset, over the command's `--preset`.
    pub preset: Option<Preset>,
    /// The other keys in the braces, over the preset and any settings file.
    pub overrides: toml::Table,
}

impl TechniqueChoice {
    /// Parses the text; whether the name is registered is the caller's to check (`path`, the
    /// reference, is a technique on the command line but not in the registry).
    pub fn parse(text: &str) -> Result<Self, CliError> {
        let parsed = irradiant::settings::SpecText::parse(text)
            .map_err(|e| CliError::Usage(e.to_string()))?;
        Ok(Self {
            label: text.split_whitespace().collect(),
            name: parsed.name,
            preset: parsed.preset,
            overrides: parsed.settings,
        })
    }

    /// The label as a file name: letters, digits, '-' and '+' kept, anything else '_'.
    pub fn file_stem(&self) -> String {
        self.label
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' || c == '+' {
                    c
                } else {
                    '_'
                }
            })
            .collect()
    }
}

/// The techniques a command lists, comma-separated outside braces (`all`: every registered
/// one), each checked.
pub fn technique_list(lists: &[String]) -> Result<Vec<TechniqueChoice>, CliError> {
    let mut texts = Vec::new();
    for list in lists {
        let (mut depth, mut start) = (0i32, 0);
        for (i, c) in list.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    texts.push(&list[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        texts.push(&list[start..]);
    }
    if texts.iter().any(|t| t.trim() == "all") {
        texts = irradiant::registry::names();
    }
    let choices: Vec<TechniqueChoice> = texts
        .into_iter()
        .filter(|t| !t.trim().is_empty())
        .map(TechniqueChoice::parse)
        .collect::<Result<_, _>>()?;
    for c in &choices {
        irradiant::registry::find(&c.name).map_err(|e| CliError::Usage(e.to_string()))?;
    }
    Ok(choices)
}

/// Checks that an output file can be written before spending GPU time on it.
pub fn check_output(path: &Path, extensions: &[&str]) -> Result<(), CliError> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    if !extensions.contains(&extension.as_str()) {
        return Err(CliError::Usage(format!(
            "{}: unsupported output type; end the name in .{}",
            path.display(),
            extensions.join(" or .")
        )));
    }
    check_folder(path)
}

/// The most path-traced samples a pixel, a probe texel or a G-buffer point may take: a million
/// puts the noise near 0.1 %, and more would run for hours on a software adapter.
pub const MAX_SAMPLES: u32 = 1 << 20;

/// A sample count for a flag: 1 to [`MAX_SAMPLES`].
pub fn parse_samples(text: &str) -> Result<u32, String> {
    match text.parse::<u32>() {
        Ok(n) if (1..=MAX_SAMPLES).contains(&n) => Ok(n),
        _ => Err(format!("use a whole number from 1 to {MAX_SAMPLES}")),
    }
}

/// [`parse_samples`], where 0 leaves the measurement out.
pub fn parse_samples_or_none(text: &str) -> Result<u32, String> {
    match text {
        "0" => Ok(0),
        _ => parse_samples(text).map_err(|e| format!("{e}, or 0 to leave it out")),
    }
}

/// Checks, before any work, that a report can go to `path`: its folder exists, and `path` is a
/// folder (replaced by the new report) or nothing yet, not a file.
pub fn check_report_folder(path: &Path) -> Result<(), CliError> {
    check_folder(path)?;
    if path.exists() && !path.is_dir() {
        return Err(CliError::Io {
            path: path.to_owned(),
            message:
                "is a file, and a report is a folder; name a new folder or an earlier report's"
                    .into(),
        });
    }
    Ok(())
}

/// Checks that the folder a file or folder goes into exists.
pub fn check_folder(path: &Path) -> Result<(), CliError> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(CliError::Io {
            path: dir.to_owned(),
            message: "the output folder does not exist; create it first".into(),
        });
    }
    Ok(())
}

/// [`RunSettings::check_and_warn`] for commands that take no settings file (`bench`): checks
/// each spec and prints `earlier` warnings and the techniques' own once, with what each finds
/// in `scene` where one is given.
pub fn check_techniques<'a>(
    earlier: &[String],
    specs: impl IntoIterator<Item = &'a TechniqueSpec>,
    scene: Option<&Scene>,
) -> Result<(), CliError> {
    let mut warnings = earlier.to_vec();
    for spec in specs {
        let kind = spec.kind()?;
        warnings.extend(kind.check(spec)?);
        if let Some(scene) = scene {
            warnings.extend(kind.scene_warnings(spec, scene));
        }
    }
    let mut seen = std::collections::HashSet::new();
    for w in warnings.iter().filter(|w| seen.insert(*w)) {
        eprintln!("warning: {w}");
    }
    Ok(())
}

/// The settings every command that renders frames takes.
#[derive(Args, Clone, Debug)]
pub struct SettingsArgs {
    /// Settings preset of the frame and every technique: fast, balanced or quality. A
    /// technique's own `preset` in braces (`ddgi{preset = "quality"}`) overrides it for that
    /// technique.
    #[arg(long, default_value = "balanced", value_parser = parse_preset)]
    pub preset: Preset,
    /// A settings file with [frame] and [technique] tables (see docs/architecture.md); it
    /// overrides the scene manifest's tables, and the flags override both.
    #[arg(long)]
    pub settings: Option<PathBuf>,
    /// Trace one ray through each pixel centre and blend no history (TAA is on by default).
    #[arg(long)]
    pub no_taa: bool,
}

fn parse_preset(text: &str) -> Result<Preset, String> {
    Preset::parse(text).map_err(|e| e.to_string())
}

/// The frame's and a technique's settings for a run: the manifest's tables, then the settings
/// file's, then the flags, each over the one before; warnings for unknown keys.
pub struct RunSettings {
    pub frame: FrameSettings,
    pub warnings: Vec<String>,
    file: SettingsFile,
}

impl RunSettings {
    pub fn new(args: &SettingsArgs, scene: &Scene, seed: u32) -> Result<Self, CliError> {
        let mut warnings = Vec::new();
        // The manifest's tables, then the file's over them.
        let mut file = SettingsFile::default();
        if !scene.settings.is_empty() {
            let text =
                toml::to_string(&scene.settings).map_err(|e| CliError::Usage(e.to_string()))?;
            file = SettingsFile::parse(&text, &format!("scene {}", scene.name), &mut warnings)?;
        }
        if let Some(path) = &args.settings {
            let from_file = SettingsFile::read(path, &mut warnings)?;
            if let Some(frame) = from_file.frame {
                let mut merged = file.frame.take().unwrap_or_default();
                merged.extend(frame);
                file.frame = Some(merged);
            }
            if from_file.technique.is_some() {
                file.technique = from_file.technique;
            }
        }
        let mut frame = file.frame_settings(args.preset, &mut warnings)?;
        if args.no_taa {
            frame.taa.enabled = false;
        }
        frame.seed = seed;
        Ok(Self {
            frame,
            warnings,
            file,
        })
    }

    /// Checks each technique's settings before any GPU work, so that a bad value is an error
    /// before anything runs, and prints every warning once: the settings files' (unknown keys),
    /// then each technique's and what it finds in the scene. Techniques that share a part
    /// (`ssil` and `ssil+ddgi`) share its warnings.
    pub fn check_and_warn<'a>(
        &self,
        specs: impl IntoIterator<Item = &'a TechniqueSpec>,
        scene: &Scene,
    ) -> Result<(), CliError> {
        check_techniques(&self.warnings, specs, Some(scene))
    }

    /// The specs of `choices` (seed 0), checked and their warnings printed
    /// ([`Self::check_and_warn`]): what the commands that run several techniques start from.
    pub fn checked_specs(
        &self,
        choices: &[TechniqueChoice],
        args: &SettingsArgs,
        scene: &Scene,
    ) -> Result<Vec<TechniqueSpec>, CliError> {
        let specs = choices
            .iter()
            .map(|choice| self.choice(choice, args, 0))
            .collect::<Result<Vec<_>, _>>()?;
        self.check_and_warn(&specs, scene)?;
        Ok(specs)
    }

    /// The technique the settings file or the manifest names, if any.
    pub fn named_technique(&self) -> Option<String> {
        self.file.technique.as_ref().map(|t| t.name.clone())
    }

    /// The spec of a choice: the settings file's or manifest's own table where it names the
    /// same technique (else the preset alone), then the choice's preset and its settings in
    /// braces over everything else.
    pub fn choice(
        &self,
        choice: &TechniqueChoice,
        args: &SettingsArgs,
        seed: u32,
    ) -> Result<TechniqueSpec, CliError> {
        let mut spec = self.named(&choice.name, args, seed)?;
        if let Some(preset) = choice.preset {
            spec.preset = preset;
        }
        merge_tables(&mut spec.settings, &choice.overrides);
        Ok(spec)
    }

    fn named(&self, name: &str, args: &SettingsArgs, seed: u32) -> Result<TechniqueSpec, CliError> {
        // The file's own spec where it names this technique, else this technique at the
        // preset with what the file sets for it as a hybrid's part or as a part's hybrid.
        let mut spec = match &self.file.technique {
            Some(spec) if spec.name == name => spec.clone(),
            Some(file) => file.under(&TechniqueSpec::new(name, args.preset)),
            None => TechniqueSpec::new(name, args.preset),
        };
        if args.preset != Preset::Balanced {
            spec.preset = args.preset;
        }
        // The DDGI family seeds its ray rotations from the command's seed, and so does a
        // hybrid's DDGI part; elsewhere the key would be unknown.
        let update: &[&str] = match name {
            "ddgi" | "classic-probes" => &["update"],
            _ if irradiant::settings::is_part_of("ddgi", name) => &["ddgi", "update"],
            _ => &[],
        };
        if !update.is_empty() {
            let mut table = &mut spec.settings;
            for key in update {
                let entry = table
                    .entry(*key)
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                let toml::Value::Table(inner) = entry else {
                    return Err(CliError::Usage(format!(
                        "technique {name}: the setting {} must be a table",
                        update.join(".")
                    )));
                };
                table = inner;
            }
            table.insert("seed".into(), (seed as i64).into());
        }
        Ok(spec)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn technique_lists_split_outside_braces_and_carry_their_settings() {
        let list =
            technique_list(&["none, ssil{visibility = false, samples = 32},ssil".into()]).unwrap();
        let labels: Vec<&str> = list.iter().map(|c| c.label.as_str()).collect();
        assert_eq!(
            labels,
            ["none", "ssil{visibility=false,samples=32}", "ssil"]
        );
        assert_eq!(list[1].name, "ssil");
        assert_eq!(list[1].overrides["samples"].as_integer(), Some(32));
        assert_eq!(list[1].file_stem(), "ssil_visibility_false_samples_32_");
        let mut base: toml::Table = toml::from_str("[update]\nhysteresis = 0.9\nrays = 8").unwrap();
        merge_tables(&mut base, &toml::from_str("[update]\nrays = 16").unwrap());
        assert_eq!(base["update"]["hysteresis"].as_float(), Some(0.9));
        assert_eq!(base["update"]["rays"].as_integer(), Some(16));
        for (bad, expected) in [
            ("ssil{visibility = false", "must end with"),
            ("ssil{visibility}", "inline table"),
            ("magic{a = 1}", "magic"),
        ] {
            let e = technique_list(&[bad.into()]).unwrap_err().to_string();
            assert!(e.contains(expected), "{bad}: {e}");
        }
        // A preset in the braces is the technique's own; the other keys stay settings.
        let quality =
            TechniqueChoice::parse("ddgi{preset = \"quality\", update.hysteresis = 0.9}").unwrap();
        assert_eq!(quality.preset, Some(Preset::Quality));
        assert!(!quality.overrides.contains_key("preset"));
        assert_eq!(
            quality.overrides["update"]["hysteresis"].as_float(),
            Some(0.9)
        );
        assert_eq!(TechniqueChoice::parse("ddgi").unwrap().preset, None);
        for bad in ["ddgi{preset = \"best\"}", "ddgi{preset = 3}"] {
            let e = TechniqueChoice::parse(bad).unwrap_err().to_string();
            assert!(e.contains("fast") && e.contains("quality"), "{bad}: {e}");
        }
        assert_eq!(
            technique_list(&["all".into()]).unwrap().len(),
            irradiant::registry::names().len()
        );
    }

    #[test]
    fn sizes_parse_and_absurd_ones_are_refused() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("64X64"), Ok((64, 64)));
        assert!(parse_size("0x0").unwrap_err().contains("no pixels"));
        assert!(
            parse_size("100000x100000")
                .unwrap_err()
                .contains("too large")
        );
        assert!(parse_size("big").unwrap_err().contains("WIDTHxHEIGHT"));
        assert!(parse_size("12x-3").is_err());
    }

    /// A manifest's `[technique]` table lies under a spec of the same technique, the spec's own
    /// keys winning, and under a hybrid's part or a hybrid's part under a part's spec; another
    /// technique's spec is left alone.
    #[test]
    fn a_scenes_technique_table_lies_under_a_spec_of_its_technique_or_its_parts() {
        let scene = Scene {
            settings: toml::from_str(
                "[technique]\nname = \"ddgi\"\n[technique.volume]\ncascades = 3\nrays_per_probe = 64",
            )
            .unwrap(),
            ..Default::default()
        };
        let mut spec = TechniqueSpec::new("ddgi", Preset::Balanced);
        spec.settings = toml::from_str("[volume]\nrays_per_probe = 128").unwrap();
        let laid = spec.on_scene(&scene).unwrap();
        assert_eq!(laid.settings["volume"]["cascades"].as_integer(), Some(3));
        assert_eq!(
            laid.settings["volume"]["rays_per_probe"].as_integer(),
            Some(128)
        );
        assert!(!laid.settings.contains_key("name"));
        let other = TechniqueSpec::new("ssil", Preset::Balanced);
        assert_eq!(other.on_scene(&scene).unwrap(), other);
        // A hybrid of it takes the table as its part's: the large world's ssil+ddgi ran one
        // volume over 480 m while its ddgi ran the manifest's cascades.
        let hybrid = TechniqueSpec::new("ssil+ddgi", Preset::Balanced)
            .on_scene(&scene)
            .unwrap();
        assert_eq!(
            hybrid.settings["ddgi"]["volume"]["cascades"].as_integer(),
            Some(3)
        );
        // As render, compare and soak lay it, the file's preset aside.
        let args = SettingsArgs {
            preset: Preset::Quality,
            settings: None,
            no_taa: false,
        };
        let run = RunSettings::new(&args, &scene, 7).unwrap();
        let choice = TechniqueChoice::parse("ssil+ddgi{ddgi.volume.rays_per_probe = 32}").unwrap();
        let spec = run.choice(&choice, &args, 7).unwrap();
        assert_eq!(spec.preset, Preset::Quality);
        let volume = &spec.settings["ddgi"]["volume"];
        assert_eq!(volume["cascades"].as_integer(), Some(3));
        assert_eq!(volume["rays_per_probe"].as_integer(), Some(32));
        assert_eq!(
            spec.settings["ddgi"]["update"]["seed"].as_integer(),
            Some(7)
        );
        // A manifest naming the hybrid gives each part its own table.
        let hybrid_scene = Scene {
            settings: toml::from_str(
                "[technique]\nname = \"ssil+ddgi\"\nnear_field = 1.0\n[technique.ddgi.volume]\ncascades = 2",
            )
            .unwrap(),
            ..Default::default()
        };
        let part = TechniqueSpec::new("ddgi", Preset::Balanced)
            .on_scene(&hybrid_scene)
            .unwrap();
        assert_eq!(part.settings["volume"]["cascades"].as_integer(), Some(2));
        assert!(!part.settings.contains_key("near_field"));
        // A table that does not read as a technique's is an error naming the scene.
        let broken = Scene {
            name: "broken".into(),
            settings: toml::from_str("[technique]\npreset = \"best\"").unwrap(),
            ..Default::default()
        };
        let e = TechniqueSpec::new("ddgi", Preset::Balanced)
            .on_scene(&broken)
            .unwrap_err()
            .to_string();
        assert!(e.contains("broken") && e.contains("[technique]"), "{e}");
        let alone = TechniqueSpec::new("ssil", Preset::Balanced);
        assert_eq!(alone.on_scene(&hybrid_scene).unwrap(), alone);
    }
}
