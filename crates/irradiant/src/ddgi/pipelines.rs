//! DDGI's compute pipelines, compiled once for a scene and a set of build settings and shared
//! by every volume (each volume binds them to its own buffers by name).

use std::sync::Arc;

use irradiant_gpu::{ComputePass, GpuContext, PassDesc};

use super::settings::DdgiSettings;
use crate::RenderError;
use crate::scene::GpuScene;

/// The distance atlas is rg32float, which not every adapter filters: the query gathers it. Every
/// pass that imports `ddgi_query` names it so (DDGI's, the light field's, ssil+ddgi's fill).
pub const QUERY_UNFILTERABLE: &[&str] = &["distance_texture"];

pub struct DdgiPipelines {
    pub ray_directions: Arc<ComputePass>,
    /// ddgi/trace; absent when shade traces its own rays (`fuse_trace_and_shade`).
    pub trace: Option<Arc<ComputePass>>,
    /// ddgi/trace's and ddgi/shadow's lanes fetch their workgroup's next ray
    /// (`DdgiSettings::fetches_rays`).
    pub fetches_rays: bool,
    /// ddgi/shade, or ddgi/trace_shade when fused.
    pub shade: Arc<ComputePass>,
    /// Present when shadow rays are queued (`DdgiSettings::queues_shadow_rays`).
    pub shadow: Option<Arc<ComputePass>>,
    /// Present with several volumes: one volume's share of the probe light at the hits of
    /// another's (or its own) probe rays (light between volumes).
    pub between_volumes: Option<Arc<ComputePass>>,
    pub relocate: Arc<ComputePass>,
    pub window_enter: Arc<ComputePass>,
    pub probe_states: Arc<ComputePass>,
    /// Starts, counts and ends the convergence rounds (ddgi_convergence).
    pub converge_step: Arc<ComputePass>,
    pub blend_weights: Arc<ComputePass>,
    pub blend_irradiance: Arc<ComputePass>,
    pub blend_distance: Arc<ComputePass>,
    pub resolve: Arc<ComputePass>,
    /// Present with the final gather (`gather.rays_per_pixel` > 0): its running mean.
    pub temporal: Option<Arc<ComputePass>>,
    /// With the final gather: ddgi/gather, each volume's share of it on the gather's image
    /// (ddgi/resolve holds the query alone), and ddgi/gather_upsample.
    pub gather: Option<(Arc<ComputePass>, Arc<ComputePass>)>,
    /// ddgi/gather_filter, one a pass (`gather.filter_passes`; none without the gather).
    pub gather_filter: Vec<Arc<ComputePass>>,
    /// ddgi/reflect and ddgi/reflect_filter, with `reflections.enabled`.
    pub reflections: Option<(Arc<ComputePass>, Arc<ComputePass>)>,
    pub visualize: Arc<ComputePass>,
    /// The probes coloured by state, with their relocation offsets (ProbeView::States).
    pub visualize_states: Arc<ComputePass>,
    /// Each pixel coloured by the volumes that light it (ProbeView::Volumes).
    pub visualize_volumes: Arc<ComputePass>,
}

