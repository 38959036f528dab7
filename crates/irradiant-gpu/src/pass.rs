//! Compute passes declared once, in their WGSL.
//!
//! A pass's bindings are the `@group(g) @binding(b) var name: …` declarations of its composed
//! WGSL that its entry point uses; [`ComputePass::new`] reads them with naga and builds the bind
//! group layouts from them, and [`ComputePass::bind`] fills each binding from
//! [`ResourceTable`]s by its name. Nothing is bound by position, and a binding is written in one
//! place: its WGSL declaration. An unknown or missing name is an error naming the pass and the
//! binding.
//!
//! Every dispatch goes through [`Workgroups`], whose constructors fold large counts so that no
//! dimension exceeds the 65 535 workgroups every adapter allows.

use std::sync::Arc;

use crate::{GpuContext, GpuError, Profiler};

mod reflect;
use reflect::reflect;

/// Workgroups any adapter allows in each dimension of a dispatch (WebGPU's minimum limit).
pub const MAX_WORKGROUPS_PER_DIMENSION: u32 = 65_535;

/// Rows of a folded dispatch: linear counts past this continue in the next row. Shaders that
/// write an indirect dispatch's counts fold them the same way.
pub const WORKGROUP_FOLD: u32 = 32_768;

/// The workgroup counts of one dispatch. Only its constructors make one, and each keeps every
/// dimension within [`MAX_WORKGROUPS_PER_DIMENSION`] by construction, so no pass can ask for
/// more than an adapter allows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Workgroups([u32; 3]);

impl Workgroups {
    /// `count` workgroups in a row, folded into rows of 32 768 past that. Shaders recover
    /// the linear workgroup index as `group.x + group.y * num_workgroups.x` (and skip the
    /// excess of the last row).
    pub fn linear(count: u64) -> Self {
        let count = count.max(1);
        let x = count.min(WORKGROUP_FOLD as u64) as u32;
        let y = count.div_ceil(x as u64);
        // More than 2^31 workgroups: no buffer an adapter binds is that large, so sizes checked
        // before allocation (crate::budget) never get here; saturate rather than wrap.
        Self([x, y.min(MAX_WORKGROUPS_PER_DIMENSION as u64) as u32, 1])
    }

    /// Enough workgroups of `size` threads for `threads` threads, folded as [`Self::linear`];
    /// the linear thread index is `(group.x + group.y * num_workgroups.x) * size + local`.
    pub fn for_threads(threads: u64, size: u32) -> Self {
        Self::linear(threads.div_ceil(size.max(1) as u64))
    }

    /// A 2D dispatch over a `width`×`height` image with `tile`-sized workgroups (8×8 in every
    /// image pass): the largest image side (16 384) needs 2 048.
    pub fn for_image(width: u32, height: u32, tile: (u32, u32)) -> Self {
        let x = width
            .div_ceil(tile.0)
            .clamp(1, MAX_WORKGROUPS_PER_DIMENSION);
        let y = height
            .div_ceil(tile.1)
            .clamp(1, MAX_WORKGROUPS_PER_DIMENSION);
        Self([x, y, 1])
    }

    /// A 3D dispatch over `layers` images of `width`×`height` (a probe map a layer) with
    /// `tile`-sized workgroups: z is the layer.
    pub fn for_layers(width: u32, height: u32, layers: u32, tile: (u32, u32)) -> Self {
        let [x, y, _] = Self::for_image(width, height, tile).0;
        Self([x, y, layers.clamp(1, MAX_WORKGROUPS_PER_DIMENSION)])
    }

    /// The workgroup counts in x, y and z, as `dispatch_workgroups` takes them.
    pub fn counts(self) -> [u32; 3] {
        self.0
    }

    /// Workgroups in all: the product of the three counts.
    pub fn total(self) -> u64 {
        self.0.iter().map(|&c| c as u64).product()
    }

    /// Whether every dimension is within `limit` (an adapter's
    /// `max_compute_workgroups_per_dimension`).
    pub fn fits(self, limit: u32) -> bool {
        self.0.iter().all(|&c| c <= limit)
    }
}

/// One resource a binding can take.
#[derive(Clone, Copy)]
pub enum Resource<'a> {
    /// A buffer, bound whole.
    Buffer(&'a wgpu::Buffer),
    /// A texture view, for a sampled or a storage texture binding.
    Texture(&'a wgpu::TextureView),
    /// A sampler.
    Sampler(&'a wgpu::Sampler),
}

impl Resource<'_> {
    fn kind(&self) -> &'static str {
        match self {
            Resource::Buffer(_) => "a buffer",
            Resource::Texture(_) => "a texture",
            Resource::Sampler(_) => "a sampler",
        }
    }
}

