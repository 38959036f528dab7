//! `--dump-atlas`: the DDGI atlases as images — irradiance as linear EXR and tonemapped PNG,
//! distance (mean) as linear EXR and normalised PNG.

use std::path::Path;

use irradiant::GpuContext;
use irradiant::ddgi::DdgiVolume;
use irradiant::frame::{Image, write_png};

use crate::CliError;

pub fn dump(ctx: &GpuContext, ddgi: &DdgiVolume, dir: &Path) -> Result<(), CliError> {
    let atlases = ddgi.read_atlases(ctx)?;
    let (iw, ih) = atlases.irradiance_size;
    let irradiance = Image {
        width: iw,
        height: ih,
        pixels: atlases.irradiance[..(iw * ih) as usize].to_vec(),
    };
    irradiance.write_exr(&dir.join("irradiance.exr"))?;
    let peak = irradiance
        .pixels
        .iter()
        .flatten()
        .fold(1e-6f32, |m, v| m.max(*v));
    let rgba: Vec<u8> = irradiance
        .pixels
        .iter()
        .flat_map(|p| {
            [p[0], p[1], p[2]]
                .map(|v| ((v / peak).powf(1.0 / 2.2) * 255.0) as u8)
                .into_iter()
                .chain([255])
        })
        .collect();
    write_png(&dir.join("irradiance.png"), &rgba, iw, ih)?;
    let (dw, dh) = atlases.distance_size;
    let distance = Image {
        width: dw,
        height: dh,
        pixels: atlases.distance[..(dw * dh) as usize]
            .iter()
            .map(|d| [d[0], d[1], 0.0])
            .collect(),
    };
    distance.write_exr(&dir.join("distance.exr"))?;
    let far = ddgi.max_ray_distance();
    let rgba: Vec<u8> = distance
        .pixels
        .iter()
        .flat_map(|p| {
            let v = ((p[0] / far).clamp(0.0, 1.0) * 255.0) as u8;
            [v, v, v, 255]
        })
        .collect();
    write_png(&dir.join("distance.png"), &rgba, dw, dh)?;
    println!(
        "wrote {}/irradiance.{{exr,png}} ({iw}×{ih}) and distance.{{exr,png}} ({dw}×{dh})",
        dir.display()
    );
    Ok(())
}
