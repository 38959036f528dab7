//! SSIL's frames laid out as the paper's Figure 9 table: a column a configuration (`bench
//! --techniques ssil --vary 'start = ["quarter", "half"]' --vary 'levels = [4, 5]' …`), a row
//! a stage — the voxel grid, each level's gather, upsampling and temporal filtering.

use super::FrameRecord;

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
pub fn print_table(records: &[&FrameRecord]) {
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
        print!(" {:>20}", r.variant.trim_start_matches("ssil "));
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
