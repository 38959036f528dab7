//! Settings as files: presets, the overlay of a user's table on a preset (unknown keys are
//! warnings, not silence), lossless round trips, and errors that name the field, the value and
//! what is allowed.
//!
//! A settings file (and a scene manifest) may carry these tables:
//!
//! ```toml
//! [frame]                 # FrameSettings, over the preset
//! area_light_samples = 4
//! [frame.taa]
//! blend = 0.1
//!
//! [technique]             # TechniqueSpec: a registered technique, a preset, its own keys
//! name = "ddgi"
//! preset = "balanced"
//! [technique.update]
//! hysteresis = 0.97
//! ```

use std::fmt::Display;
use std::path::Path;

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::frame::FrameSettings;

/// The three named points of every settings type's trade-offs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// Cheapest settings that still look right: previews, large scenes, slow adapters.
    Fast,
    /// The default: between fast and quality in cost, noise and lag.
    #[default]
    Balanced,
    /// Less noise and lag for more time: stills, comparisons, fast adapters.
    Quality,
}

impl Preset {
    /// Every preset, cheapest first.
    pub const ALL: [Preset; 3] = [Preset::Fast, Preset::Balanced, Preset::Quality];

    /// Its name in settings files and on the command line (`fast`, `balanced`, `quality`).
    pub fn name(self) -> &'static str {
        match self {
            Preset::Fast => "fast",
            Preset::Balanced => "balanced",
            Preset::Quality => "quality",
        }
    }

    /// The preset of this name; an error listing the names when it is none of them.
    pub fn parse(text: &str) -> Result<Self, SettingsError> {
        Self::ALL
            .into_iter()
            .find(|p| p.name() == text)
            .ok_or_else(|| SettingsError::Invalid {
                field: "preset".into(),
                value: text.into(),
                allowed: "fast, balanced or quality".into(),
            })
    }
}

/// A settings type's three named points. `preset` picks one by name.
pub trait Presets: Sized {
    /// The settings of [`Preset::Fast`].
    fn fast() -> Self;
    /// The settings of [`Preset::Balanced`].
    fn balanced() -> Self;
    /// The settings of [`Preset::Quality`].
    fn quality() -> Self;

    /// The settings of `preset`.
    fn preset(preset: Preset) -> Self {
        match preset {
            Preset::Fast => Self::fast(),
            Preset::Balanced => Self::balanced(),
            Preset::Quality => Self::quality(),
        }
    }
}

/// Implements [`Presets`] with a settings type's own `fast`, `balanced` and `quality`.
macro_rules! presets_from_inherent {
    ($settings:ty) => {
        impl $crate::settings::Presets for $settings {
            fn fast() -> Self {
                <$settings>::fast()
            }
            fn balanced() -> Self {
                <$settings>::balanced()
            }
            fn quality() -> Self {
                <$settings>::quality()
            }
        }
    };
}
pub(crate) use presets_from_inherent;

/// A settings type whose every setting's doc comment (what it does and what it trades) is
/// found by its path (`["update", "hysteresis"]`): the viewer's tooltips, from the comments
/// the code already carries.
pub trait SettingDocs {
    /// The doc comment of the setting, or group, at `path`.
    fn setting_doc(path: &[&str]) -> Option<&'static str>;
}

/// Implements [`SettingDocs`] from the type's field docs (`documented::DocumentedFields`),
/// with each named group's settings found through its own type.
macro_rules! setting_docs {
    ($settings:ty $({ $($group:literal => $group_type:ty),* $(,)? })?) => {
        impl $crate::settings::SettingDocs for $settings {
            fn setting_doc(path: &[&str]) -> Option<&'static str> {
                match path {
                    [name] => {
                        <$settings as documented::DocumentedFields>::get_field_docs(name).ok()
                    }
                    $($([$group, rest @ ..] => {
                        <$group_type as $crate::settings::SettingDocs>::setting_doc(rest)
                    })*)?
                    _ => None,
                }
            }
        }
    };
}
pub(crate) use setting_docs;

/// A technique as settings describe it: a registered name, a preset, and the technique's own
/// keys over the preset (tables such as `[technique.update]`; each technique documents its
/// keys on its settings type). Round-trips through TOML without loss.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TechniqueSpec {
    /// The registered technique's name (`ddgi`; see [`crate::registry`]).
    pub name: String,
    /// The preset its own settings start from (balanced when a file leaves it out).
    #[serde(default)]
    pub preset: Preset,
    /// The technique's own settings over the preset; unknown keys are warned about when the
    /// technique reads them.
    #[serde(flatten)]
    pub settings: toml::Table,
}

