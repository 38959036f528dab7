// ddgi/converge_step: one thread, recorded before each convergence round and once after the
// last (ddgi_convergence). Before the first it starts the rounds: if ddgi/probe_states listed
// a newly probe, the rounds' indirect dispatches are those of this frame's list of updating
// probes (only the newly ones take part), else empty; then it counts the rounds, and after the
// last sets the round back to 0 for the normal update.
#import ddgi_volume
#import ddgi_states

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(21) var<storage, read> active_probes: DdgiActiveProbes;
@group(2) @binding(22) var<storage, read_write> convergence: DdgiConvergence;

@compute @workgroup_size(1, 1, 1)
fn main() {
    if convergence.round >= volume.convergence_rounds {
        convergence.round = 0u;
        return;
    }
    if convergence.round == 0u {
        let any_newly = convergence.newly != 0u;
        convergence.newly = 0u;
        let rays = vec4<u32>(active_probes.rays_x, active_probes.rays_y, active_probes.rays_z, 0u);
        let blends = vec4<u32>(active_probes.blends_x, active_probes.blends_y, active_probes.blends_z, 0u);
        convergence.rays = select(vec4<u32>(0u), rays, any_newly);
        convergence.blends = select(vec4<u32>(0u), blends, any_newly);
    }
    convergence.round += 1u;
}
