//! Renders the sample report (or a report JSON given as the first
//! argument) to /tmp/report.svg, /tmp/report.html and the terminal table,
//! for looking at the renderings: `cargo run --example render_report`.
//! The output directory can be changed with `REPORT_OUT_DIR`; with
//! `REPORT_JSON` set the report JSON is written to /tmp/report.json too.
//! `--tracker` renders the laser-tracker variant (no camera); `--poses N`
//! the sample with N poses (half of them validation poses), to check the
//! charts stay readable from a handful of poses to hundreds; `--regions`
//! the sample as a multi-session set's, with three regions; `--stage` as
//! a stage set's, with three sequences (Fig. 5).

use robocal::report::{render_html, render_svg, render_table, sample, Report};
use std::error::Error;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn Error>> {
    let report: Report = match std::env::args().nth(1) {
        Some(path) if path == "--tracker" => sample::sample_tracker_report(),
        Some(flag) if flag == "--regions" => {
            robocal::report::sample_regions::sample_regions_report()
        }
        Some(flag) if flag == "--stage" => robocal::report::sample_stage::sample_stage_report(),
        Some(flag) if flag == "--poses" => {
            let n: usize = std::env::args()
                .nth(2)
                .ok_or("--poses needs a count")?
                .parse()?;
            sample::sample_report_sized(n - n / 2, n / 2)
        }
        Some(path) => serde_json::from_str(&std::fs::read_to_string(path)?)?,
        None => sample::sample_report(),
    };
    if std::env::var_os("REPORT_JSON").is_some() {
        std::fs::write("/tmp/report.json", serde_json::to_string_pretty(&report)?)?;
    }
    let dir = PathBuf::from(std::env::var("REPORT_OUT_DIR").unwrap_or_else(|_| "/tmp".into()));
    std::fs::write(dir.join("report.svg"), render_svg(&report))?;
    std::fs::write(dir.join("report.html"), render_html(&report))?;
    print!("{}", render_table(&report));
    println!("wrote {0}/report.svg and {0}/report.html", dir.display());
    Ok(())
}
