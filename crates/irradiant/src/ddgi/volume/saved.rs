//! What a volume keeps from frame to frame, as a saved file holds it (ddgi/saved.rs): the
//! atlases, the blend's running values, the probes' offsets and states and the list of those
//! that update next; and the volume restored from them, converged, without a relocation or a
//! classification frame.

// The volume's types and imports, from volume.rs.
use super::*;

impl DdgiVolume {
    /// The buffers a saved volume holds, in the file's order.
    pub fn saved_buffers(&self) -> [&wgpu::Buffer; 7] {
        let r = &self.resources;
        [
            &r.irradiance,
            &r.irradiance_bounce,
            &r.irradiance_history,
            &r.distance,
            &r.offsets,
            &r.states,
            &r.active_probes,
        ]
    }

    /// Takes up saved buffers (each exactly its buffer's size) as of `frames` blended frames:
    /// the atlases' textures are copied from them, and the next frame updates them as the
    /// frame after those would have (no relocation or classification starts over).
    pub fn restore(&mut self, ctx: &GpuContext, data: &[&[u8]], frames: u32) {
        for (buffer, bytes) in self.saved_buffers().into_iter().zip(data) {
            ctx.queue.write_buffer(buffer, 0, bytes);
        }
        let r = &self.resources;
        // The lists' trace dispatches depend on whether this session's kernels fetch (the scene
        // settings', not the key's): rewritten from each list's count, as probe_states would.
        for list in [0, NEWLY_LIST] {
            let word = |at: u64| {
                let i = (list + at) as usize;
                u32::from_le_bytes(data[6][i..i + 4].try_into().expect("a header word"))
            };
            let trace = match self.fetches_rays {
                true => {
                    let rays = u64::from(word(0)) * u64::from(self.settings.volume.rays_per_probe);
                    crate::shaders::fetch_dispatch(rays, self.settings.speed.fetch_workgroups)
                        .counts()
                }
                false => [word(ACTIVE_RAY_GROUPS), word(ACTIVE_RAY_GROUPS + 4), 1],
            };
            let at = list + ACTIVE_TRACE_GROUPS;
            ctx.queue
                .write_buffer(&r.active_probes, at, bytemuck::cast_slice(&trace));
        }
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some("ddgi/restore"),
            });
        copy_atlas_to_texture(
            &mut encoder,
            &r.irradiance,
            &r.irradiance_texture,
            ATLAS_TEXEL_BYTES,
        );
        copy_atlas_to_texture(
            &mut encoder,
            &r.irradiance_bounce,
            &r.irradiance_bounce_texture,
            ATLAS_TEXEL_BYTES,
        );
        copy_atlas_to_texture(
            &mut encoder,
            &r.distance,
            &r.distance_texture,
            ATLAS_TEXEL_BYTES,
        );
        ctx.queue.submit([encoder.finish()]);
        self.frame = frames.max(RELOCATION_FRAMES);
        self.relocation_pending = false;
        self.states_pending = false;
        self.boosts.clear();
    }
}
