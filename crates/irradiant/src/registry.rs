//! The registry of real-time techniques: the one list that `render --technique`, `compare
//! --techniques`, `bench`, the session and the tests find techniques in.
//!
//! It sits above the techniques: it imports each technique's folder, and the techniques import
//! only the trait and types of [`crate::technique`]. Adding a technique touches its own folder
//! and one line of [`REGISTRY`] (the checklist is in docs/architecture.md).

use crate::RenderError;
use crate::settings::TechniqueSpec;
use crate::technique::TechniqueKind;

/// Every real-time technique, in the order tools list them. One line each.
pub static REGISTRY: &[&dyn TechniqueKind] = &[
    &crate::none::NONE,
    &crate::ddgi::CLASSIC_PROBES,
    &crate::ddgi::DDGI,
    &crate::ssil::SSIL,
    &crate::ssil::SSIL_DDGI,
    &crate::lightfield::LIGHTFIELD,
    &crate::lightfield::LIGHTFIELD_TRACED,
    &crate::lightfield::LIGHTFIELD_NAIVE,
];

/// A registered technique by name.
pub fn find(name: &str) -> Result<&'static dyn TechniqueKind, RenderError> {
    REGISTRY
        .iter()
        .copied()
        .find(|k| k.name() == name)
        .ok_or_else(|| {
            let known: Vec<String> = REGISTRY
                .iter()
                .map(|k| format!("{} ({})", k.name(), k.description()))
                .collect();
            RenderError::Settings(format!(
                "unknown technique '{name}': use {}",
                known.join(", ")
            ))
        })
}

/// Every registered name, for command-line value lists.
pub fn names() -> Vec<&'static str> {
    REGISTRY.iter().map(|k| k.name()).collect()
}

impl TechniqueSpec {
    /// The registered technique this spec names (an error listing the registered ones when
    /// none has that name).
    pub fn kind(&self) -> Result<&'static dyn TechniqueKind, RenderError> {
        find(&self.name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::Preset;

    #[test]
    fn registry_names_are_unique_and_specs_round_trip() {
        let names = names();
        for (i, a) in names.iter().enumerate() {
            assert!(!names[i + 1..].contains(a), "{a} registered twice");
        }
        let spec: TechniqueSpec =
            toml::from_str("name = \"ddgi\"\npreset = \"fast\"\n[update]\nhysteresis = 0.9\n")
                .unwrap();
        assert_eq!(spec.preset, Preset::Fast);
        let again: TechniqueSpec = toml::from_str(&toml::to_string(&spec).unwrap()).unwrap();
        assert_eq!(spec, again);
        let e = find("magic").err().unwrap().to_string();
        assert!(e.contains("'magic'") && e.contains("ddgi"), "{e}");
    }
}
