//! WGSL composition: one small include step used by every shader.
//!
//! A shader names the shared modules it needs with lines `#import name`; [`compose`] replaces
//! each with the module's text (once, however often it is imported, imports first), and
//! prepends `const NAME = value;` for each constant, which is how optional inputs and sizes
//! become shader defines. Naga then validates the result, so a broken shader is an error
//! value, not a panic.

use std::collections::HashSet;

#[derive(Debug, thiserror::Error)]
pub enum ShaderError {
    #[error("shader '{shader}': `#import {module}` names no known module")]
    UnknownModule { shader: String, module: String },
    #[error("shader '{shader}' does not compile:\n{message}")]
    Invalid { shader: String, message: String },
}

/// Named WGSL modules that `#import` can name.
#[derive(Clone, Default)]
pub struct ShaderLibrary {
    modules: Vec<(&'static str, &'static str)>,
}

impl ShaderLibrary {
    pub fn with(mut self, name: &'static str, source: &'static str) -> Self {
        self.modules.push((name, source));
        self
    }

    fn get(&self, name: &str) -> Option<&'static str> {
        self.modules
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, s)| *s)
    }
}

/// Resolves imports and constants, and validates the result with naga.
pub fn compose(
    label: &str,
    source: &str,
    library: &ShaderLibrary,
    constants: &[(&str, String)],
) -> Result<String, ShaderError> {
    let mut out = String::new();
    for (name, value) in constants {
        out.push_str(&format!("const {name} = {value};\n"));
    }
    let mut included = HashSet::new();
    include(label, source, library, &mut included, &mut out)?;
    let module = naga::front::wgsl::parse_str(&out).map_err(|e| ShaderError::Invalid {
        shader: label.to_owned(),
        message: e.emit_to_string(&out),
    })?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|e| ShaderError::Invalid {
        shader: label.to_owned(),
        message: e.emit_to_string(&out),
    })?;
    Ok(out)
}

fn include(
    label: &str,
    source: &str,
    library: &ShaderLibrary,
    included: &mut HashSet<String>,
    out: &mut String,
) -> Result<(), ShaderError> {
    for line in source.lines() {
        if let Some(name) = line.trim().strip_prefix("#import ") {
            let name = name.trim();
            if included.insert(name.to_owned()) {
                let module = library
                    .get(name)
                    .ok_or_else(|| ShaderError::UnknownModule {
                        shader: label.to_owned(),
                        module: name.to_owned(),
                    })?;
                include(label, module, library, included, out)?;
            }
        } else {
            out.push_str(line);
            out.push('\n');
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn imports_are_resolved_once_and_constants_prepended() {
        let lib = ShaderLibrary::default()
            .with("a", "fn a() -> f32 { return 1.0; }")
            .with("b", "#import a\nfn b() -> f32 { return a() + K; }");
        let src = "#import b\n#import a\n@compute @workgroup_size(1) fn main() { _ = b(); }";
        let out = compose("test", src, &lib, &[("K", "2.0".into())]).unwrap();
        assert_eq!(out.matches("fn a()").count(), 1);
        assert!(out.starts_with("const K = 2.0;"));
    }

    #[test]
    fn unknown_imports_and_bad_wgsl_are_errors() {
        let lib = ShaderLibrary::default();
        assert!(matches!(
            compose("t", "#import nope", &lib, &[]),
            Err(ShaderError::UnknownModule { .. })
        ));
        assert!(matches!(
            compose("t", "fn f() -> u32 { return 1.0; }", &lib, &[]),
            Err(ShaderError::Invalid { .. })
        ));
    }
}
