//! Shared by the GPU tests: one adapter, or a loud skip (never a skip when CI=true).

#![allow(dead_code)]

use irradiant::{AdapterChoice, GpuContext};

/// The test adapter. Without one, tests skip with a message on a developer machine and fail
/// under CI (CI=true), where a missing driver must not pass as green.
pub fn gpu() -> Option<GpuContext> {
    match GpuContext::new(&AdapterChoice::from_env()) {
        Ok(ctx) => Some(ctx),
        Err(e) if std::env::var("CI").is_ok_and(|v| v == "true") => panic!("CI=true and no usable GPU adapter: {e}"),
        Err(e) => {
            eprintln!("SKIPPED: no usable GPU adapter ({e})");
            None
        }
    }
}

/// The shared scenes beside the checkout (../shared/scenes).
pub fn shared_scenes() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/scenes")
}

pub fn repo_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}
