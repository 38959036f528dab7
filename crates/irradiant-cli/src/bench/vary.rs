//! `bench --vary 'KEY = [v1, v2]'`: every listed technique timed at each value of one of its
//! settings, in the same grammar as the settings in a technique's braces. Several `--vary`
//! multiply, the first outermost, so that a paper's grid (SSIL's Figure 9: start × levels ×
//! samples × visibility) is one command.

use crate::CliError;
use crate::options::TechniqueChoice;

/// One `--vary`: a setting's path (`["volume", "rays_per_probe"]`) and the values to time.
#[derive(Clone, Debug, PartialEq)]
pub struct Vary {
    pub key: Vec<String>,
    pub values: Vec<toml::Value>,
}

/// Most values one `--vary` may list: each multiplies the frames timed.
const MAX_VALUES: usize = 64;

impl Vary {
    /// Parses `KEY = [v1, v2, …]` (TOML: a dotted key and an array of the setting's values).
    pub fn parse(text: &str) -> Result<Self, CliError> {
        let usage = |problem: String| {
            CliError::Usage(format!(
                "--vary '{text}': {problem}; write one setting and its values as a TOML array, e.g. --vary 'volume.rays_per_probe = [64, 256]'"
            ))
        };
        let table: toml::Table = toml::from_str(text).map_err(|e| usage(e.message().into()))?;
        let (mut key, mut value) = (Vec::new(), toml::Value::Table(table));
        while let toml::Value::Table(t) = value {
            if t.len() != 1 {
                return Err(usage(format!("it names {} settings at one level", t.len())));
            }
            let (k, v) = t.into_iter().next().expect("one entry");
            key.push(k);
            value = v;
        }
        let toml::Value::Array(values) = value else {
            return Err(usage("the values are not in an array".into()));
        };
        if values.is_empty() || values.len() > MAX_VALUES {
            return Err(usage(format!(
                "{} values: give 1 to {MAX_VALUES}",
                values.len()
            )));
        }
        if key.first().is_some_and(|k| k == "preset") {
            return Err(usage(
                "presets are chosen per technique: list ddgi{preset = \"fast\"},ddgi{preset = \"quality\"} instead"
                    .into(),
            ));
        }
        Ok(Self { key, values })
    }
}

/// Each choice at every combination of the `varies`' values (the first `--vary` outermost), its
/// label extended with the values it takes. A `--vary` applies to the techniques that have the
/// setting and leaves the others as they are, so that one call can time DDGI's grid beside
/// SSIL's; a setting no listed technique has is an error.
pub fn expand(
    choices: &[TechniqueChoice],
    varies: &[Vary],
) -> Result<Vec<TechniqueChoice>, CliError> {
    let mut all = choices.to_vec();
    for vary in varies {
        let mut next = Vec::new();
        let mut applied = false;
        for choice in &all {
            if !has_setting(choice, vary)? {
                next.push(choice.clone());
                continue;
            }
            applied = true;
            for value in &vary.values {
                let mut choice = choice.clone();
                irradiant::settings::set_path(&mut choice.overrides, &vary.key, value.clone());
                choice.label = format!("{} {}={}", choice.label, vary.key.join("."), value);
                next.push(choice);
            }
        }
        if !applied {
            return Err(CliError::Usage(format!(
                "--vary {}: none of the techniques listed has that setting (docs/guide.md lists where each technique's settings are)",
                vary.key.join(".")
            )));
        }
        all = next;
    }
    Ok(all)
}

/// Whether the choice's technique knows the varied setting: setting it adds no unknown-key
/// warning to what the technique's own check says (a value it refuses is a setting it has:
/// the refusal comes when the specs are checked).
fn has_setting(choice: &TechniqueChoice, vary: &Vary) -> Result<bool, CliError> {
    let kind =
        irradiant::registry::find(&choice.name).map_err(|e| CliError::Usage(e.to_string()))?;
    let mut spec = irradiant::TechniqueSpec::new(
        &choice.name,
        choice.preset.unwrap_or(irradiant::Preset::Balanced),
    );
    spec.settings = choice.overrides.clone();
    let before = kind.check(&spec);
    irradiant::settings::set_path(&mut spec.settings, &vary.key, vary.values[0].clone());
    let after = kind.check(&spec);
    Ok(match (before, after) {
        (Ok(before), Ok(after)) => after.len() <= before.len(),
        _ => true,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn varies_multiply_the_techniques_first_outermost() {
        let choices =
            crate::options::technique_list(&["ddgi{volume.probe_counts = [4, 2, 4]},ssil".into()])
                .unwrap();
        let varies = [
            Vary::parse("volume.rays_per_probe = [64, 256]").unwrap(),
            Vary::parse("speed.probe_states = [false, true]").unwrap(),
        ];
        assert_eq!(varies[0].key, ["volume", "rays_per_probe"]);
        let all = expand(&choices, &varies).unwrap();
        // DDGI takes both (2 × 2); SSIL has neither setting and is timed once as it is.
        assert_eq!(all.len(), 5);
        let ddgi = &all[1];
        assert_eq!(
            ddgi.label,
            "ddgi{volume.probe_counts=[4,2,4]} volume.rays_per_probe=64 speed.probe_states=true"
        );
        // The spec's own keys stay beside the varied ones.
        assert_eq!(
            ddgi.overrides["volume"]["probe_counts"]
                .as_array()
                .unwrap()
                .len(),
            3
        );
        assert_eq!(
            ddgi.overrides["volume"]["rays_per_probe"].as_integer(),
            Some(64)
        );
        assert_eq!(
            ddgi.overrides["speed"]["probe_states"].as_bool(),
            Some(true)
        );
        assert_eq!(all[4].label, "ssil");
        assert!(all[4].overrides.is_empty());
        let ssil_grid = expand(
            &crate::options::technique_list(&["ssil".into()]).unwrap(),
            &[
                Vary::parse("start = [\"quarter\", \"half\"]").unwrap(),
                Vary::parse("visibility = [false, true]").unwrap(),
            ],
        )
        .unwrap();
        assert_eq!(ssil_grid.len(), 4);
        assert_eq!(ssil_grid[3].label, "ssil start=\"half\" visibility=true");
        let e = expand(&choices, &[Vary::parse("magic = [1, 2]").unwrap()])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("none of the techniques listed has that setting"),
            "{e}"
        );
    }

    #[test]
    fn a_malformed_vary_says_how_to_write_one() {
        for (bad, expected) in [
            ("rays = 64", "not in an array"),
            ("rays = []", "0 values"),
            ("a = [1]\nb = [2]", "2 settings"),
            ("volume.rays_per_probe", "TOML array"),
            ("preset = [\"fast\"]", "per technique"),
        ] {
            let e = Vary::parse(bad).unwrap_err().to_string();
            assert!(e.contains(expected), "{bad}: {e}");
        }
    }
}
