//! A pass's bindings read from its composed WGSL with naga: each `@group(g) @binding(b)`
//! variable its entry point uses, as the bind group layout entry wgpu needs.

use std::collections::BTreeMap;

use super::{BindingDecl, PassError};

/// The bindings of the entry point `main`, group by group, from the validated module.
pub(super) fn reflect(
    label: &str,
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    unfilterable: &[&str],
) -> Result<BTreeMap<u32, Vec<BindingDecl>>, PassError> {
    let declaration_error = |problem: String| PassError::Declaration {
        pass: label.to_owned(),
        problem,
    };
    let entry = module
        .entry_points
        .iter()
        .position(|e| e.name == "main")
        .ok_or_else(|| declaration_error("has no entry point `main`".into()))?;
    let uses = info.get_entry_point(entry);
    for name in unfilterable {
        if !module
            .global_variables
            .iter()
            .any(|(_, v)| v.name.as_deref() == Some(*name))
        {
            return Err(declaration_error(format!(
                "names '{name}' as unfilterable, but declares no binding of that name"
            )));
        }
    }
    // A float texture is filterable in the layout only where the pass samples it: a texture
    // only loaded is declared unfilterable, which accepts every float format (rgba32float
    // included, which not every adapter filters). Samplers used with a texture named
    // unfilterable must be non-filtering.
    let sampled: Vec<_> = uses.sampling_set.iter().map(|key| key.image).collect();
    let mut non_filtering = Vec::new();
    for key in &uses.sampling_set {
        let image = &module.global_variables[key.image];
        if image
            .name
            .as_deref()
            .is_some_and(|n| unfilterable.contains(&n))
        {
            non_filtering.push(key.sampler);
        }
    }
    let mut groups: BTreeMap<u32, Vec<BindingDecl>> = BTreeMap::new();
    for (handle, var) in module.global_variables.iter() {
        let Some(rb) = &var.binding else { continue };
        if uses[handle].is_empty() {
            continue;
        }
        let name = var.name.clone().ok_or_else(|| {
            declaration_error(format!("binding {}/{} has no name", rb.group, rb.binding))
        })?;
        let inner = &module.types[var.ty].inner;
        let ty = match var.space {
            naga::AddressSpace::Uniform => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            naga::AddressSpace::Storage { access } => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage {
                    read_only: !access.contains(naga::StorageAccess::STORE),
                },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            naga::AddressSpace::Handle => match inner {
                naga::TypeInner::Image {
                    dim,
                    arrayed,
                    class,
                } => {
                    let view_dimension = view_dimension(*dim, *arrayed);
                    match class {
                        naga::ImageClass::Sampled { kind, multi } => wgpu::BindingType::Texture {
                            sample_type: match kind {
                                naga::ScalarKind::Float => wgpu::TextureSampleType::Float {
                                    filterable: sampled.contains(&handle)
                                        && !unfilterable.contains(&name.as_str()),
                                },
                                naga::ScalarKind::Sint => wgpu::TextureSampleType::Sint,
                                _ => wgpu::TextureSampleType::Uint,
                            },
                            view_dimension,
                            multisampled: *multi,
                        },
                        naga::ImageClass::Depth { multi } => wgpu::BindingType::Texture {
                            sample_type: wgpu::TextureSampleType::Depth,
                            view_dimension,
                            multisampled: *multi,
                        },
                        naga::ImageClass::Storage { format, access } => {
                            wgpu::BindingType::StorageTexture {
                                access: storage_access(*access),
                                format: storage_format(*format).ok_or_else(|| {
                                    declaration_error(format!(
                                        "'{name}' has the storage format {format:?}, which Irradiant does not map"
                                    ))
                                })?,
                                view_dimension,
                            }
                        }
                        other => {
                            return Err(declaration_error(format!(
                                "'{name}' is an image of a class Irradiant does not bind ({other:?})"
                            )));
                        }
                    }
                }
                naga::TypeInner::Sampler { comparison } => {
                    wgpu::BindingType::Sampler(if *comparison {
                        wgpu::SamplerBindingType::Comparison
                    } else if non_filtering.contains(&handle) {
                        wgpu::SamplerBindingType::NonFiltering
                    } else {
                        wgpu::SamplerBindingType::Filtering
                    })
                }
                other => {
                    return Err(declaration_error(format!(
                        "'{name}' is a handle of a type Irradiant does not bind ({other:?})"
                    )));
                }
            },
            other => {
                return Err(declaration_error(format!(
                    "'{name}' has a binding in the {other:?} address space"
                )));
            }
        };
        let list = groups.entry(rb.group).or_default();
        if let Some(clash) = list.iter().find(|b| b.binding == rb.binding) {
            return Err(declaration_error(format!(
                "'{}' and '{name}' both declare group {} binding {}",
                clash.name, rb.group, rb.binding
            )));
        }
        list.push(BindingDecl {
            name,
            group: rb.group,
            binding: rb.binding,
            ty,
        });
    }
    Ok(groups)
}

fn view_dimension(dim: naga::ImageDimension, arrayed: bool) -> wgpu::TextureViewDimension {
    use naga::ImageDimension as D;
    match (dim, arrayed) {
        (D::D1, _) => wgpu::TextureViewDimension::D1,
        (D::D2, false) => wgpu::TextureViewDimension::D2,
        (D::D2, true) => wgpu::TextureViewDimension::D2Array,
        (D::D3, _) => wgpu::TextureViewDimension::D3,
        (D::Cube, false) => wgpu::TextureViewDimension::Cube,
        (D::Cube, true) => wgpu::TextureViewDimension::CubeArray,
    }
}

fn storage_access(access: naga::StorageAccess) -> wgpu::StorageTextureAccess {
    let load = access.contains(naga::StorageAccess::LOAD);
    let store = access.contains(naga::StorageAccess::STORE);
    match (load, store) {
        (true, true) => wgpu::StorageTextureAccess::ReadWrite,
        (true, false) => wgpu::StorageTextureAccess::ReadOnly,
        _ => wgpu::StorageTextureAccess::WriteOnly,
    }
}

fn storage_format(format: naga::StorageFormat) -> Option<wgpu::TextureFormat> {
    use naga::StorageFormat as S;
    use wgpu::TextureFormat as T;
    Some(match format {
        S::R32Float => T::R32Float,
        S::R32Uint => T::R32Uint,
        S::R32Sint => T::R32Sint,
        S::Rg32Float => T::Rg32Float,
        S::Rg32Uint => T::Rg32Uint,
        S::Rgba8Unorm => T::Rgba8Unorm,
        S::Rgba8Snorm => T::Rgba8Snorm,
        S::Rgba8Uint => T::Rgba8Uint,
        S::Rgba16Float => T::Rgba16Float,
        S::Rgba16Uint => T::Rgba16Uint,
        S::Rgba32Float => T::Rgba32Float,
        S::Rgba32Uint => T::Rgba32Uint,
        S::Rgba32Sint => T::Rgba32Sint,
        S::Bgra8Unorm => T::Bgra8Unorm,
        _ => return None,
    })
}
