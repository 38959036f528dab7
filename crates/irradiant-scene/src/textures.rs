//! Texture files: decoding (image crate), case-insensitive lookup, alpha from a separate map.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::model::Texture;

/// Loads each (colour file, alpha file) pair once and hands out indices into the scene's textures.
#[derive(Default)]
pub struct TextureCache {
    textures: Vec<Texture>,
    by_key: HashMap<(String, Option<String>), Option<u32>>,
}

impl TextureCache {
    /// Returns `None` (after a warning) when the file is missing or unreadable: a user expects the
    /// scene to render with flat colour rather than not at all.
    pub fn load(
        &mut self,
        base_dir: &Path,
        name: &str,
        alpha_name: Option<&str>,
        warnings: &mut Vec<String>,
    ) -> Option<u32> {
        let key = (name.to_owned(), alpha_name.map(str::to_owned));
        if let Some(&index) = self.by_key.get(&key) {
            return index;
        }
        let index = match read_rgba(base_dir, name) {
            Ok(mut texture) => {
                if let Some(alpha_name) = alpha_name {
                    match read_rgba(base_dir, alpha_name) {
                        Ok(alpha) => copy_luminance_to_alpha(&mut texture, &alpha),
                        Err(e) => warnings.push(e),
                    }
                }
                self.textures.push(texture);
                Some(self.textures.len() as u32 - 1)
            }
            Err(e) => {
                warnings.push(e);
                None
            }
        };
        self.by_key.insert(key, index);
        index
    }

    pub fn into_textures(self) -> Vec<Texture> {
        self.textures
    }
}

fn read_rgba(base_dir: &Path, name: &str) -> Result<Texture, String> {
    let path = resolve(base_dir, name).ok_or_else(|| {
        format!("{}: texture not found; the material is drawn with its flat colour. Put the file there or fix the name in the material file", base_dir.join(name).display())
    })?;
    let bytes = std::fs::read(&path)
        .map_err(|e| format!("{}: texture cannot be read ({e})", path.display()))?;
    decode_texture(&bytes, name).map_err(|e| {
        format!(
            "{}: texture cannot be decoded ({e}); the material is drawn with its flat colour",
            path.display()
        )
    })
}

/// Largest texture side decoded: larger files are refused before their pixels are allocated
/// (a corrupt header can claim 4 billion pixels).
pub const MAX_TEXTURE_SIDE: u32 = 16384;

/// Decodes a PNG or JPEG (or any format the image crate knows, by its content) into sRGB RGBA8,
/// refusing images past [`MAX_TEXTURE_SIDE`] or 1 GiB of pixels before allocating them.
pub fn decode_texture(bytes: &[u8], name: &str) -> Result<Texture, String> {
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_TEXTURE_SIDE);
    limits.max_image_height = Some(MAX_TEXTURE_SIDE);
    limits.max_alloc = Some(1 << 30);
    reader.limits(limits);
    let image = reader.decode().map_err(|e| e.to_string())?.to_rgba8();
    Ok(Texture {
        name: name.to_owned(),
        width: image.width(),
        height: image.height(),
        rgba8: image.into_raw(),
    })
}

/// Finds `name` under `base_dir`, accepting backslashes and a different letter case
/// (Sponza's MTL names `SP_LUK.JPG` for the file `sp_luk.JPG`).
pub(crate) fn resolve(base_dir: &Path, name: &str) -> Option<PathBuf> {
    let relative = name.replace('\\', "/");
    let exact = base_dir.join(&relative);
    if exact.is_file() {
        return Some(exact);
    }
    let wanted = exact.file_name()?.to_string_lossy().to_lowercase();
    let dir = exact.parent()?;
    std::fs::read_dir(dir)
        .ok()?
        .flatten()
        .map(|e| e.path())
        .find(|p| {
            p.is_file()
                && p.file_name()
                    .is_some_and(|f| f.to_string_lossy().to_lowercase() == wanted)
        })
}

fn copy_luminance_to_alpha(texture: &mut Texture, alpha: &Texture) {
    let (w, h) = (texture.width as usize, texture.height as usize);
    for y in 0..h {
        for x in 0..w {
            // Nearest texel of the mask, which may have another size.
            let ax = x * alpha.width as usize / w;
            let ay = y * alpha.height as usize / h;
            let a = &alpha.rgba8[4 * (ay * alpha.width as usize + ax)..][..3];
            texture.rgba8[4 * (y * w + x) + 3] =
                ((a[0] as u32 + a[1] as u32 + a[2] as u32) / 3) as u8;
        }
    }
}
