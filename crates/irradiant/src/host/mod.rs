//! Irradiant inside a host's renderer (docs/embedding.md): on the host's device
//! ([`GpuContext::from_host`]), fed the host's G-buffer each frame ([`HostGBuffer`], converted by
//! host/import into Irradiant's layout), recording its passes into the host's command encoder
//! and leaving the indirect light in a texture the host composes. Irradiant's own frames go
//! through the same recording ([`crate::Session`]'s), with its traced G-buffer in place of the
//! host's.
//!
//! ```no_run
//! # fn demo(
//! #     ctx: std::sync::Arc<irradiant::GpuContext>,
//! #     scene: irradiant_scene::Scene,
//! #     camera: irradiant_scene::Camera,
//! #     gbuffer: irradiant::host::HostGBuffer,
//! # ) -> Result<(), irradiant::RenderError> {
//! use irradiant::host::HostGi;
//! let mut gi = HostGi::new(ctx.clone(), scene, irradiant::SessionSettings {
//!     size: (1280, 720),
//!     technique: irradiant::TechniqueSpec::new("ddgi", irradiant::Preset::Balanced),
//!     ..Default::default()
//! })?;
//! let mut encoder = ctx.device.create_command_encoder(&Default::default());
//! gi.record(&mut encoder, &camera, &gbuffer)?;   // after the host's G-buffer pass
//! ctx.queue.submit([encoder.finish()]);
//! // gi.indirect(): rgba16float, the indirect light to add to the host's lit image.
//! # Ok(()) }
//! ```

mod compose;
pub mod constants;
mod gbuffer;

use std::sync::Arc;

use irradiant_gpu::{BoundPass, ComputePass, GpuContext, PassDesc, ResourceTable, wgpu};
use irradiant_scene::{Camera, Scene};

pub use gbuffer::{
    DepthConvention, GpuHostImport, HostGBuffer, MaterialChannels, MotionConvention, NormalEncoding,
};

use crate::session::{GBufferSource, HOST_SCENE};
use crate::{RenderError, Session, SessionSettings};

/// The host's textures host/import reads: never filterable (a depth or 32-bit float texture
/// may stand in any of them).
const HOST_TEXTURES: &[&str] = &[
    "host_depth",
    "host_normal",
    "host_base_colour",
    "host_material",
    "host_emission",
    "host_motion",
];

/// Irradiant's G-buffer textures ([`HostGi::native_gbuffer`]), in the layout of
/// `frame/gbuffer_layout.wgsl` (docs/embedding.md, "Drawing into Irradiant's G-buffer"); each
/// has RENDER_ATTACHMENT usage, in the format [`NativeGBuffer::formats`] gives.
pub struct NativeGBuffer<'a> {
    /// r32float: the distance along the camera ray through the pixel's centre; negative
    /// (clear to -1) where the pixel sees no surface.
    pub depth: &'a wgpu::TextureView,
    /// rgba16float: xy the shading normal, zw the geometric normal, both in world space,
    /// turned towards the camera and octahedral-encoded ([`OCTAHEDRAL_WGSL`]'s `oct_encode`).
    pub normal: &'a wgpu::TextureView,
    /// rgba16float: rgb the linear base colour, a the perceptual roughness.
    pub albedo: &'a wgpu::TextureView,
    /// rgba16float: rgb the emitted radiance towards the camera, a the metalness.
    pub emission: &'a wgpu::TextureView,
    /// rgba32float: xy where the surface was last frame minus where it is now, in pixels; z
    /// the specular scale (1 for most materials); w unused.
    pub motion: &'a wgpu::TextureView,
    /// The formats of depth, normal, albedo, emission and motion, in this order: the host's
    /// render pipeline's colour targets.
    pub formats: [wgpu::TextureFormat; 5],
}

/// Bytes a sample the five targets of [`NativeGBuffer`] take: r32float, three rgba16float and
/// rgba32float.
const NATIVE_BYTES_PER_SAMPLE: u32 = 4 + 3 * 8 + 16;