/// Resources by name: what a scene, a frame or a technique offers its passes.
#[derive(Default)]
pub struct ResourceTable<'a> {
    entries: Vec<(String, Resource<'a>)>,
}

impl<'a> ResourceTable<'a> {
    /// An empty table.
    pub fn new() -> Self {
        Self::default()
    }

    /// Offers `buffer` under `name`.
    pub fn buffer(mut self, name: impl Into<String>, buffer: &'a wgpu::Buffer) -> Self {
        self.entries.push((name.into(), Resource::Buffer(buffer)));
        self
    }

    /// Offers the texture `view` under `name`, for sampled and storage bindings alike.
    pub fn texture(mut self, name: impl Into<String>, view: &'a wgpu::TextureView) -> Self {
        self.entries.push((name.into(), Resource::Texture(view)));
        self
    }

    /// Offers `sampler` under `name`.
    pub fn sampler(mut self, name: impl Into<String>, sampler: &'a wgpu::Sampler) -> Self {
        self.entries.push((name.into(), Resource::Sampler(sampler)));
        self
    }

    /// The resource offered under `name`, if any (the first, if it is offered twice).
    pub fn get(&self, name: &str) -> Option<Resource<'a>> {
        self.entries
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, r)| *r)
    }

    /// The names offered, in the order they were added.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|(n, _)| n.as_str())
    }
}

/// Why a pass could not be built or bound. Messages name the pass and the binding.
#[derive(Debug, thiserror::Error)]
pub enum PassError {
    /// The pass's WGSL does not compose or validate.
    #[error(transparent)]
    Shader(#[from] crate::ShaderError),
    /// wgpu refused the pass's layouts, pipeline or bind groups.
    #[error(transparent)]
    Gpu(#[from] GpuError),
    /// A binding cannot be filled: no table offers its name, more than one does, or the
    /// resource offered is of another kind than its declaration.
    #[error("pass '{pass}': binding '{name}' (group {group}, binding {binding}) {problem}")]
    Binding {
        /// Label of the pass.
        pass: String,
        /// Name of the binding, as its WGSL declares it.
        name: String,
        /// Its `@group` index.
        group: u32,
        /// Its `@binding` index.
        binding: u32,
        /// What is wrong, worded to follow the binding in the message.
        problem: String,
    },
    /// The WGSL declares something Irradiant cannot bind: no entry point `main`, a binding
    /// without a name or two at one slot, a type or storage format it does not map, or an
    /// [`unfilterable`](PassDesc::unfilterable) name that no binding has.
    #[error("pass '{pass}': {problem}")]
    Declaration {
        /// Label of the pass.
        pass: String,
        /// What is wrong with its declarations.
        problem: String,
    },
}

/// What a binding holds, as its WGSL declares it.
#[derive(Clone, Debug, PartialEq)]
pub struct BindingDecl {
    /// The variable's name, by which [`ComputePass::bind`] looks the resource up.
    pub name: String,
    /// Its `@group` index.
    pub group: u32,
    /// Its `@binding` index.
    pub binding: u32,
    /// The layout entry's type, read off the declaration.
    pub ty: wgpu::BindingType,
}

/// How a pass is made: its label (`technique/stage`), its WGSL (with `#import`s), the shader
/// constants prepended to it, and the textures that are not filterable (f32 formats, which not
/// every adapter filters: WGSL's types cannot say so).
pub struct PassDesc<'a> {
    /// The pass's label, `technique/stage`: names its pipeline, its errors and its timings.
    pub label: &'static str,
    /// The pass's WGSL, `#import`s unresolved.
    pub source: &'a str,
    /// Constants prepended as `const NAME = value;`: (name, WGSL value).
    pub constants: Vec<(&'static str, String)>,
    /// Names of the float textures that are not filterable.
    pub unfilterable: &'a [&'a str],
}

impl<'a> PassDesc<'a> {
    /// A pass of `source` under `label`, with no constants and no texture named unfilterable.
    pub fn new(label: &'static str, source: &'a str) -> Self {
        Self {
            label,
            source,
            constants: Vec::new(),
            unfilterable: &[],
        }
    }