impl TechniqueSpec {
    /// A technique at a preset, with no settings of its own.
    pub fn new(name: &str, preset: Preset) -> Self {
        Self {
            name: name.into(),
            preset,
            settings: toml::Table::new(),
        }
    }

    /// A technique with every setting spelled out (what a typed settings struct serialises to).
    pub fn with_settings<T: Serialize>(name: &str, settings: &T) -> Self {
        Self {
            name: name.into(),
            preset: Preset::Balanced,
            settings: as_table(settings),
        }
    }

    /// What this spec, a manifest's or a settings file's `[technique]`, sets for technique
    /// `name`: its own settings where it names `name`; the same under its name where `name` is
    /// a hybrid with it as a part (a `ddgi` table is `ssil+ddgi`'s `[ddgi]`); its part's table
    /// where it names a hybrid of which `name` is a part. None where it says nothing of `name`.
    /// So a scene's probe layout (the large world's cascades) holds for DDGI alone and for
    /// `ssil+ddgi`'s DDGI part, not only for the one its manifest names.
    pub fn settings_for(&self, name: &str) -> Option<toml::Table> {
        if self.name == name {
            Some(self.settings.clone())
        } else if is_part_of(&self.name, name) {
            let own = toml::Value::Table(self.settings.clone());
            Some(toml::Table::from_iter([(self.name.clone(), own)]))
        } else if is_part_of(name, &self.name) {
            self.settings.get(name)?.as_table().cloned()
        } else {
            None
        }
    }

    /// `spec` with what this spec sets for its technique underneath (`settings_for`), the
    /// keys of `spec` winning; `spec` as it is where this one says nothing of it.
    pub fn under(&self, spec: &TechniqueSpec) -> TechniqueSpec {
        let Some(mut settings) = self.settings_for(&spec.name) else {
            return spec.clone();
        };
        merge_tables(&mut settings, &spec.settings);
        TechniqueSpec {
            settings,
            ..spec.clone()
        }
    }

    /// This spec as `scene` runs it: what the manifest's `[technique]` table sets for its
    /// technique (`settings_for`) under its own settings; as it is where the manifest has no
    /// such table. A table that does not read as a technique's is an error naming the scene.
    pub fn on_scene(&self, scene: &irradiant_scene::Scene) -> Result<TechniqueSpec, SettingsError> {
        let Some(table) = scene.settings.get("technique") else {
            return Ok(self.clone());
        };
        let manifest: TechniqueSpec =
            table
                .clone()
                .try_into()
                .map_err(|e: toml::de::Error| SettingsError::Malformed {
                    source_name: format!("scene {}", scene.name),
                    message: format!("its [technique] table: {e}"),
                })?;
        Ok(manifest.under(self))
    }
}

/// Whether technique `part` is one of hybrid `hybrid`'s parts (`ddgi` of `ssil+ddgi`).
pub fn is_part_of(part: &str, hybrid: &str) -> bool {
    hybrid.contains('+') && hybrid.split('+').any(|p| p == part)
}

/// `over` laid into `base`, table by table, the keys of `over` winning.
pub fn merge_tables(base: &mut toml::Table, over: &toml::Table) {
    for (key, value) in over {
        match (base.get_mut(key), value) {
            (Some(toml::Value::Table(b)), toml::Value::Table(o)) => merge_tables(b, o),
            _ => {
                base.insert(key.clone(), value.clone());
            }
        }
    }
}

impl Default for TechniqueSpec {
    fn default() -> Self {
        Self::new("ddgi", Preset::Balanced)
    }
}

/// A technique as the command line and the viewer write it: `name` or `name{key = value, …}`,
/// the braces a TOML inline table over the preset, `preset = "…"` among them the technique's
/// own preset. Whether the name is registered is the caller's to check.
#[derive(Clone, Debug, PartialEq)]
pub struct SpecText {
    /// The name before the braces.
    pub name: String,
    /// `preset = "…"` in the braces, if given.
    pub preset: Option<Preset>,
    /// The other keys in the braces.
    pub settings: toml::Table,
}

