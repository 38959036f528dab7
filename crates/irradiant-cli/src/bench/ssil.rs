//! `bench --ssil-start …`: screen-space indirect illumination over the grid of the paper's
//! Figure 9 (start resolution × levels × samples a level × visibility), each pass timed as the
//! paper's table lists them: the voxel grid, each level's gather, upsampling and temporal
//! filtering.

use clap::{Args, ValueEnum};
use irradiant::ssil::{SsilSettings, StartResolution};

use super::FrameRecord;

#[derive(Args)]
pub struct SsilGridArgs {
    /// Time SSIL from each of these start resolutions, comma-separated (the paper's Figure 9:
    /// quarter,half). Left out: SSIL's grid is not timed.
    #[arg(long, value_enum, value_delimiter = ',')]
    pub ssil_start: Vec<StartArg>,
    /// Levels to time SSIL with, comma-separated (Figure 9: 4,5).
    #[arg(long, value_delimiter = ',', default_value = "4")]
    pub ssil_levels: Vec<u32>,
    /// Samples a level to time SSIL with, comma-separated (Figure 9: 64,256).
    #[arg(long, value_delimiter = ',', default_value = "64")]
    pub ssil_samples: Vec<u32>,
    /// Visibility to time SSIL with, comma-separated: on and/or off (Figure 9: off,on).
    #[arg(long, value_enum, value_delimiter = ',', default_value = "on")]
    pub ssil_visibility: Vec<OnOff>,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum StartArg {
    Full,
    Half,
    Quarter,
}

#[derive(Clone, Copy, Debug, PartialEq, ValueEnum)]
pub enum OnOff {
    On,
    Off,
}

/// Every combination of the listed values over the balanced settings (one bounce, glossy on),
/// in the order listed, visibility innermost as in the paper's table.
pub fn variants(args: &SsilGridArgs) -> Vec<SsilSettings> {
    let mut all = Vec::new();
    for start in &args.ssil_start {
        for &levels in &args.ssil_levels {
            for &samples in &args.ssil_samples {
                for visibility in &args.ssil_visibility {
                    all.push(SsilSettings {
                        start: match start {
                            StartArg::Full => StartResolution::Full,
                            StartArg::Half => StartResolution::Half,
                            StartArg::Quarter => StartResolution::Quarter,
                        },
                        levels,
                        samples,
                        visibility: *visibility == OnOff::On,
                        ..SsilSettings::balanced()
                    });
                }
            }
        }
    }
    all
}

/// start/levels/samples/visibility, as the table's column heads.
pub fn variant_name(s: &SsilSettings) -> String {
    format!(
        "{}/{}/{}/{}",
        format!("{:?}", s.start).to_lowercase(),
        s.levels,
        s.samples,
        if s.visibility { "vis" } else { "no-vis" }
    )
}

/// Milliseconds of every pass of `r` whose label `keep` accepts.
fn ms(r: &FrameRecord, keep: impl Fn(&str) -> bool) -> f64 {
    r.passes
        .iter()
        .filter(|(l, _)| keep(l))
        .fold(0.0, |sum, p| sum + p.1)
}

/// One row of Figure 9's table: a stage's time in a configuration's record.
type Column = Box<dyn Fn(&FrameRecord) -> f64>;

/// The paper's Figure 9 laid out as it is: a column per configuration, a row per stage.
pub fn print_table(records: &[FrameRecord]) {
    let Some(first) = records.first() else {
        return;
    };
    let mut rows: Vec<(String, Column)> = vec![
        (
            "G-buffer pyramid".into(),
            Box::new(|r| ms(r, |l| l == "frame/pyramid")),
        ),
        (
            "voxel grid".into(),
            Box::new(|r| ms(r, |l| l == "ssil/voxelize" || l == "ssil/voxel_down")),
        ),
    ];
    for level in 1..=6 {
        let label = format!("ssil/gather_{level}");
        if records
            .iter()
            .any(|r| r.passes.iter().any(|(l, _)| *l == label))
        {
            rows.push((
                format!("level {level}"),
                Box::new(move |r| ms(r, |l| l == label)),
            ));
        }
    }
    rows.push((
        "bounce and probe light".into(),
        Box::new(|r| ms(r, |l| l == "ssil/bounce" || l == "ssil/probe_light")),
    ));
    rows.push((
        "upsampling + temporal".into(),
        Box::new(|r| ms(r, |l| l == "ssil/upsample" || l == "ssil/temporal")),
    ));
    rows.push((
        "SSIL total".into(),
        Box::new(|r| ms(r, |l| l.starts_with("ssil/"))),
    ));
    rows.push(("frame total".into(), Box::new(|r| r.frame_ms)));
    print!("\n{:<22}", format!("{} SSIL ms", first.scene));
    for r in records {
        print!(" {:>20}", r.variant);
    }
    println!();
    for (name, value) in &rows {
        print!("{name:<22}");
        for r in records {
            print!(" {:>20.3}", value(r));
        }
        println!();
    }
}
