//! Every Rust GPU struct matches its WGSL declaration (size and field offsets).

use irradiant::gpu_types::all_layouts;

#[test]
fn rust_structs_match_wgsl() {
    let sources = [
        include_str!("../src/shaders/types.wgsl"),
        include_str!("../src/pathtrace/params.wgsl"),
        include_str!("../src/pathtrace/gather.wgsl"),
        include_str!("../src/raycast/trace.wgsl"),
        include_str!("../src/frame/frame_types.wgsl"),
        include_str!("../src/ddgi/volume.wgsl"),
        include_str!("../src/ddgi/rays.wgsl"),
        include_str!("../src/ssil/common.wgsl"),
        include_str!("../src/lightfield/lightfield.wgsl"),
        include_str!("../src/lightfield/filter.wgsl"),
        include_str!("../src/lightfield/trace_rays.wgsl"),
    ];
    // The structs are declared across these files; strip imports and bindings so that each
    // parses alone, and check each layout against the file that declares it.
    let mut wgsl = String::new();
    for s in sources {
        for line in s.lines() {
            let t = line.trim_start();
            if t.starts_with("#import") || t.starts_with("@group") {
                continue;
            }
            wgsl.push_str(line);
            wgsl.push('\n');
        }
    }
    // Keep only declarations (structs and consts): cut every function body.
    let declarations = keep_declarations(&wgsl);
    irradiant_gpu::check_struct_layouts(&declarations, &all_layouts()).unwrap();
}

#[test]
fn a_wrong_layout_is_reported() {
    let wgsl = "struct GpuRayHit { t: f32, triangle: u32, instance: u32, _pad: u32, extra: u32 }";
    let layouts: Vec<_> = all_layouts()
        .into_iter()
        .filter(|l| l.0 == "GpuRayHit")
        .collect();
    assert!(irradiant_gpu::check_struct_layouts(wgsl, &layouts).is_err());
}

fn keep_declarations(wgsl: &str) -> String {
    let mut out = String::new();
    let mut depth = 0;
    let mut in_fn = false;
    for line in wgsl.lines() {
        let t = line.trim_start();
        if depth == 0 && (t.starts_with("fn ") || t.starts_with("@compute")) {
            in_fn = true;
        }
        if !in_fn {
            out.push_str(line);
            out.push('\n');
        }
        depth += line.matches('{').count() as i32 - line.matches('}').count() as i32;
        if in_fn && depth == 0 && line.contains('}') {
            in_fn = false;
        }
    }
    out
}