impl DdgiPipelines {
    /// Compiles the passes for `volumes` probe volumes (the light between them only where
    /// there are several), the largest of which casts `most_probe_rays` when every probe
    /// updates.
    pub fn new(
        ctx: &GpuContext,
        scene: &GpuScene,
        settings: &DdgiSettings,
        volumes: usize,
        most_probe_rays: u64,
    ) -> Result<Self, RenderError> {
        let fetches_rays = settings.fetches_rays(scene, most_probe_rays);
        let mut common = scene.shader_constants();
        common.extend(shader_constants(settings));
        common.push(("FETCH_RAYS", format!("{}u", fetches_rays as u32)));
        common.push((
            "FETCH_WORKGROUPS",
            format!("{}u", settings.speed.fetch_workgroups),
        ));
        let compile = |label: &'static str, source: &str, extra: Vec<(&'static str, String)>| {
            let desc = PassDesc::new(label, source)
                .constants(common.clone())
                .constants(extra)
                .unfilterable(QUERY_UNFILTERABLE);
            crate::shaders::pass(ctx, &desc).map_err(RenderError::from)
        };
        let fused = settings.speed.fuse_trace_and_shade;
        let queue = settings.queues_shadow_rays();
        let v = &settings.volume;
        // ddgi_query's atlas textures are named unfilterable in every pass; passes that do not
        // import it do not declare them, and naming them is then an error — so only those.
        let compile_plain =
            |label: &'static str, source: &str, extra: Vec<(&'static str, String)>| {
                let desc = PassDesc::new(label, source)
                    .constants(common.clone())
                    .constants(extra);
                crate::shaders::pass(ctx, &desc).map_err(RenderError::from)
            };
        // ddgi/resolve queries; with the final gather ddgi/gather traces.
        let gather_rays = settings.gather.rays_per_pixel;
        let gather_constants = vec![
            ("GATHER_RAYS", format!("{gather_rays}u")),
            (
                "GATHER_FIREFLY_CLAMP",
                format!("{:?}", settings.gather.firefly_clamp),
            ),
        ];
        let blend = include_str!("resolve_blend.wgsl");
        let resolve_source = format!(
            "{}\n{blend}\n{}",
            include_str!("resolve.wgsl"),
            include_str!("resolve_query.wgsl")
        );
        let gather_source = format!(
            "{}\n{blend}\n{}",
            include_str!("gather.wgsl"),
            include_str!("resolve_gather.wgsl")
        );
        Ok(Self {
            ray_directions: compile_plain(
                "ddgi/ray_directions",
                include_str!("ray_directions.wgsl"),
                vec![],
            )?,
            fetches_rays,
            trace: if fused {
                None
            } else {
                Some(compile_plain(
                    "ddgi/trace",
                    include_str!("trace.wgsl"),
                    vec![],
                )?)
            },
            shade: compile(
                if fused {
                    "ddgi/trace_shade"
                } else {
                    "ddgi/shade"
                },
                include_str!("shade.wgsl"),
                vec![
                    ("FUSED_TRACE", format!("{}u", fused as u32)),
                    ("SHADOW_QUEUE", format!("{}u", queue as u32)),
                    (
                        "TRACED_BOUNCE",
                        format!("{}u", settings.update.traced_bounce as u32),
                    ),
                ],
            )?,
            shadow: if queue {
                Some(compile_plain(
                    "ddgi/shadow",
                    include_str!("shadow.wgsl"),
                    vec![],
                )?)
            } else {
                None
            },
            between_volumes: if volumes > 1 {
                Some(compile(
                    "ddgi/between_volumes",
                    include_str!("between_volumes.wgsl"),
                    vec![],
                )?)
            } else {
                None
            },
            relocate: compile_plain("ddgi/relocate", include_str!("relocate.wgsl"), vec![])?,
            window_enter: compile_plain(
                "ddgi/window_enter",
                include_str!("window_enter.wgsl"),
                vec![],
            )?,
            probe_states: compile_plain(
                "ddgi/probe_states",
                include_str!("probe_states.wgsl"),
                vec![],
            )?,
            converge_step: compile_plain(
                "ddgi/converge_step",
                include_str!("converge_step.wgsl"),
                vec![],
            )?,
            blend_weights: compile_plain(
                "ddgi/blend_weights",
                include_str!("blend_weights.wgsl"),
                vec![],
            )?,
            blend_irradiance: compile_plain(
                "ddgi/blend_irradiance",
                include_str!("blend_irradiance.wgsl"),
                blend_constants(v.irradiance_texels),
            )?,
            blend_distance: compile_plain(
                "ddgi/blend_distance",
                include_str!("blend_distance.wgsl"),
                blend_constants(v.distance_texels),
            )?,
            // resolve_blend.wgsl's switch: the resolve writes the light after the diffuse
            // weight, the gather keeps the light arriving.
            resolve: compile(
                "ddgi/resolve",
                &resolve_source,
                vec![("BLEND_DIFFUSE_WEIGHT", "true".into())],
            )?,
            gather: if gather_rays > 0 {
                Some((
                    compile(
                        "ddgi/gather",
                        &gather_source,
                        [("BLEND_DIFFUSE_WEIGHT", "false".into())]
                            .into_iter()
                            .chain(gather_constants)
                            .collect(),
                    )?,
                    compile_plain(
                        "ddgi/gather_upsample",
                        include_str!("gather_upsample.wgsl"),
                        vec![],
                    )?,
                ))
            } else {
                None
            },
            temporal: if gather_rays > 0 {
                Some(compile_plain(
                    "ddgi/temporal",
                    include_str!("temporal.wgsl"),
                    vec![],
                )?)
            } else {
                None
            },
            gather_filter: if gather_rays > 0 {
                let passes = settings.gather.filter_passes;
                (0..passes)
                    .map(|k| {
                        compile_plain(
                            "ddgi/gather_filter",
                            include_str!("gather_filter.wgsl"),
                            vec![
                                // 1, 2, 4, …: each pass reaches twice as far with the same 3×3 taps.
                                ("FILTER_STEP", format!("{}u", 1u32 << k)),
                                ("FILTER_FIRST", format!("{}u", (k == 0) as u32)),
                            ],
                        )
                    })
                    .collect::<Result<_, _>>()?
            } else {
                Vec::new()
            },
            reflections: if settings.reflections.enabled {
                let constants = settings.reflections.shader_constants();
                Some((
                    compile(
                        "ddgi/reflect",
                        include_str!("reflect.wgsl"),
                        constants.clone(),
                    )?,
                    compile_plain(
                        "ddgi/reflect_filter",
                        include_str!("reflect_filter.wgsl"),
                        constants,
                    )?,
                ))
            } else {
                None
            },
            visualize: compile(
                "ddgi/visualize",
                include_str!("visualize.wgsl"),
                vec![("COLOUR_BY_STATE", "0u".into())],
            )?,
            visualize_states: compile(
                "ddgi/visualize_states",
                include_str!("visualize.wgsl"),
                vec![("COLOUR_BY_STATE", "1u".into())],
            )?,
            visualize_volumes: compile_plain(
                "ddgi/visualize_volumes",
                include_str!("visualize_volumes.wgsl"),
                vec![],
            )?,
        })
    }
}

