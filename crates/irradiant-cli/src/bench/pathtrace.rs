//! The path tracer's sample, timed on both schedules: one sample a pixel and a batch of
//! sixteen, and the wavefront's sample split by pass.

use irradiant::GpuScene;
use irradiant::pathtrace::{PathSchedule, PathTraceSettings, PathTracer};
use irradiant_gpu::GpuContext;

use super::{PassRecord, RayRun, pass_record, time_passes};
use crate::CliError;

/// One sample a pixel, as the viewer traces while the camera rests, and sixteen in one
/// submission, as references are rendered: per sample, the megakernel's idle lanes spread over
/// more paths. The wavefront's sample of one is also split by its passes' labels
/// (`pathtrace/tail (wavefront, 1 spp)`, …: each the median over the runs of that
/// label's passes summed in a run), so that a change to one pass shows where it lands.
pub(super) fn time_path_tracer(
    ctx: &GpuContext,
    (scene, gpu_scene): (&irradiant_scene::Scene, &GpuScene),
    run: &RayRun,
) -> Result<Vec<PassRecord>, CliError> {
    let (size, timing, order) = (run.size, run.timing, run.order);
    let mut records = Vec::new();
    for samples in [1, 16] {
        for (schedule, label) in [
            (PathSchedule::Megakernel, "pathtrace/trace"),
            (PathSchedule::Wavefront, "pathtrace/wavefront"),
        ] {
            let mut tracer = PathTracer::new(ctx, gpu_scene, size.0, size.1)?;
            let settings = PathTraceSettings {
                samples_per_pixel: samples,
                samples_per_dispatch: samples,
                schedule,
                ..PathTraceSettings::balanced()
            };
            let timed = time_passes(ctx, timing, |encoder, profiler| {
                tracer.record(
                    ctx,
                    encoder,
                    gpu_scene,
                    &scene.camera,
                    &settings,
                    samples,
                    profiler,
                )?;
                Ok(())
            })?;
            if tracer.traced_with() != schedule {
                continue;
            }
            let label = match samples {
                1 => format!("{label} (1 spp)"),
                _ => format!("{label} (a sample of {samples})"),
            };
            records.push(pass_record(
                &scene.name,
                order,
                &label,
                &timed
                    .spans
                    .iter()
                    .map(|t| t / samples as f64)
                    .collect::<Vec<_>>(),
                None,
            ));
            if samples == 1 && schedule == PathSchedule::Wavefront {
                for (pass, times) in &timed.by_label {
                    records.push(pass_record(
                        &scene.name,
                        order,
                        &format!("{pass} (wavefront, 1 spp)"),
                        times,
                        None,
                    ));
                }
            }
        }
    }
    Ok(records)
}