    /// Adds constants to prepend to the WGSL (see [`compose`](crate::compose)).
    pub fn constants(
        mut self,
        constants: impl IntoIterator<Item = (&'static str, String)>,
    ) -> Self {
        self.constants.extend(constants);
        self
    }

    /// Names the textures that are not filterable: their layout entries, and those
    /// of the samplers used with them, are declared non-filtering.
    pub fn unfilterable(mut self, names: &'a [&'a str]) -> Self {
        self.unfilterable = names;
        self
    }
}

/// Passes a context keeps at most: every technique's at its presets on a few scenes (a
/// technique makes up to about 30).
const PASSES_KEPT: usize = 512;

/// What makes a pass, whole: two passes of one key compose the same WGSL.
#[derive(Clone, PartialEq, Eq, Hash)]
pub(crate) struct PassKey {
    /// The library's modules, hashed: a process may hold several libraries.
    library: u64,
    label: &'static str,
    source: String,
    constants: Vec<(&'static str, String)>,
    unfilterable: Vec<String>,
}

impl PassKey {
    fn of(library: &crate::ShaderLibrary, desc: &PassDesc) -> Self {
        Self {
            library: {
                let mut h = std::collections::hash_map::DefaultHasher::new();
                library.hash_sources(&mut h);
                std::hash::Hasher::finish(&h)
            },
            label: desc.label,
            source: desc.source.to_owned(),
            constants: desc.constants.clone(),
            unfilterable: desc.unfilterable.iter().map(|s| (*s).to_owned()).collect(),
        }
    }
}

/// A compute pipeline and the bind group layouts read off its WGSL.
pub struct ComputePass {
    /// The pass's label, `technique/stage`.
    pub label: &'static str,
    pipeline: wgpu::ComputePipeline,
    /// Per group index: its layout and its bindings (None: the pass uses no binding there).
    groups: Vec<Option<(wgpu::BindGroupLayout, Vec<BindingDecl>)>>,
}

impl ComputePass {
    /// Composes the pass's WGSL, reads the bindings its entry point `main` uses, and creates
    /// the bind group layouts and the pipeline. Errors name the pass. A pass made before on
    /// this context from the same description and library is handed out again.
    pub fn new(
        ctx: &GpuContext,
        library: &crate::ShaderLibrary,
        desc: &PassDesc,
    ) -> Result<Arc<Self>, PassError> {
        let key = PassKey::of(library, desc);
        if let Some(pass) = ctx.passes.lock().unwrap().get(&key) {
            return Ok(pass.clone());
        }
        let pass = Self::create(ctx, library, desc)?;
        let mut passes = ctx.passes.lock().unwrap();
        // Scenes' constants make passes of their own: a long session of many scenes starts
        // over rather than keep every one (techniques alive hold theirs).
        if passes.len() >= PASSES_KEPT {
            passes.clear();
        }
        passes.insert(key, pass.clone());
        Ok(pass)
    }

