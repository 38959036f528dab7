//! What the command-line tests share: running the binary, a scratch folder, an expected
//! failure.

#![allow(dead_code)] // each test file uses its own share of these

use std::process::Command;

pub fn irradiant(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_irradiant"))
        .args(args)
        .env("XDG_RUNTIME_DIR", "/tmp")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        !stderr.contains("panicked"),
        "irradiant {args:?} panicked:\n{stderr}"
    );
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr,
    )
}

/// Two-rooms with its lamp switching off: a scene that animates.
pub const TWO_ROOMS_SWITCH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenes/two-rooms/switch.toml"
);

/// An empty folder of its own for one test.
pub fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("irradiant-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

pub fn fails_with(args: &[&str], expected: &str) {
    let (ok, _, stderr) = irradiant(args);
    assert!(!ok, "irradiant {args:?} should fail");
    assert!(
        stderr.contains(expected),
        "irradiant {args:?}: expected '{expected}' in:\n{stderr}"
    );
}

/// Whether a run found a GPU adapter; without one a test skips, except under `CI=true` where it
/// goes on and fails.
pub fn has_adapter(ok: bool, stderr: &str) -> bool {
    if !ok && stderr.contains("no GPU adapter") && std::env::var("CI").as_deref() != Ok("true") {
        eprintln!("SKIPPED: no GPU adapter");
        return false;
    }
    true
}
