//! `robocal filter FILE.csv`: a program's Cartesian targets filtered for a
//! controller that runs the robot's nominal model (`POST …/filter`), CSV in
//! and CSV out, so that a cell's point list goes through in one command.

use std::path::PathBuf;

use super::client::{answer_of, Client, ClientError};
use super::evaluate::{parse_row, read_input, SetArgs};
use super::evaluate_docs::{error_of, pose_doc, FilterAnswer, FilterBody, FilterLine, POSE_WIDTH};
use crate::report::format::fixed;
/// Column names of the input (a header line with letters is skipped).
pub const INPUT_COLUMNS: &str = "x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg";
/// Decimals of every number written (mm, deg): a nanometre and a
/// micro-degree, far below any controller's resolution, and no
/// `-0.000000000000031826` from round-off.
const OUTPUT_DECIMALS: usize = 6;

/// Column names of the output for a robot of `joints` axes: the filtered
/// flange pose in the base frame for the nominal controller, one column
/// per joint the robot will take, the replayed residual, and the reason
/// when a target has no solution.
pub fn output_columns(joints: usize) -> String {
    let joint_columns: Vec<String> = (1..=joints).map(|j| format!("j{j}_deg")).collect();
    format!(
        "index,x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,{},residual_mm,error",
        joint_columns.join(",")
    )
}

#[derive(Debug, Clone, clap::Args)]
pub struct FilterArgs {
    #[command(flatten)]
    pub set: SetArgs,
    /// Targets: the pose of the tool in the target (or tracker) frame, one
    /// per line, columns `x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg` (commas or
    /// spaces; fixed-axis X-Y-Z angles; a header line and `#` comment lines
    /// are skipped). `-` reads stdin. Output, one CSV line per target:
    /// `index,x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,j1_deg,..,jN_deg,residual_mm,error`
    /// where x..rz is the flange pose in the base frame to send to the
    /// nominal controller, j1..jN the joints the robot takes (one column
    /// each) and `error` why a target has none (then empty).
    pub file: PathBuf,
    /// The tool in the flange frame, `x,y,z,rx,ry,rz` (mm, deg).
    #[arg(long, value_name = "X,Y,Z,RX,RY,RZ", allow_hyphen_values = true)]
    pub tool: String,
    /// Joint angles (deg) whose configuration every solution keeps.
    #[arg(long, value_name = "J1,..,J6", allow_hyphen_values = true)]
    pub seed: Option<String>,
}

/// The `filter` request body of a CSV text and the flags.
pub fn filter_body(csv: &str, args: &FilterArgs) -> Result<FilterBody, String> {
    let mut targets = Vec::new();
    for (n, line) in csv.lines().enumerate() {
        let line = line.trim();
        let header = line.starts_with(|c: char| c.is_ascii_alphabetic());
        if line.is_empty() || line.starts_with('#') || (targets.is_empty() && header) {
            continue;
        }
        let what = format!("line {}", n + 1);
        targets.push(pose_doc(&parse_row(line, &what)?, &what)?);
    }
    if targets.is_empty() {
        return Err(format!(
            "no targets in the file: one {INPUT_COLUMNS} row per line"
        ));
    }
    Ok(FilterBody {
        targets,
        tool: pose_doc(&parse_row(&args.tool, "--tool")?, "--tool")?,
        seed_joints_deg: args
            .seed
            .as_deref()
            .map(|seed| parse_row(seed, "--seed"))
            .transpose()?,
    })
}

/// One target's CSV line ([`output_columns`] of `joints` axes, with its
/// newline): the filtered pose, joints and residual, or empty cells and
/// the error.
pub fn csv_line(line: &FilterLine, joints: usize) -> String {
    // The numbers given (a missing one leaves its cell empty).
    let numbers = |v: &[Option<f64>]| -> Vec<String> {
        v.iter()
            .map(|x| x.map_or(String::new(), |x| fixed(x, OUTPUT_DECIMALS)))
            .collect()
    };
    let mut cells = Vec::new();
    if let Some(pose) = &line.nominal_target {
        cells.extend(numbers(&pose.translation_mm));
        cells.extend(numbers(&pose.rotation_deg));
    }
    cells.resize(POSE_WIDTH, String::new());
    let mut joint_cells = line.joints_deg.as_deref().map(numbers).unwrap_or_default();
    joint_cells.resize(joints, String::new());
    cells.extend(joint_cells);
    let residual = line
        .residual_mm
        .map_or(String::new(), |r| fixed(r, OUTPUT_DECIMALS));
    let error = line
        .error
        .as_ref()
        .map_or(String::new(), |e| format!("\"{}\"", e.replace('"', "\"\"")));
    format!("{},{},{residual},{error}\n", line.index, cells.join(","))
}