    fn create(
        ctx: &GpuContext,
        library: &crate::ShaderLibrary,
        desc: &PassDesc,
    ) -> Result<Arc<Self>, PassError> {
        let composed =
            crate::shader::compose_module(desc.label, desc.source, library, &desc.constants)?;
        let declarations = reflect(
            desc.label,
            &composed.module,
            &composed.info,
            desc.unfilterable,
        )?;
        let label = desc.label;
        let pass = ctx.scoped(label, |device| {
            let mut groups: Vec<Option<(wgpu::BindGroupLayout, Vec<BindingDecl>)>> = Vec::new();
            for (group, bindings) in &declarations {
                let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
                    .iter()
                    .map(|b| wgpu::BindGroupLayoutEntry {
                        binding: b.binding,
                        visibility: wgpu::ShaderStages::COMPUTE,
                        ty: b.ty,
                        count: None,
                    })
                    .collect();
                let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(label),
                    entries: &entries,
                });
                while groups.len() < *group as usize {
                    groups.push(None);
                }
                groups.push(Some((layout, bindings.clone())));
            }
            let layouts: Vec<Option<&wgpu::BindGroupLayout>> = groups
                .iter()
                .map(|g| g.as_ref().map(|(layout, _)| layout))
                .collect();
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: &layouts,
                immediate_size: 0,
            });
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(composed.text.clone().into()),
            });
            let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: Some(&layout),
                module: &module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            });
            Self {
                label,
                pipeline,
                groups,
            }
        })?;
        Ok(Arc::new(pass))
    }

    /// The bindings the pass takes, group by group.
    pub fn bindings(&self) -> impl Iterator<Item = &BindingDecl> {
        self.groups.iter().flatten().flat_map(|(_, b)| b.iter())
    }

    /// Binds every binding by its name, looked up in `tables` (the first table that has the
    /// name wins; two that both have it are a mistake caught here). A missing name, or a
    /// resource of the wrong kind, is an error naming the pass and the binding.
    pub fn bind(
        self: &Arc<Self>,
        ctx: &GpuContext,
        tables: &[&ResourceTable],
    ) -> Result<BoundPass, PassError> {
        let mut groups = Vec::with_capacity(self.groups.len());
        for group in &self.groups {
            let Some((layout, bindings)) = group else {
                groups.push(None);
                continue;
            };
            let mut entries = Vec::with_capacity(bindings.len());
            for b in bindings {
                let error = |problem: String| PassError::Binding {
                    pass: self.label.to_owned(),
                    name: b.name.clone(),
                    group: b.group,
                    binding: b.binding,
                    problem,
                };
                let found: Vec<Resource> = tables.iter().filter_map(|t| t.get(&b.name)).collect();
                let resource = match found.as_slice() {
                    [] => {
                        let offered: Vec<&str> = tables.iter().flat_map(|t| t.names()).collect();
                        return Err(error(format!(
                            "is not offered by the scene, the frame or the technique (they offer: {})",
                            offered.join(", ")
                        )));
                    }
                    [one] => *one,
                    _ => {
                        return Err(error(
                            "is offered twice; each name must have one owner".into(),
                        ));
                    }
                };
                let resource = match (&b.ty, resource) {
                    (wgpu::BindingType::Buffer { .. }, Resource::Buffer(buffer)) => {
                        buffer.as_entire_binding()
                    }
                    (
                        wgpu::BindingType::Texture { .. }
                        | wgpu::BindingType::StorageTexture { .. },
                        Resource::Texture(view),
                    ) => wgpu::BindingResource::TextureView(view),
                    (wgpu::BindingType::Sampler(_), Resource::Sampler(sampler)) => {
                        wgpu::BindingResource::Sampler(sampler)
                    }
                    (ty, r) => {
                        return Err(error(format!(
                            "is declared as {} but the resource of that name is {}",
                            describe(ty),
                            r.kind()
                        )));
                    }
                };
                entries.push(wgpu::BindGroupEntry {
                    binding: b.binding,
                    resource,
                });
            }
            let group = ctx.scoped(self.label, |device| {
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(self.label),
                    layout,
                    entries: &entries,
                })
            })?;
            groups.push(Some(group));
        }
        Ok(BoundPass {
            pass: self.clone(),
            groups,
            label: self.label,
        })
    }
}

/// A pass with its bind groups: ready to dispatch.
pub struct BoundPass {
    pass: Arc<ComputePass>,
    groups: Vec<Option<wgpu::BindGroup>>,
    label: &'static str,
}

impl BoundPass {
    /// The label the pass is recorded and timed under.
    pub fn label(&self) -> &'static str {
        self.label
    }

    /// The same pass under another label (`ssil/gather_2`): one pipeline timed per use.
    pub fn labelled(mut self, label: &'static str) -> Self {
        self.label = label;
        self
    }

    /// Records one dispatch in its own compute pass (so that it gets its own timestamps).
    pub fn dispatch(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
        workgroups: Workgroups,
    ) {
        let [x, y, z] = workgroups.counts();
        let mut pass = self.begin(encoder, profiler);
        pass.dispatch_workgroups(x, y, z);
    }

    /// Like [`Self::dispatch`], with the workgroup counts read on the GPU: three u32 at
    /// `offset` in `args`, written by an earlier pass (which folds them as [`Workgroups`] does).
    pub fn dispatch_indirect(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
        args: &wgpu::Buffer,
        offset: u64,
    ) {
        let mut pass = self.begin(encoder, profiler);
        pass.dispatch_workgroups_indirect(args, offset);
    }

    fn begin<'e>(
        &self,
        encoder: &'e mut wgpu::CommandEncoder,
        profiler: Option<&mut Profiler>,
    ) -> wgpu::ComputePass<'e> {
        let timestamp_writes = profiler.and_then(|p| p.pass(self.label));
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(self.label),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pass.pipeline);
        for (i, group) in self.groups.iter().enumerate() {
            if let Some(group) = group {
                pass.set_bind_group(i as u32, group, &[]);
            }
        }
        pass
    }
}