/// Constants of a blend pass over tiles of `texels` interior texels: TILE_TEXELS (the tile's
/// texels, border included), BLEND_SPLIT (threads sharing one texel: enough to fill 256
/// threads), BLEND_THREADS (a workgroup's threads: BLEND_SPLIT for each tile texel, up to
/// 256) and BLEND_CHUNK (rays held in workgroup memory at once).
fn blend_constants(texels: u32) -> Vec<(&'static str, String)> {
    let tile_texels = (texels + 2) * (texels + 2);
    let split = (256 / tile_texels).max(1);
    vec![
        (
            "BLEND_THREADS",
            format!("{}u", (split * tile_texels).min(256)),
        ),
        ("BLEND_SPLIT", format!("{split}u")),
        ("TILE_TEXELS", format!("{tile_texels}u")),
        ("BLEND_CHUNK", format!("{BLEND_CHUNK}u")),
    ]
}

/// Rays the blend passes hold in workgroup memory at once: 4 KiB of radiance.
const BLEND_CHUNK: u32 = 256;

/// Constants every DDGI shader sees: PROBES_PER_GROUP (ray_slot in rays.wgsl), LIGHT_PER_WARP
/// (ddgi/shade), BLIND_BOUNCES and BLIND_THRESHOLD (ddgi_hit_light's probe rays).
fn shader_constants(settings: &DdgiSettings) -> Vec<(&'static str, String)> {
    vec![
        (
            "PROBES_PER_GROUP",
            format!("{}u", settings.speed.probes_per_group),
        ),
        (
            "LIGHT_PER_WARP",
            format!("{}u", settings.speed.light_per_warp as u32),
        ),
        (
            "BLIND_BOUNCES",
            format!("{}u", settings.update.blind_bounces),
        ),
        (
            "BLIND_THRESHOLD",
            format!("{:?}", settings.update.blind_threshold),
        ),
        // The final gather's image: a texel a pixel, or a 2×2 block (`half_resolution`).
        (
            "GATHER_SCALE",
            format!("{}u", 1 + settings.gather.half_resolution as u32),
        ),
    ]
}
