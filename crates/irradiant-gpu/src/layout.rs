//! Checks each Rust GPU struct against its WGSL declaration: same size, same field names at
//! the same offsets. Replaces "keep in sync" comments with a test that fails.

/// The layout of a `#[repr(C)]` Rust struct, for [`check_struct_layouts`]:
/// `gpu_layout!(GpuCamera { position, tan_half_fov_y, … })` lists every field in order.
#[macro_export]
macro_rules! gpu_layout {
    ($ty:ident { $($field:ident),* $(,)? }) => {
        (
            stringify!($ty),
            std::mem::size_of::<$ty>(),
            vec![$((stringify!($field), std::mem::offset_of!($ty, $field))),*],
        )
    };
}

/// Why Rust and WGSL layouts differ, one problem a line, or why the WGSL did not parse.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct StructLayoutError(pub String);

/// One Rust struct's expected layout, as [`check_struct_layouts`] takes it.
pub type Expected = (&'static str, usize, Vec<(&'static str, usize)>);

/// Compares each expected layout with the struct of the same name in `wgsl`.
pub fn check_struct_layouts(wgsl: &str, expected: &[Expected]) -> Result<(), StructLayoutError> {
    let module = naga::front::wgsl::parse_str(wgsl)
        .map_err(|e| StructLayoutError(e.emit_to_string(wgsl)))?;
    let mut problems = Vec::new();
    for (name, size, fields) in expected {
        let found = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref() == Some(*name));
        let Some((_, ty)) = found else {
            problems.push(format!("{name}: no WGSL struct of that name"));
            continue;
        };
        let naga::TypeInner::Struct { members, span } = &ty.inner else {
            problems.push(format!("{name}: not a struct in WGSL"));
            continue;
        };
        if *span as usize != *size {
            problems.push(format!("{name}: Rust size {size}, WGSL size {span}"));
        }
        let wgsl_fields: Vec<(String, usize)> = members
            .iter()
            .map(|m| (m.name.clone().unwrap_or_default(), m.offset as usize))
            .collect();
        let rust_fields: Vec<(String, usize)> =
            fields.iter().map(|(n, o)| (n.to_string(), *o)).collect();
        if wgsl_fields != rust_fields {
            problems.push(format!(
                "{name}: fields differ\n  Rust: {rust_fields:?}\n  WGSL: {wgsl_fields:?}"
            ));
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(StructLayoutError(problems.join("\n")))
    }
}