/// The WGSL of Irradiant's octahedral normal encoding (`oct_encode`, `oct_decode`), for a
/// host's shader that writes [`NativeGBuffer::normal`]: prepend it to the shader's source.
pub const OCTAHEDRAL_WGSL: &str = include_str!("../probes/octahedral.wgsl");

/// The indirect light the host composes, and the pass that writes it.
struct HostOutput {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    pass: BoundPass,
}

/// Global illumination for a host's frames: a session whose G-buffer is the host's.
pub struct HostGi {
    session: Session,
    composer: compose::Composer,
    import: Arc<ComputePass>,
    /// host/import bound to the host's textures and the frame's G-buffer (its depth stands
    /// for the frame): bound again only when either changes, not every frame.
    bound_import: Option<([wgpu::Texture; 7], BoundPass)>,
    import_params: wgpu::Buffer,
    /// The conventions last written into `import_params`: written again only when they change.
    written_params: Option<GpuHostImport>,
    output: HostOutput,
    /// Whether frame/direct runs for the host ([`HostGi::set_direct_light`]).
    direct_light: bool,
}

impl HostGi {
    /// Builds the scene, the frame (without TAA: the host's G-buffer is not jittered) and the
    /// technique on `ctx` (the host's device, [`GpuContext::from_host`]).
    /// The host's scene is checked first as a loaded file is (`irradiant_scene::validate`): a
    /// vertex that is not finite, an index or a material out of range is refused naming the
    /// mesh; what can be repaired is, with a warning in `session().warnings()`.
    pub fn new(
        ctx: Arc<GpuContext>,
        mut scene: Scene,
        mut settings: SessionSettings,
    ) -> Result<Self, RenderError> {
        settings.frame = settings.frame.without_taa();
        let mut warnings = Vec::new();
        irradiant_scene::validate(&mut scene, HOST_SCENE.as_ref(), &mut warnings)
            .map_err(|e| RenderError::Settings(e.to_string()))?;
        let mut session = Session::new(ctx, scene, settings)?;
        session.add_warnings(warnings);
        let ctx = session.ctx();
        let import = crate::shaders::pass(
            ctx,
            &PassDesc::new("host/import", include_str!("import.wgsl")).unfilterable(HOST_TEXTURES),
        )?;
        let import_params = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("host/import_params"),
            size: std::mem::size_of::<GpuHostImport>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let output = Self::output(&session)?;
        Ok(Self {
            session,
            composer: Default::default(),
            import,
            bound_import: None,
            import_params,
            written_params: None,
            output,
            direct_light: false,
        })
    }

    fn output(session: &Session) -> Result<HostOutput, RenderError> {
        let ctx = session.ctx();
        let texture = irradiant_gpu::texture_2d(
            &ctx.device,
            "host/indirect",
            session.frame().size(),
            wgpu::TextureFormat::Rgba16Float,
            1,
            wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
        );
        let view = texture.create_view(&Default::default());
        let own = ResourceTable::new().texture("host_indirect", &view);
        let pass = crate::shaders::pass(
            ctx,
            &PassDesc::new("host/indirect", include_str!("indirect.wgsl")),
        )?
        .bind(ctx, &[&own, &session.frame().resources.table()])?;
        Ok(HostOutput {
            texture,
            view,
            pass,
        })
    }