impl SpecText {
    /// Parses `text`; every error names the text and how to write it.
    pub fn parse(text: &str) -> Result<Self, SettingsError> {
        let text = text.trim();
        let malformed = |message: String| SettingsError::Malformed {
            source_name: format!("technique '{text}'"),
            message,
        };
        if text.is_empty() {
            return Err(malformed(
                "a technique is empty: name one, e.g. ddgi or ddgi{preset = \"quality\"}".into(),
            ));
        }
        let (name, mut settings) = match text.split_once('{') {
            Some((name, rest)) => {
                let inner = rest.strip_suffix('}').ok_or_else(|| {
                    malformed(
                        "settings in braces must end with '}', e.g. ssil{visibility = false}"
                            .into(),
                    )
                })?;
                let table: toml::Table = toml::from_str(&format!("v = {{{inner}}}")).map_err(|e| {
                    malformed(format!("the settings in braces are not a TOML inline table ({}); write them as key = value, comma-separated", e.message()))
                })?;
                let Some(toml::Value::Table(t)) = table.get("v") else {
                    unreachable!("a table parsed from `v = {{…}}` holds the table v")
                };
                (name.trim(), t.clone())
            }
            None => (text, toml::Table::new()),
        };
        let preset = match settings.remove("preset") {
            None => None,
            Some(toml::Value::String(p)) => {
                Some(Preset::parse(&p).map_err(|e| malformed(e.to_string()))?)
            }
            Some(other) => {
                return Err(malformed(format!(
                    "preset = {other} is not a preset name; write preset = \"fast\", \"balanced\" or \"quality\" (in quotes)"
                )));
            }
        };
        Ok(Self {
            name: name.to_owned(),
            preset,
            settings,
        })
    }
}

/// Sets `table[key[0]][key[1]]… = value`, making (or replacing with) tables on the way: a
/// setting's dotted path, as `bench --vary` and the viewer's panel change one setting of a
/// spec.
pub fn set_path(table: &mut toml::Table, key: &[String], value: toml::Value) {
    match key {
        [] => {}
        [last] => {
            table.insert(last.clone(), value);
        }
        [first, rest @ ..] => {
            let entry = table
                .entry(first.clone())
                .or_insert_with(|| toml::Value::Table(toml::Table::new()));
            if !entry.is_table() {
                *entry = toml::Value::Table(toml::Table::new());
            }
            if let toml::Value::Table(t) = entry {
                set_path(t, rest, value);
            }
        }
    }
}

/// A settings struct as the TOML table a settings file writes for it.
pub fn as_table<T: Serialize>(settings: &T) -> toml::Table {
    toml::Table::try_from(settings).expect("settings serialise to a TOML table")
}

/// A setting that cannot be used. Every message names the field, the value and the fix.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SettingsError {
    /// A setting has a value outside what is allowed (a range, a list of names).
    #[error("setting {field} = {value} is not allowed: use {allowed}")]
    Invalid {
        /// The setting's dotted path (`frame.taa.blend`).
        field: String,
        /// The value given, as text.
        value: String,
        /// What is allowed instead ("a value from 0.001 to 1").
        allowed: String,
    },
    /// A settings text cannot be read, is not valid TOML, has a value of the wrong type or
    /// nests too deep.
    #[error("{source_name}: {message}")]
    Malformed {
        /// Where the text came from: a file's path, or the table's prefix (`frame`).
        source_name: String,
        /// What is wrong with it.
        message: String,
    },
}