/// The whole answer as CSV ([`output_columns`]), one line per target in order.
pub fn filter_csv(answer: &FilterAnswer, joints: usize) -> String {
    let mut out = format!("{}\n", output_columns(joints));
    for (index, pose) in answer.nominal_targets.iter().enumerate() {
        out.push_str(&csv_line(
            &FilterLine {
                index,
                nominal_target: pose.clone(),
                joints_deg: answer.joints_deg.get(index).cloned().flatten(),
                residual_mm: answer.residual_mm.get(index).copied().flatten(),
                error: error_of(&answer.errors, index),
            },
            joints,
        ));
    }
    out
}

/// The robot's joint count (the CSV's joint columns).
async fn joint_count(client: &Client, serial: &str) -> Result<usize, ClientError> {
    let robot: serde_json::Value = answer_of(
        &client
            .call(reqwest::Method::GET, &format!("/v1/robots/{serial}"), None)
            .await?,
    )?;
    Ok(robot["kinematics"]["joints"].as_array().map_or(0, Vec::len))
}

/// `--json` prints the server's whole answer; the CSV streams: each line is
/// printed as the server sends its target (`Accept: application/x-ndjson`).
pub async fn filter(client: &Client, args: &FilterArgs) -> Result<(), ClientError> {
    let csv = read_input(&args.file).map_err(ClientError::Local)?;
    let body = filter_body(&csv, args).map_err(ClientError::Local)?;
    if args.set.json {
        let answer = client
            .evaluate(&args.set.serial, args.set.version, "filter", &body)
            .await?;
        println!("{}", answer.trim_end());
        return Ok(());
    }
    let joints = joint_count(client, &args.set.serial).await?;
    println!("{}", output_columns(joints));
    client
        .evaluate_lines(
            &args.set.serial,
            args.set.version,
            "filter",
            &body,
            |line| {
                print!("{}", csv_line(&answer_of(line)?, joints));
                Ok(())
            },
        )
        .await
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args() -> FilterArgs {
        FilterArgs {
            set: SetArgs {
                serial: "R".into(),
                version: None,
                json: false,
            },
            file: "-".into(),
            tool: "0,0,100,0,0,0".into(),
            seed: Some("0,10,10,0,60,0".into()),
        }
    }

    #[test]
    fn a_csv_with_header_and_comments_becomes_the_request() {
        let csv = "x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg\n# first\n150,0,-790,3.5,3.7,1e-3\n\n10 20 30 0 0 0\n";
        let body = filter_body(csv, &args()).unwrap();
        assert_eq!(body.targets.len(), 2);
        assert_eq!(body.targets[0].rotation_deg, [3.5, 3.7, 0.001]);
        assert_eq!(body.targets[1].translation_mm, [10.0, 20.0, 30.0]);
        assert_eq!(body.tool.translation_mm, [0.0, 0.0, 100.0]);
        assert_eq!(body.seed_joints_deg.unwrap()[4], 60.0);
    }

    #[test]
    fn bad_lines_are_named() {
        let e = filter_body("1,2,3,4,5,6\n1,2,3\n", &args()).unwrap_err();
        assert!(e.contains("line 2") && e.contains("6 numbers"), "{e}");
        let e = filter_body("1,2,3,4,5,x6\n", &args()).unwrap_err();
        assert!(e.contains("line 1"), "{e}");
        assert!(filter_body("# nothing\n", &args())
            .unwrap_err()
            .contains("no targets"));
    }

    #[test]
    fn the_answer_is_one_csv_line_per_target_errors_included() {
        let answer: FilterAnswer = serde_json::from_str(
            r#"{
            "nominal_targets": [
                {"translation_mm": [1.0, 2.0, 3.0], "rotation_deg": [4.0, 5.0, 6.0]}, null],
            "joints_deg": [[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], null],
            "residual_mm": [-3.1826e-14, null],
            "errors": [{"index": 1, "message": "target out of reach"}]}"#,
        )
        .unwrap();
        let csv = filter_csv(&answer, 6);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines[0],
            "index,x_mm,y_mm,z_mm,rx_deg,ry_deg,rz_deg,j1_deg,j2_deg,j3_deg,j4_deg,j5_deg,j6_deg,residual_mm,error"
        );
        assert_eq!(
            lines[1],
            "0,1.000000,2.000000,3.000000,4.000000,5.000000,6.000000,\
             1.000000,2.000000,3.000000,4.000000,5.000000,6.000000,0.000000,"
        );
        assert_eq!(lines[2], "1,,,,,,,,,,,,,,\"target out of reach\"");
    }
}
