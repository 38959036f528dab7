//! DDGI's probes saved to a file and read back at start (`render --save-probes FILE` and
//! `--load-probes FILE`), so that a game starts with converged light instead of warming up.
//! A file is keyed by everything that shapes the probes — the scene's content, its lights and
//! transforms as they stand when it is built, the volumes, the settings, the shaders and this
//! crate's version — and a file saved for anything else is refused with the reason, never
//! used. Written under a temporary name and renamed into place.
//!
//! Layout: the magic (8 bytes, with the format's version), the key (u64), the volumes (u32);
//! then each volume's blended frames (u32) and its buffers (DdgiVolume::saved_buffers), each
//! as its length (u64) and its bytes. Little-endian throughout.

use std::hash::{Hash, Hasher};
use std::io::Write;
use std::path::Path;

use irradiant_gpu::GpuContext;
use irradiant_scene::{ProbeVolumeDesc, Scene};

use super::{Ddgi, DdgiSettings};
use crate::RenderError;

/// The first bytes of a file, with the format's version.
const MAGIC: &[u8; 8] = b"IRDDGI\0\x01";

/// A hash of the scene as the probes see it: its content, and its lights and instance
/// transforms when the technique is built.
pub fn scene_key(scene: &Scene, pose: &irradiant_scene::Pose) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    scene.hash_content(&mut h);
    format!("{:?}{:?}", pose.lights, pose.instance_transforms).hash(&mut h);
    h.finish()
}

/// The key of probes of the scene `scene_key` names, with these settings: it also covers the
/// volumes the settings place, every shader's text and this crate's version.
pub fn probes_key(scene_key: u64, volumes: &[ProbeVolumeDesc], settings: &DdgiSettings) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    env!("CARGO_PKG_VERSION").hash(&mut h);
    crate::shaders::library().hash_sources(&mut h);
    scene_key.hash(&mut h);
    format!("{volumes:?}{settings:?}").hash(&mut h);
    h.finish()
}

/// One volume of a saved file: its blended frames and its buffers' bytes.
pub type SavedVolume<'a> = (u32, Vec<&'a [u8]>);

/// The chunks of a saved file — per volume its frames and buffers — when `bytes` is a file for
/// `key` whose buffers are exactly `sizes` (per volume, per buffer); the reason otherwise.
pub fn parse<'a>(
    bytes: &'a [u8],
    key: u64,
    sizes: &[Vec<u64>],
) -> Result<Vec<SavedVolume<'a>>, String> {
    let take = |rest: &mut &[u8], n: usize| -> Result<Vec<u8>, String> {
        if rest.len() < n {
            return Err("it ends early (truncated)".into());
        }
        let (head, tail) = rest.split_at(n);
        *rest = tail;
        Ok(head.to_vec())
    };
    let mut rest = bytes;
    if take(&mut rest, 8)? != MAGIC {
        return Err("it is not a probe file of this version".into());
    }
    let stored = u64::from_le_bytes(take(&mut rest, 8)?.try_into().expect("8 bytes"));
    if stored != key {
        return Err(
            "it was saved for another scene, other settings or another build of Irradiant".into(),
        );
    }
    let volumes = u32::from_le_bytes(take(&mut rest, 4)?.try_into().expect("4 bytes"));
    if volumes as usize != sizes.len() {
        return Err(format!(
            "it holds {volumes} volumes where the scene has {}",
            sizes.len()
        ));
    }
    let mut out = Vec::new();
    for buffers in sizes {
        let frames = u32::from_le_bytes(take(&mut rest, 4)?.try_into().expect("4 bytes"));
        let mut chunks = Vec::new();
        for &size in buffers {
            let length = u64::from_le_bytes(take(&mut rest, 8)?.try_into().expect("8 bytes"));
            if length != size {
                return Err(format!(
                    "a buffer of {length} bytes where {size} are expected"
                ));
            }
            if (rest.len() as u64) < size {
                return Err("it ends early (truncated)".into());
            }
            let (data, tail) = rest.split_at(size as usize);
            chunks.push(data);
            rest = tail;
        }
        out.push((frames, chunks));
    }
    if !rest.is_empty() {
        return Err(format!("{} bytes are left over", rest.len()));
    }
    Ok(out)
}

impl Ddgi {
    /// The key of its probes as they stand (the scene it was built for, its settings now).
    pub fn probes_key(&self) -> u64 {
        probes_key(self.scene_key, &self.descs, &self.settings)
    }