impl SettingsError {
    /// An [`SettingsError::Invalid`] naming the field, the value and what is allowed.
    pub fn invalid(
        field: impl Into<String>,
        value: impl Display,
        allowed: impl Into<String>,
    ) -> Self {
        Self::Invalid {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

/// Refuses `value` outside `lo..=hi` (and NaN), naming `field`.
pub fn check_range<T: PartialOrd + Display + Copy>(
    field: &str,
    value: T,
    lo: T,
    hi: T,
) -> Result<(), SettingsError> {
    if value >= lo && value <= hi {
        Ok(())
    } else {
        Err(SettingsError::invalid(
            field,
            value,
            format!("a value from {lo} to {hi}"),
        ))
    }
}

/// `base` with the keys of `table` laid over it, field by field (nested tables merge). A key
/// the settings type does not have is a warning naming it and the known keys at that level;
/// a value of the wrong type is an error naming the field.
pub fn overlay<T: Serialize + DeserializeOwned>(
    base: &T,
    table: &toml::Table,
    prefix: &str,
    warnings: &mut Vec<String>,
) -> Result<T, SettingsError> {
    let mut merged = toml::Table::try_from(base).map_err(|e| SettingsError::Malformed {
        source_name: prefix.into(),
        message: e.to_string(),
    })?;
    merge(&mut merged, table, prefix, warnings);
    T::deserialize(toml::Value::Table(merged)).map_err(|e| SettingsError::Malformed {
        source_name: prefix.into(),
        message: format!("{e} (check the types of the [{prefix}] settings)"),
    })
}

fn merge(into: &mut toml::Table, from: &toml::Table, prefix: &str, warnings: &mut Vec<String>) {
    for (key, value) in from {
        let path = format!("{prefix}.{key}");
        match (into.get_mut(key), value) {
            (None, _) => {
                let known: Vec<&str> = into.keys().map(String::as_str).collect();
                warnings.push(format!(
                    "unknown setting {path} is ignored (known at this level: {})",
                    known.join(", ")
                ));
            }
            (Some(toml::Value::Table(inner)), toml::Value::Table(value)) => {
                merge(inner, value, &path, warnings)
            }
            (Some(slot), value) => *slot = value.clone(),
        }
    }
}

/// Deepest tables a settings file may nest under [frame] or [technique]: no setting is more
/// than 2 below them; far deeper input (a fuzzer's) would not even read back once written.
const MAX_TABLE_DEPTH: usize = 8;

/// How many tables deep `table` nests, itself counted.
fn table_depth(table: &toml::Table) -> usize {
    fn value_depth(value: &toml::Value) -> usize {
        match value {
            toml::Value::Table(t) => table_depth(t),
            toml::Value::Array(items) => items.iter().map(value_depth).max().unwrap_or(0),
            _ => 0,
        }
    }
    1 + table.values().map(value_depth).max().unwrap_or(0)
}

/// What a settings file (or a manifest) sets: the frame and the technique, each optional.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SettingsFile {
    /// The `[frame]` table, laid over a preset's [`FrameSettings`] by
    /// [`SettingsFile::frame_settings`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame: Option<toml::Table>,
    /// The `[technique]` table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub technique: Option<TechniqueSpec>,
}

impl SettingsFile {
    /// Reads a settings file; unknown top-level tables are warnings.
    pub fn read(path: &Path, warnings: &mut Vec<String>) -> Result<Self, SettingsError> {
        let text = std::fs::read_to_string(path).map_err(|e| SettingsError::Malformed {
            source_name: path.display().to_string(),
            message: format!("cannot read it: {e}"),
        })?;
        Self::parse(&text, &path.display().to_string(), warnings)
    }

    /// Parses settings text; `source_name` names it in errors and warnings. Unknown tables
    /// and keys are warnings; tables nested too deep are refused.
    pub fn parse(
        text: &str,
        source_name: &str,
        warnings: &mut Vec<String>,
    ) -> Result<Self, SettingsError> {
        let deserializer =
            toml::Deserializer::parse(text).map_err(|e| SettingsError::Malformed {
                source_name: source_name.into(),
                message: e.to_string(),
            })?;
        let file: Self = serde_ignored::deserialize(deserializer, |path| {
            warnings.push(format!("{source_name}: unknown setting {path} is ignored"))
        })
        .map_err(|e: toml::de::Error| SettingsError::Malformed {
            source_name: source_name.into(),
            message: e.to_string(),
        })?;
        let tables = [
            file.frame.as_ref(),
            file.technique.as_ref().map(|t| &t.settings),
        ];
        let depth = tables
            .into_iter()
            .flatten()
            .map(table_depth)
            .max()
            .unwrap_or(0);
        if depth > MAX_TABLE_DEPTH {
            return Err(SettingsError::Malformed {
                source_name: source_name.into(),
                message: format!(
                    "its tables nest {depth} deep, where no setting is more than 2 below [frame] or [technique]; check the table headers (a dotted header such as [frame.taa] opens one table a dot)"
                ),
            });
        }
        Ok(file)
    }

    /// The frame settings: the preset's, with this file's `[frame]` table over them,
    /// validated.
    pub fn frame_settings(
        &self,
        preset: Preset,
        warnings: &mut Vec<String>,
    ) -> Result<FrameSettings, SettingsError> {
        let base = FrameSettings::preset(preset);
        let settings = match &self.frame {
            Some(table) => overlay(&base, table, "frame", warnings)?,
            None => base,
        };
        settings.validate()?;
        Ok(settings)
    }

    /// Writes it back as TOML text, which parses to an equal `SettingsFile`.
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("settings serialise")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The settings fuzzer's find: a [frame] table under a hundred dotted headers parsed, but
    /// its round trip did not (the TOML reader's recursion limit). Now refused up front.
    #[test]
    fn absurdly_nested_settings_are_refused_naming_the_file() {
        let text = include_str!("../tests/fuzz-regressions/settings-nested-tables.toml");
        let e = SettingsFile::parse(text, "nested.toml", &mut Vec::new()).unwrap_err();
        assert!(
            e.to_string().contains("nested.toml") && e.to_string().contains("nest"),
            "{e}"
        );
        let ordinary = "[frame.taa]\nblend = 0.2\n[technique]\nname = \"ddgi\"\n[technique.volume]\nrays_per_probe = 64\n";
        let file = SettingsFile::parse(ordinary, "ok.toml", &mut Vec::new()).unwrap();
        let again = SettingsFile::parse(&file.to_toml(), "again", &mut Vec::new()).unwrap();
        assert_eq!(file, again);
    }

    #[test]
    fn overlay_sets_known_fields_and_warns_about_unknown_ones() {
        let table: toml::Table =
            toml::from_str("area_light_samples = 2\nbogus = 1\n[taa]\nblend = 0.5\ncolour = 3\n")
                .unwrap();
        let mut warnings = Vec::new();
        let s = overlay(&FrameSettings::balanced(), &table, "frame", &mut warnings).unwrap();
        assert_eq!(s.area_light_samples, 2);
        assert_eq!(s.taa.blend, 0.5);
        assert_eq!(s.taa.clip_sigma, FrameSettings::balanced().taa.clip_sigma);
        assert_eq!(warnings.len(), 2, "{warnings:?}");
        assert!(warnings[0].contains("frame.bogus") && warnings[0].contains("area_light_samples"));
        assert!(warnings[1].contains("frame.taa.colour"));
    }

    #[test]
    fn wrong_types_and_ranges_name_the_field() {
        let table: toml::Table = toml::from_str("area_light_samples = \"many\"").unwrap();
        let e = overlay(&FrameSettings::balanced(), &table, "frame", &mut Vec::new()).unwrap_err();
        assert!(e.to_string().contains("frame"), "{e}");
        let mut s = FrameSettings::balanced();
        s.taa.blend = 0.0;
        let e = s.validate().unwrap_err().to_string();
        assert!(
            e.contains("frame.taa.blend = 0") && e.contains("0.001 to 1"),
            "{e}"
        );
        // A cut's neighbours share the reuse pass's fixed array with the steady ones.
        let mut s = FrameSettings::balanced();
        s.resampling.cut_neighbours = 17;
        let e = s.validate().unwrap_err().to_string();
        assert!(
            e.contains("frame.resampling.cut_neighbours = 17") && e.contains("0 to 16"),
            "{e}"
        );
    }

    #[test]
    fn settings_files_round_trip_without_loss() {
        let text = "[frame]\narea_light_samples = 2\n\n[frame.taa]\nenabled = false\n\n[technique]\nname = \"ddgi\"\npreset = \"fast\"\n\n[technique.update]\nhysteresis = 0.9\n";
        let mut warnings = Vec::new();
        let file = SettingsFile::parse(text, "test.toml", &mut warnings).unwrap();
        assert!(warnings.is_empty(), "{warnings:?}");
        let again = SettingsFile::parse(&file.to_toml(), "again", &mut warnings).unwrap();
        assert_eq!(file, again);
        let frame = file
            .frame_settings(Preset::Balanced, &mut warnings)
            .unwrap();
        assert!(!frame.taa.enabled);
        // The full settings of every preset round-trip through TOML too.
        for preset in Preset::ALL {
            let s = FrameSettings::preset(preset);
            let table = toml::Table::try_from(&s).unwrap();
            assert_eq!(
                overlay(&FrameSettings::fast(), &table, "frame", &mut warnings).unwrap(),
                s
            );
        }
        assert!(warnings.is_empty());
        let mut warnings = Vec::new();
        SettingsFile::parse("[frames]\nx = 1\n", "typo.toml", &mut warnings).unwrap();
        assert!(
            warnings[0].contains("typo.toml") && warnings[0].contains("frames"),
            "{warnings:?}"
        );
    }
}
