//! The bake (§3): probes placed and moved out of solids, their radiance, normal and distance
//! maps, the min-mip, and the prefiltered irradiance and distance moments — or all of it read
//! from the disk cache under a key of everything that shapes it.

// The technique's own types, constants and imports, from the folder's mod.rs.
use super::*;

/// What the bake cost.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BakeReport {
    /// Wall-clock milliseconds from the first bake pass to the GPU's finishing the last (or to
    /// the cache entry's upload).
    pub milliseconds: f64,
    /// Bytes of the baked probe data (the maps and the prefiltered atlases).
    pub bytes: u64,
    /// Read from the disk cache.
    pub cached: bool,
}

/// lightfield/prefilter sums every texel of a probe's reduced map, twice (irradiance and
/// distance), in one invocation: 2 × prefilter_resolution² loop iterations. Where the adapter
/// ends an invocation's loops past a limit (llvmpipe), a larger map would be summed only in
/// part, silently; it is refused instead, naming the setting.
pub(super) fn check_prefilter_loops(
    settings: &LightfieldSettings,
    info: &irradiant_gpu::GpuInfo,
) -> Result<(), RenderError> {
    let Some(limit) = info.loop_iteration_limit else {
        return Ok(());
    };
    let size = settings.prefilter_side() as u64;
    if 2 * size * size < limit as u64 {
        return Ok(());
    }
    // The largest power of two under the limit.
    let root = (limit as f64 / 2.0).sqrt() as u32;
    let largest = 1u32 << (31 - root.leading_zeros());
    Err(SettingsError::invalid(
        "technique.bake.prefilter_resolution",
        size,
        format!(
            "{largest} or less on {}, which ends a shader invocation's loops after {limit} \
             iterations and would sum only part of each map (2 × {size}² texels); or pick a \
             hardware GPU with --adapter",
            info.name
        ),
    )
    .into())
}

impl Lightfield {
    pub(super) fn bake_or_load(
        &mut self,
        cx: &TechniqueContext,
    ) -> Result<BakeReport, RenderError> {
        let ctx = cx.ctx;
        let start = Instant::now();
        let key = bake_key(
            cx.scene,
            &self.grid,
            &self.settings.bake,
            self.settings.shade.self_shadow_bias,
        );
        let file = cx.cache_dir.map(|dir| cache::entry_path(dir, key));
        let bytes = self.baked_bytes();
        if let Some(file) = &file
            && cache::load(ctx, file, key, &self.resources.maps)?
        {
            ctx.queue.write_buffer(
                &self.resources.volume,
                0,
                bytemuck::bytes_of(&self.volume()),
            );
            ctx.check("uploading cached light-field probes")?;
            return Ok(BakeReport {
                milliseconds: start.elapsed().as_secs_f64() * 1e3,
                bytes,
                cached: true,
            });
        }
        self.bake_now(cx)?;
        let report = BakeReport {
            milliseconds: start.elapsed().as_secs_f64() * 1e3,
            bytes,
            cached: false,
        };
        if let Some(file) = &file {
            cache::store(ctx, file, key, &self.resources.maps)?;
        }
        Ok(report)
    }

    /// Bakes the probes: one submission a step, each waited on, so that progress is real.
    fn bake_now(&mut self, cx: &TechniqueContext) -> Result<(), RenderError> {
        let ctx = cx.ctx;
        let r = &self.resources;
        let p = &self.pipelines;
        let scene_table = cx.gpu_scene.resources();
        let frame_table = cx.frame.resources.table();
        let shared = r.table();
        let bind =
            |pass: &Arc<ComputePass>, own: ResourceTable| -> Result<BoundPass, RenderError> {
                Ok(pass.bind(ctx, &[&scene_table, &frame_table, &shared, &own])?)
            };
        ctx.queue
            .write_buffer(&r.volume, 0, bytemuck::bytes_of(&self.volume()));
        let geometry = bind(
            &p.bake_geometry,
            ResourceTable::new().texture("target_geometry", &r.maps.geometry.view),
        )?;
        let relocate = bind(
            &p.relocate,
            ResourceTable::new().buffer("target_probe_offsets", &r.maps.offsets),
        )?;
        let min_mip = bind(
            &p.min_mip,
            ResourceTable::new().texture("target_low", &r.maps.low.view),
        )?;
        let states = bind(
            &p.probe_states,
            ResourceTable::new().buffer("target_probe_states", &r.maps.states),
        )?;
        let radiance = bind(
            &p.bake_radiance,
            ResourceTable::new().texture("target_radiance", &r.maps.radiance.view),
        )?;
        let reduce = bind(
            &p.reduce,
            ResourceTable::new()
                .texture("target_small_radiance", &r.small_radiance.view)
                .texture("target_small_moments", &r.small_moments.view),
        )?;
        let prefilter = bind(
            &p.prefilter,
            ResourceTable::new()
                .texture("small_radiance", &r.small_radiance.view)
                .texture("small_moments", &r.small_moments.view)
                .texture("target_irradiance", &r.maps.irradiance.view)
                .texture("target_distance", &r.maps.distance.view),
        )?;
        let dispatches = bake_dispatches(&self.grid, &self.settings);
        let passes = [
            &geometry, &relocate, &min_mip, &states, &radiance, &reduce, &prefilter,
        ];
        // Bounce n's radiance, reduce and prefilter come after everything else.
        let first_bounce_step = dispatches.len() - 3 * (self.settings.bake.bounces as usize + 1);
        let steps = dispatches.len() as u32;
        let progress = cx.progress;
        let report = |done: u32| {
            if let Some(progress) = progress {
                progress.report("baking light-field probes", done, steps);
            }
        };
        report(0);
        for (step, (label, groups)) in dispatches.iter().enumerate() {
            let bounce = (step.saturating_sub(first_bounce_step) / 3) as u32;
            ctx.queue
                .write_buffer(&r.params, 0, bytemuck::bytes_of(&self.params(bounce)));
            let pass = passes[BAKE.iter().position(|b| b == label).expect("a bake pass")];
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
            pass.dispatch(&mut encoder, None, *groups);
            ctx.queue.submit([encoder.finish()]);
            ctx.wait()?;
            report(step as u32 + 1);
        }
        ctx.check("baking light-field probes")?;
        Ok(())
    }
}
