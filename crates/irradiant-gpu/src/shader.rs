//! WGSL composition: one small include step used by every shader.
//!
//! A shader names the shared modules it needs with lines `#import name`; [`compose`] replaces
//! each with the module's text (once, however often it is imported, imports first), and
//! prepends `const NAME = value;` for each constant, which is how optional inputs and sizes
//! become shader defines. Naga then validates the result, so a broken shader is an error
//! value, not a panic.
//!
//! Constants that Rust and WGSL share are defined once, in Rust, with [`wgsl_constants!`]:
//! the macro makes the Rust constants and a WGSL module declaring the same values, which the
//! shader library serves under a name like any other module.

use std::borrow::Cow;
use std::collections::HashSet;

/// Why a shader could not be composed.
#[derive(Debug, thiserror::Error)]
pub enum ShaderError {
    /// An `#import` names a module the library does not have.
    #[error("shader '{shader}': `#import {module}` names no known module")]
    UnknownModule {
        /// Label of the shader being composed.
        shader: String,
        /// The name imported.
        module: String,
    },
    /// The composed WGSL does not parse or does not validate with naga.
    #[error("shader '{shader}' does not compile:\n{message}")]
    Invalid {
        /// Label of the shader being composed.
        shader: String,
        /// naga's diagnostic, quoting the composed source.
        message: String,
    },
}

/// Named WGSL modules that `#import` can name.
#[derive(Clone, Default)]
pub struct ShaderLibrary {
    modules: Vec<(&'static str, Cow<'static, str>)>,
}

impl ShaderLibrary {
    /// Adds the module `name`, which `#import name` includes, with its WGSL `source`.
    pub fn with(mut self, name: &'static str, source: impl Into<Cow<'static, str>>) -> Self {
        self.modules.push((name, source.into()));
        self
    }

    /// Feeds every module's name and text into `h`: caches of data the shaders computed key
    /// on it, so that a change to any shader retires their entries.
    pub fn hash_sources<H: std::hash::Hasher>(&self, h: &mut H) {
        use std::hash::Hash;
        for (name, source) in &self.modules {
            name.hash(h);
            source.hash(h);
        }
    }

    fn get(&self, name: &str) -> Option<&str> {
        self.modules
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, s)| s.as_ref())
    }
}

/// A composed shader: its text, and naga's parse and analysis of it.
pub struct Composed {
    /// The composed WGSL: the constants, then the source with each import replaced by its
    /// module.
    pub text: String,
    /// naga's parse of `text`.
    pub module: naga::Module,
    /// naga's validation analysis of `module` (what each entry point uses, among others).
    pub info: naga::valid::ModuleInfo,
}

/// Resolves imports and constants, and validates the result with naga.
pub fn compose(
    label: &str,
    source: &str,
    library: &ShaderLibrary,
    constants: &[(&str, String)],
) -> Result<String, ShaderError> {
    Ok(compose_module(label, source, library, constants)?.text)
}

/// [`compose`], keeping naga's module and analysis (pass reflection reads them).
pub fn compose_module(
    label: &str,
    source: &str,
    library: &ShaderLibrary,
    constants: &[(&str, String)],
) -> Result<Composed, ShaderError> {
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
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&module)
    .map_err(|e| ShaderError::Invalid {
        shader: label.to_owned(),
        message: e.emit_to_string(&out),
    })?;
    Ok(Composed {
        text: out,
        module,
        info,
    })
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

/// A value that can be written as a WGSL constant.
pub trait WgslValue: Copy {
    /// The WGSL type name (`u32`, `i32`, `f32`).
    fn wgsl_type() -> &'static str;
    /// The value as a WGSL literal of that type (`3u`, `-1i`, `0.5`).
    fn literal(self) -> String;
}

impl WgslValue for u32 {
    fn wgsl_type() -> &'static str {
        "u32"
    }
    fn literal(self) -> String {
        format!("{self}u")
    }
}

impl WgslValue for i32 {
    fn wgsl_type() -> &'static str {
        "i32"
    }
    fn literal(self) -> String {
        format!("{self}i")
    }
}

impl WgslValue for f32 {
    fn wgsl_type() -> &'static str {
        "f32"
    }
    fn literal(self) -> String {
        // `{:?}` always writes a decimal point or an exponent, as WGSL's float literals need.
        format!("{self:?}")
    }
}

/// One `const NAME: type = value;` line.
pub fn wgsl_const<T: WgslValue>(name: &str, value: T) -> String {
    format!("const {name}: {} = {};\n", T::wgsl_type(), value.literal())
}

/// Constants shared by Rust and WGSL, defined once: each becomes a Rust `pub const` with its
/// doc comment, and `wgsl()` returns the same constants as WGSL for the shader library.
///
/// ```
/// irradiant_gpu::wgsl_constants! {
///     /// A probe that traces every frame.
///     PROBE_VIGILANT: u32 = 0;
///     BIAS: f32 = 0.2;
/// }
/// assert_eq!(PROBE_VIGILANT, 0);
/// assert!(wgsl().contains("const BIAS: f32 = 0.2;"));
/// ```
#[macro_export]
macro_rules! wgsl_constants {
    ($( $(#[$meta:meta])* $name:ident : $ty:ty = $value:expr ; )*) => {
        $( $(#[$meta])* pub const $name: $ty = $value; )*
        /// These constants as WGSL declarations (a module of the shader library).
        pub fn wgsl() -> String {
            let mut text = String::new();
            $( text.push_str(&$crate::wgsl_const(stringify!($name), $name)); )*
            text
        }
    };
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

    mod shared {
        crate::wgsl_constants! {
            /// A bit.
            FLAG: u32 = 4;
            SCALE: f32 = 0.2;
            NEGATIVE: i32 = -3;
            WHOLE: f32 = 1.0;
        }
    }

    #[test]
    fn shared_constants_compile_as_wgsl_with_the_rust_values() {
        let lib = ShaderLibrary::default().with("shared", shared::wgsl());
        let src = "#import shared\n@compute @workgroup_size(1) fn main() { _ = f32(FLAG) * SCALE * f32(NEGATIVE) * WHOLE; }";
        let out = compose("t", src, &lib, &[]).unwrap();
        assert!(out.contains("const FLAG: u32 = 4u;"), "{out}");
        assert!(out.contains("const SCALE: f32 = 0.2;"), "{out}");
        assert!(out.contains("const NEGATIVE: i32 = -3i;"), "{out}");
        assert!(out.contains("const WHOLE: f32 = 1.0;"), "{out}");
        assert_eq!(shared::FLAG, 4);
    }
}