    /// Records this frame's global illumination into the host's `encoder`, after the host's
    /// G-buffer pass: the G-buffer imported, the direct light Irradiant's techniques need, the
    /// technique's update and resolve, and the indirect light into [`HostGi::indirect`].
    /// `camera` is the view the G-buffer was rendered from (the previous one is remembered).
    /// Every texture and the camera are checked first; an error names what is wrong.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
        gbuffer: &HostGBuffer,
    ) -> Result<(), RenderError> {
        self.record_frame(encoder, camera, Some(gbuffer), false)
    }

    /// [`HostGi::record`] with every pass timed (timestamp queries, where the adapter has
    /// them): after the host submits `encoder`, `session_mut().read_timings()` reads them.
    pub fn record_timed(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
        gbuffer: &HostGBuffer,
    ) -> Result<(), RenderError> {
        self.record_frame(encoder, camera, Some(gbuffer), true)
    }

    /// Irradiant's own G-buffer, for a host that rasterizes into it instead of handing its
    /// textures over: then [`HostGi::record_native`] reads it as it is, and host/import (a read
    /// and a write of every channel, 0.045 ms at 1080p on an H200) does not run. The views are
    /// the frame's: fetch them again after [`HostGi::resize`].
    /// A device whose `max_color_attachment_bytes_per_sample` is under the 44 bytes the five
    /// targets take is refused by name (request [`GpuContext::requirements`]' limits).
    pub fn native_gbuffer(&self) -> Result<NativeGBuffer<'_>, RenderError> {
        let ctx = self.session.ctx();
        let allowed = ctx.device.limits().max_color_attachment_bytes_per_sample;
        if allowed < NATIVE_BYTES_PER_SAMPLE {
            return Err(RenderError::Settings(format!(
                "the host's device allows {allowed} bytes a sample of colour targets and drawing into Irradiant's G-buffer takes {NATIVE_BYTES_PER_SAMPLE}: request max_color_attachment_bytes_per_sample as GpuContext::requirements lists it, or hand over your own textures (HostGi::record)"
            )));
        }
        let r = &self.session.frame().resources;
        let names = [
            "gbuffer_depth",
            "gbuffer_normal",
            "gbuffer_albedo",
            "gbuffer_emission",
            "gbuffer_motion",
        ];
        Ok(NativeGBuffer {
            formats: names.map(|name| r.texture(name).format()),
            depth: r.view("gbuffer_depth"),
            normal: r.view("gbuffer_normal"),
            albedo: r.view("gbuffer_albedo"),
            emission: r.view("gbuffer_emission"),
            motion: r.view("gbuffer_motion"),
        })
    }

    /// [`HostGi::record`] for a host that drew this frame into [`HostGi::native_gbuffer`].
    pub fn record_native(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
    ) -> Result<(), RenderError> {
        self.record_frame(encoder, camera, None, false)
    }

    /// [`HostGi::record_native`] with every pass timed, as [`HostGi::record_timed`].
    pub fn record_native_timed(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
    ) -> Result<(), RenderError> {
        self.record_frame(encoder, camera, None, true)
    }

    fn record_frame(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        camera: &Camera,
        gbuffer: Option<&HostGBuffer>,
        profiled: bool,
    ) -> Result<(), RenderError> {
        if let Some(gbuffer) = gbuffer {
            gbuffer.check(self.session.frame().size())?;
        }
        let eye = camera.position;
        let valid = [eye, camera.target, camera.up]
            .iter()
            .all(|v| v.is_finite())
            && (camera.target - eye).length() > 0.0
            && camera.fov_y_degrees.is_finite()
            && (1.0..179.0).contains(&camera.fov_y_degrees);
        if !valid {
            return Err(RenderError::Settings(format!(
                "the host's camera {camera:?} is not a view: give a finite position, a target apart from it and a vertical field of view of 1 to 179 degrees"
            )));
        }
        self.session.set_camera(camera.clone());
        if let Some(gbuffer) = gbuffer {
            self.bind_import(gbuffer)?;
        }
        let import = gbuffer
            .and(self.bound_import.as_ref())
            .map(|(_, pass)| pass);
        self.session.record(
            encoder,
            GBufferSource::Host {
                import,
                direct: self.direct_light,
            },
            profiled,
        );
        let groups = self.session.frame().image_groups();
        self.output
            .pass
            .dispatch(encoder, self.session.profiler(profiled), groups);
        if profiled {
            self.session.resolve_timestamps(encoder);
        }
        self.session.finish_frame();
        Ok(())
    }

    /// Writes the host's conventions for host/import, and binds it to the host's textures and
    /// the frame's G-buffer (its depth stands for the frame) where either changed.
    fn bind_import(&mut self, gbuffer: &HostGBuffer) -> Result<(), RenderError> {
        let ctx = self.session.ctx();
        let params = gbuffer.params();
        let written = self.written_params.as_ref().map(bytemuck::bytes_of);
        if written != Some(bytemuck::bytes_of(&params)) {
            ctx.queue
                .write_buffer(&self.import_params, 0, bytemuck::bytes_of(&params));
            self.written_params = Some(params);
        }
        let [a, b, c, d, e, f] = gbuffer.textures();
        let frame_depth = self
            .session
            .frame()
            .resources
            .texture("gbuffer_depth")
            .clone();
        let key = [a, b, c, d, e, f, frame_depth];
        if self
            .bound_import
            .as_ref()
            .is_none_or(|(bound, _)| *bound != key)
        {
            let views = gbuffer.views();
            let host = gbuffer::import_table(&views, &self.import_params);
            let import = self
                .import
                .bind(ctx, &[&host, &self.session.frame().resources.table()])?;
            self.bound_import = Some((key, import));
        }
        Ok(())
    }

    /// The indirect light of the last recorded frame: rgba16float at the frame's size, outgoing
    /// radiance (albedo applied) in rgb, 0 where the pixel sees no surface. Add it to the lit
    /// image.
    pub fn indirect(&self) -> &wgpu::TextureView {
        &self.output.view
    }

    /// Adds the indirect light of the frame just recorded into the host's HDR `target` (of the
    /// frame's size, RENDER_ATTACHMENT usage, a blendable format such as Rgba16Float), on the
    /// same encoder after [`HostGi::record`]: for a host that would rather not sample
    /// [`HostGi::indirect`] in its own lighting pass. The target's alpha is left as it is.
    pub fn compose_into(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::Texture,
    ) -> Result<(), RenderError> {
        let size = self.session.frame().size();
        self.composer
            .record(self.session.ctx(), encoder, &self.output.view, target, size)
    }

    /// Whether Irradiant computes the direct light into [`HostGi::direct`] each frame (off at
    /// first: a host lights its surfaces itself). On costs frame/direct, a ray-traced shadow
    /// ray a light and emitter samples a pixel (0.86 ms of Sibenik at 1080p on an H200,
    /// BENCHMARKS.md); a technique that gathers the lit image (`ssil`) runs it either way.
    pub fn set_direct_light(&mut self, on: bool) {
        if on && !self.direct_light {
            // Its running mean holds frames from before it stopped.
            self.session.restart_direct();
        }
        self.direct_light = on;
    }

    /// The direct light Irradiant computes from the host's G-buffer and the scene's lights
    /// (ray-traced shadows, emitters sampled; a running mean while nothing moves):
    /// rgba32float, radiance in rgb; written only after [`HostGi::set_direct_light`]`(true)`.
    /// A host adds its own direct light instead, or this.
    pub fn direct(&self) -> &wgpu::TextureView {
        self.session.frame().resources.view("direct")
    }

    /// The texture behind [`HostGi::indirect`] (to copy or read back).
    pub fn indirect_texture(&self) -> &wgpu::Texture {
        &self.output.texture
    }

    /// Changes the frame's size to the host's: the technique is rebuilt at it.
    pub fn resize(&mut self, size: (u32, u32)) -> Result<(), RenderError> {
        self.session.resize(size)?;
        self.output = Self::output(&self.session)?;
        Ok(())
    }

    /// The session underneath: the scene's animation (`seek`), the technique and its settings
    /// (`set_technique`), saved probes, the frame's images for measuring.
    pub fn session(&self) -> &Session {
        &self.session
    }

    /// The session underneath, to change.
    pub fn session_mut(&mut self) -> &mut Session {
        &mut self.session
    }
}