fn describe(ty: &wgpu::BindingType) -> &'static str {
    match ty {
        wgpu::BindingType::Buffer { .. } => "a buffer",
        wgpu::BindingType::Texture { .. } | wgpu::BindingType::StorageTexture { .. } => "a texture",
        wgpu::BindingType::Sampler(_) => "a sampler",
        _ => "another kind of resource",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn workgroups_fold_past_the_limit_and_cover_every_thread() {
        for threads in [0u64, 1, 63, 64, 65, 4_194_240, 4_194_305, 1 << 32, 3 << 33] {
            let w = Workgroups::for_threads(threads, 64);
            assert!(w.fits(MAX_WORKGROUPS_PER_DIMENSION), "{threads}: {w:?}");
            assert!(w.total() * 64 >= threads, "{threads} threads, {w:?}");
        }
        // The largest image, 16 384 a side, in 8×8 tiles.
        assert_eq!(
            Workgroups::for_image(16384, 16384, (8, 8)).counts(),
            [2048, 2048, 1]
        );
        assert_eq!(Workgroups::for_image(1, 1, (8, 8)).counts(), [1, 1, 1]);
        // Small counts stay one row, as before folding existed.
        assert_eq!(Workgroups::linear(100).counts(), [100, 1, 1]);
    }

    fn parse(source: &str) -> (naga::Module, naga::valid::ModuleInfo) {
        let module = naga::front::wgsl::parse_str(source).unwrap();
        let info = naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::all(),
        )
        .validate(&module)
        .unwrap();
        (module, info)
    }

    #[test]
    fn bindings_are_read_off_the_wgsl_with_their_access() {
        let (module, info) = parse(
            "@group(0) @binding(0) var<uniform> params: vec4<f32>;
             @group(0) @binding(3) var<storage, read> input: array<f32>;
             @group(1) @binding(1) var<storage, read_write> output: array<f32>;
             @group(1) @binding(2) var unused: texture_2d<f32>;
             @group(1) @binding(3) var loaded: texture_2d<f32>;
             @group(1) @binding(4) var colour: texture_2d<f32>;
             @group(1) @binding(5) var bilinear: sampler;
             @group(2) @binding(0) var moments: texture_2d<f32>;
             @group(2) @binding(1) var gather: sampler;
             @group(2) @binding(2) var image: texture_storage_2d<rgba16float, write>;
             @compute @workgroup_size(1) fn main() {
                 output[0] = input[0] + params.x + textureGather(0, moments, gather, vec2<f32>(0.5)).x
                     + textureLoad(loaded, vec2<i32>(0), 0).x + textureSampleLevel(colour, bilinear, vec2<f32>(0.5), 0.0).x;
                 textureStore(image, vec2<i32>(0), vec4<f32>(1.0));
             }",
        );
        let groups = reflect("test/pass", &module, &info, &["moments"]).unwrap();
        let names: Vec<(&str, u32, u32)> = groups
            .values()
            .flatten()
            .map(|b| (b.name.as_str(), b.group, b.binding))
            .collect();
        // The unused texture is left out of the layout: nothing needs to bind it.
        assert_eq!(
            names,
            [
                ("params", 0, 0),
                ("input", 0, 3),
                ("output", 1, 1),
                ("loaded", 1, 3),
                ("colour", 1, 4),
                ("bilinear", 1, 5),
                ("moments", 2, 0),
                ("gather", 2, 1),
                ("image", 2, 2)
            ]
        );
        let ty = |name: &str| {
            groups
                .values()
                .flatten()
                .find(|b| b.name == name)
                .unwrap()
                .ty
        };
        assert!(matches!(
            ty("input"),
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                ..
            }
        ));
        assert!(matches!(
            ty("output"),
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: false },
                ..
            }
        ));
        assert!(matches!(
            ty("moments"),
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                ..
            }
        ));
        assert_eq!(
            ty("gather"),
            wgpu::BindingType::Sampler(wgpu::SamplerBindingType::NonFiltering)
        );
        // Loaded only: unfilterable, so that any float format binds. Sampled: filterable.
        assert!(matches!(
            ty("loaded"),
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                ..
            }
        ));
        assert!(matches!(
            ty("colour"),
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                ..
            }
        ));
        assert_eq!(
            ty("bilinear"),
            wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering)
        );
        assert!(matches!(
            ty("image"),
            wgpu::BindingType::StorageTexture {
                format: wgpu::TextureFormat::Rgba16Float,
                access: wgpu::StorageTextureAccess::WriteOnly,
                ..
            }
        ));
    }

    #[test]
    fn unknown_unfilterable_names_are_errors() {
        let (module, info) = parse("@compute @workgroup_size(1) fn main() {}");
        let message = reflect("test/names", &module, &info, &["atlas"])
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("test/names") && message.contains("'atlas'"),
            "{message}"
        );
    }
}
