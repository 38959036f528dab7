//! Parsing and checking of the options commands share.

use std::path::Path;

use crate::CliError;

/// Largest image side: 16384 is the common GPU texture limit, and 16384² already needs 4 GiB
/// of accumulation buffer.
pub const MAX_SIDE: u32 = 16384;

/// `WxH`, e.g. `1280x720`.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (w, h) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("'{text}' is not a size: write WIDTHxHEIGHT, e.g. 640x480"))?;
    let side = |s: &str| {
        s.trim().parse::<u32>().map_err(|_| {
            format!("'{text}' is not a size: write WIDTHxHEIGHT with whole numbers, e.g. 640x480")
        })
    };
    let (w, h) = (side(w)?, side(h)?);
    if w == 0 || h == 0 {
        return Err(format!("size {w}x{h} has no pixels: use at least 1x1"));
    }
    if w > MAX_SIDE || h > MAX_SIDE {
        return Err(format!(
            "size {w}x{h} is too large: each side at most {MAX_SIDE}"
        ));
    }
    Ok((w, h))
}

/// Checks that an output file can be written before spending GPU time on it.
pub fn check_output(path: &Path, extensions: &[&str]) -> Result<(), CliError> {
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    if !extensions.contains(&extension.as_str()) {
        return Err(CliError::Usage(format!(
            "{}: unsupported output type; end the name in .{}",
            path.display(),
            extensions.join(" or .")
        )));
    }
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        return Err(CliError::Io {
            path: dir.to_owned(),
            message: "the output folder does not exist; create it first".into(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_absurd_ones_are_refused() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("64X64"), Ok((64, 64)));
        assert!(parse_size("0x0").unwrap_err().contains("no pixels"));
        assert!(
            parse_size("100000x100000")
                .unwrap_err()
                .contains("too large")
        );
        assert!(parse_size("big").unwrap_err().contains("WIDTHxHEIGHT"));
        assert!(parse_size("12x-3").is_err());
    }
}
