// dispatch: indirect dispatches the shaders write, folded as Workgroups::linear folds direct
// ones so that no dimension passes the 65 535 workgroups every adapter allows.
#import dispatch_constants

// An indirect dispatch's (x, y) for `workgroups` workgroups in a row.
fn folded_groups(workgroups: u32) -> vec2<u32> {
    return vec2<u32>(min(workgroups, WORKGROUP_FOLD), (workgroups + WORKGROUP_FOLD - 1u) / WORKGROUP_FOLD);
}

// A workgroup's place in a folded dispatch (rows are WORKGROUP_FOLD wide whenever there is
// more than one): not from num_workgroups, which wgpu leaves 0 on D3D12 for indirect
// dispatches it does not check.
fn folded_index(group: vec3<u32>) -> u32 {
    return group.x + group.y * WORKGROUP_FOLD;
}

// Rays a workgroup takes where its lanes fetch (bvh_fetch), for `rays` rays in all and a
// dispatch of at most `workgroups`: 64 while they fit, then as many more 64s as it takes
// (shaders::fetch_run).
fn fetch_run(rays: u32, workgroups: u32) -> u32 {
    let per_64 = 64u * max(workgroups, 1u);
    return 64u * max(1u, (rays + per_64 - 1u) / per_64);
}

// The dispatch's (x, y) of `rays` rays whose lanes fetch, a run of fetch_run a workgroup
// (shaders::fetch_dispatch).
fn fetch_groups(rays: u32, workgroups: u32) -> vec2<u32> {
    let run = fetch_run(rays, workgroups);
    return folded_groups((rays + run - 1u) / run);
}

// Whether lanes that fetch pay for `rays` rays in a dispatch of at most `workgroups`: only where
// a run passes 64 rays, so that a lane has more than one to fetch (shaders::fetch_pays).
fn fetch_pays(rays: u32, workgroups: u32) -> bool {
    return rays > 64u * max(workgroups, 1u);
}
