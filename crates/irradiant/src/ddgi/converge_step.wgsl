// ddgi/converge_step: one thread, recorded before each convergence round and once after the
// last (ddgi_convergence): counts the rounds, 1 to `convergence_rounds`, then sets the round
// back to 0 for the normal update. The rounds dispatch over the list of newly probes
// (DdgiActiveProbes' second list), empty in most frames.
#import ddgi_volume
#import ddgi_states

@group(2) @binding(0) var<uniform> volume: GpuDdgiVolume;
@group(2) @binding(22) var<storage, read_write> convergence: DdgiConvergence;

@compute @workgroup_size(1, 1, 1)
fn main() {
    if convergence.round >= volume.convergence_rounds {
        convergence.round = 0u;
    } else {
        convergence.round += 1u;
    }
}
