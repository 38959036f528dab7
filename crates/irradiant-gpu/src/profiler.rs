//! GPU pass timing with timestamp queries: each compute pass labelled `technique/stage` gets a
//! begin and an end timestamp; [`Profiler::read`] turns them into milliseconds.

use crate::{GpuContext, GpuError, read_buffer};

/// The GPU time of one pass of a frame.
#[derive(Clone, Debug)]
pub struct PassTiming {
    /// The pass's label, `technique/stage`.
    pub label: String,
    /// Time from the pass's beginning timestamp to its end one, in milliseconds.
    pub milliseconds: f64,
    /// Time from the frame's first pass's beginning to this pass's, in milliseconds: with
    /// `milliseconds`, the span of several passes, the gaps between them included.
    pub start_milliseconds: f64,
}

/// Timestamp queries for the compute passes of a frame, read back as [`PassTiming`]s.
/// Records nothing where the device has no timestamp queries.
pub struct Profiler {
    query_set: Option<wgpu::QuerySet>,
    resolve: Option<wgpu::Buffer>,
    capacity: u32,
    labels: Vec<String>,
    period_ns: f64,
}

impl Profiler {
    /// `capacity` passes per frame. Without TIMESTAMP_QUERY the profiler records nothing.
    pub fn new(ctx: &GpuContext, capacity: u32) -> Self {
        let enabled = ctx.info.timestamps;
        let query_set = enabled.then(|| {
            ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("profiler/timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: capacity * 2,
            })
        });
        let resolve = enabled.then(|| {
            ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("profiler/resolve"),
                size: capacity as u64 * 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        });
        Self {
            query_set,
            resolve,
            capacity,
            labels: Vec::new(),
            period_ns: ctx.queue.get_timestamp_period() as f64,
        }
    }

    /// Whether the device has timestamp queries, so that passes are timed.
    pub fn enabled(&self) -> bool {
        self.query_set.is_some()
    }

    /// Timestamp writes for the next pass, or `None` when disabled or full.
    pub fn pass(&mut self, label: &str) -> Option<wgpu::ComputePassTimestampWrites<'_>> {
        let query_set = self.query_set.as_ref()?;
        let index = self.labels.len() as u32;
        if index >= self.capacity {
            return None;
        }
        self.labels.push(label.to_owned());
        Some(wgpu::ComputePassTimestampWrites {
            query_set,
            beginning_of_pass_write_index: Some(2 * index),
            end_of_pass_write_index: Some(2 * index + 1),
        })
    }

    /// Records the resolve of this frame's timestamps; call before submitting the encoder.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        if let (Some(q), Some(b)) = (&self.query_set, &self.resolve) {
            let n = self.labels.len() as u32 * 2;
            if n > 0 {
                encoder.resolve_query_set(q, 0..n, b, 0);
            }
        }
    }

    /// Reads the timings of the submitted frame and starts a new one.
    pub fn read(&mut self, ctx: &GpuContext) -> Result<Vec<PassTiming>, GpuError> {
        let labels = std::mem::take(&mut self.labels);
        let Some(buffer) = &self.resolve else {
            return Ok(Vec::new());
        };
        if labels.is_empty() {
            return Ok(Vec::new());
        }
        let bytes = read_buffer(ctx, buffer, 0, labels.len() as u64 * 16)?;
        let ticks: &[u64] = bytemuck::cast_slice(&bytes);
        let to_ms = |t: u64| t as f64 * self.period_ns * 1e-6;
        Ok(labels
            .into_iter()
            .enumerate()
            .map(|(i, label)| PassTiming {
                label,
                milliseconds: to_ms(ticks[2 * i + 1].saturating_sub(ticks[2 * i])),
                start_milliseconds: to_ms(ticks[2 * i].saturating_sub(ticks[0])),
            })
            .collect())
    }
}