    /// Writes every volume's probes to `path` (it waits for the GPU).
    pub fn save_probes(&self, ctx: &GpuContext, path: &Path) -> Result<(), RenderError> {
        if self.volumes.iter().any(|v| v.follows()) {
            // Its probes are where the camera was: a file would start another session's
            // window in the wrong place.
            return Err(RenderError::Probes {
                path: path.to_owned(),
                problem: "a volume follows the camera, and its probes move with it: save the probes of volumes that stay (leave out `follow`)".into(),
            });
        }
        let mut bytes = Vec::new();
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&self.probes_key().to_le_bytes());
        bytes.extend_from_slice(&(self.volumes.len() as u32).to_le_bytes());
        for volume in &self.volumes {
            bytes.extend_from_slice(&volume.frame.to_le_bytes());
            for buffer in volume.saved_buffers() {
                bytes.extend_from_slice(&buffer.size().to_le_bytes());
                bytes.extend(irradiant_gpu::read_buffer(ctx, buffer, 0, buffer.size())?);
            }
        }
        crate::frame::write_atomically(path, |temporary| {
            std::fs::File::create(temporary)
                .and_then(|mut f| f.write_all(&bytes).and_then(|()| f.sync_all()))
                .map_err(|e| e.to_string())
        })
        .map_err(|e| RenderError::Probes {
            path: path.to_owned(),
            problem: format!(
                "cannot write the probes: {e}. Check that the folder exists and is writable."
            ),
        })
    }

    /// Reads every volume's probes from `path`, saved by [`Ddgi::save_probes`] for this scene
    /// and these settings: the next frame starts from them. A file for anything else is
    /// refused with the reason.
    pub fn load_probes(&mut self, ctx: &GpuContext, path: &Path) -> Result<(), RenderError> {
        let refuse = |problem: String| RenderError::Probes {
            path: path.to_owned(),
            problem,
        };
        let bytes =
            std::fs::read(path).map_err(|e| refuse(format!("cannot read the probes: {e}")))?;
        let sizes: Vec<Vec<u64>> = (self.volumes.iter())
            .map(|v| v.saved_buffers().iter().map(|b| b.size()).collect())
            .collect();
        let volumes = parse(&bytes, self.probes_key(), &sizes).map_err(|why| {
            refuse(format!(
                "these probes cannot be used: {why}. Save them again with --save-probes for this scene and these settings."
            ))
        })?;
        for (volume, (frames, chunks)) in self.volumes.iter_mut().zip(volumes) {
            volume.restore(ctx, &chunks, frames);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(key: u64, frames: u32, buffers: &[&[u8]]) -> Vec<u8> {
        let mut bytes = MAGIC.to_vec();
        bytes.extend_from_slice(&key.to_le_bytes());
        bytes.extend_from_slice(&1u32.to_le_bytes());
        bytes.extend_from_slice(&frames.to_le_bytes());
        for b in buffers {
            bytes.extend_from_slice(&(b.len() as u64).to_le_bytes());
            bytes.extend_from_slice(b);
        }
        bytes
    }

    #[test]
    fn a_saved_file_is_read_back_and_anything_else_refused() {
        let sizes = vec![vec![4, 2]];
        let good = file(7, 40, &[&[1, 2, 3, 4], &[5, 6]]);
        let parsed = parse(&good, 7, &sizes).unwrap();
        assert_eq!(parsed, vec![(40, vec![&[1u8, 2, 3, 4][..], &[5, 6][..]])]);
        assert!(
            parse(&good, 8, &sizes)
                .unwrap_err()
                .contains("another scene")
        );
        assert!(
            parse(&good[..good.len() - 1], 7, &sizes)
                .unwrap_err()
                .contains("truncated")
        );
        assert!(
            parse(&good, 7, &[vec![4, 3]])
                .unwrap_err()
                .contains("2 bytes where 3")
        );
        assert!(
            parse(&good, 7, &[vec![4, 2], vec![1]])
                .unwrap_err()
                .contains("1 volumes")
        );
        let mut longer = good.clone();
        longer.push(0);
        assert!(parse(&longer, 7, &sizes).unwrap_err().contains("left over"));
        assert!(
            parse(b"not a probe file", 7, &sizes)
                .unwrap_err()
                .contains("not a probe file")
        );
        assert!(parse(&[], 7, &sizes).is_err());
    }

    #[test]
    fn the_key_changes_with_the_scene_and_the_settings() {
        let scene = irradiant_scene::builtin("cornell").unwrap();
        let key = |s: &Scene, settings: &DdgiSettings| {
            let descs = super::super::volume_descs(s, settings);
            probes_key(scene_key(s, &s.pose_at(0.0)), &descs, settings)
        };
        let base = key(&scene, &DdgiSettings::balanced());
        assert_eq!(base, key(&scene, &DdgiSettings::balanced()));
        assert_ne!(base, key(&scene, &DdgiSettings::fast()));
        let mut moved = scene.clone();
        moved.meshes[0].positions[0].y += 1e-3;
        assert_ne!(base, key(&moved, &DdgiSettings::balanced()));
        let mut lit = scene.pose_at(0.0);
        lit.camera.position.x += 1.0;
        assert_eq!(
            scene_key(&scene, &scene.pose_at(0.0)),
            scene_key(&scene, &lit),
            "the camera does not shape the probes"
        );
    }
}
