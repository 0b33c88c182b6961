//! `robocal forward` and `robocal compensate`: the off-line programming
//! tool's two questions to a parameter set (`POST …/forward`,
//! `POST …/compensate`) from the command line. Rows come from flags or
//! from a file (the REST request body as JSON, or a plain table of
//! numbers, one row per line); the answer is printed as a table, or as the
//! server's JSON with `--json`.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use super::client::{answer_of, Client, ClientError};
use super::evaluate_docs::{
    error_of, pose_doc, CompensateAnswer, CompensateBody, CompensateLine, ForwardAnswer,
    ForwardBody, PoseNumbers, Seeds,
};

/// Which parameter set, and how to print the answer.
#[derive(Debug, Clone, clap::Args)]
pub struct SetArgs {
    /// Robot serial number.
    #[arg(long)]
    pub serial: String,
    /// Parameter-set version (default: the latest).
    #[arg(long)]
    pub version: Option<i64>,
    /// Print the server's JSON answer instead of a table.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, Clone, clap::Args)]
pub struct ForwardArgs {
    #[command(flatten)]
    pub set: SetArgs,
    /// One row of joint angles in degrees, comma-separated (repeat the flag
    /// for several rows), e.g. `--joints 0,10,10,0,60,0`.
    #[arg(long = "joints", value_name = "J1,..,J6", allow_hyphen_values = true)]
    pub joints: Vec<String>,
    /// Rows from a file (`-` reads stdin): the REST body
    /// `{"joints_deg": [[...]], "tool": ...}` as JSON, or a table with one
    /// row of joint angles (degrees) per line, separated by commas or spaces.
    #[arg(long)]
    pub file: Option<PathBuf>,
}

#[derive(Debug, Clone, clap::Args)]
pub struct CompensateArgs {
    #[command(flatten)]
    pub set: SetArgs,
    /// One target pose of the tool (default: the camera) in the target
    /// frame, `x,y,z,rx,ry,rz` in mm and degrees (repeat for several).
    #[arg(
        long = "target",
        value_name = "X,Y,Z,RX,RY,RZ",
        allow_hyphen_values = true
    )]
    pub targets: Vec<String>,
    /// Joint angles (degrees) near the wanted solution, one seed for all
    /// targets, comma-separated.
    #[arg(long, value_name = "J1,..,J6", allow_hyphen_values = true)]
    pub seed: Option<String>,
    /// Targets from a file (`-` reads stdin): the REST body
    /// `{"targets": [...], "seed_joints_deg": ..., "tool": ...}` as JSON, or
    /// a table with one `x y z rx ry rz` row (mm, degrees) per line.
    #[arg(long)]
    pub file: Option<PathBuf>,
}

/// Numbers of one row: commas and/or whitespace between them.
pub(super) fn parse_row(text: &str, what: &str) -> Result<Vec<f64>, String> {
    let row: Vec<f64> = text
        .split(|c: char| c == ',' || c.is_whitespace())
        .filter(|t| !t.is_empty())
        .map(|t| {
            t.parse::<f64>()
                .map_err(|_| format!("{what} {text:?}: {t:?} is not a number"))
        })
        .collect::<Result<_, _>>()?;
    if row.is_empty() {
        return Err(format!("{what} {text:?} has no numbers"));
    }
    Ok(row)
}

pub(super) fn read_input(path: &Path) -> Result<String, String> {
    if path == Path::new("-") {
        std::io::read_to_string(std::io::stdin()).map_err(|e| format!("stdin: {e}"))
    } else {
        std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))
    }
}

/// A file's content: a JSON object is the request body itself; otherwise a
/// table, one row per non-empty line (`#` starts a comment line).
enum FileInput<B> {
    Body(B),
    Rows(Vec<Vec<f64>>),
}

fn parse_file<B: DeserializeOwned>(text: &str, what: &str) -> Result<FileInput<B>, String> {
    if text.trim_start().starts_with('{') {
        return serde_json::from_str(text)
            .map(FileInput::Body)
            .map_err(|e| format!("the file is not a valid request body: {e}"));
    }
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| parse_row(l, what))
        .collect::<Result<_, _>>()
        .map(FileInput::Rows)
}

/// The `forward` request body of the flags and file.
pub fn forward_body(args: &ForwardArgs) -> Result<ForwardBody, String> {
    let mut rows: Vec<Vec<f64>> = args
        .joints
        .iter()
        .map(|j| parse_row(j, "--joints"))
        .collect::<Result<_, _>>()?;
    let mut body = ForwardBody::default();
    if let Some(path) = &args.file {
        match parse_file(&read_input(path)?, "joints row")? {
            FileInput::Body(b) => body = b,
            FileInput::Rows(r) => rows.extend(r),
        }
    }
    body.joints_deg.extend(rows);
    if body.joints_deg.is_empty() {
        return Err("no joints: give --joints J1,..,J6 or --file".into());
    }
    Ok(body)
}

/// The `compensate` request body of the flags and file.
pub fn compensate_body(args: &CompensateArgs) -> Result<CompensateBody, String> {
    let target = |r: &[f64]| pose_doc(r, "a target");
    let mut targets = args
        .targets
        .iter()
        .map(|t| parse_row(t, "--target").and_then(|r| target(&r)))
        .collect::<Result<Vec<_>, _>>()?;
    let mut body = CompensateBody::default();
    if let Some(path) = &args.file {
        match parse_file(&read_input(path)?, "target row")? {
            FileInput::Body(b) => body = b,
            FileInput::Rows(rows) => {
                for r in rows {
                    targets.push(target(&r)?);
                }
            }
        }
    }
    body.targets.extend(targets);
    if body.targets.is_empty() {
        return Err("no targets: give --target X,Y,Z,RX,RY,RZ or --file".into());
    }
    if let Some(seed) = &args.seed {
        body.seed_joints_deg = Some(Seeds::One(parse_row(seed, "--seed")?));
    }
    Ok(body)
}

/// Numbers to `decimals` places, space-separated; `?` for a missing one.
fn numbers(values: &[Option<f64>], decimals: usize) -> String {
    values
        .iter()
        .map(|x| x.map_or("?".into(), |x| format!("{x:.decimals$}")))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `forward` as a table: per row the camera (and tool) pose in the target
/// frame, millimetres and degrees.
pub fn forward_table(answer: &ForwardAnswer) -> String {
    let mut out = String::from("row  frame   x y z (mm)                     rx ry rz (deg)\n");
    for (i, pose) in answer.poses.iter().enumerate() {
        let frames: [(&str, &Option<PoseNumbers>); 2] = [
            ("camera", &pose.camera_in_target),
            ("tool", &pose.tool_in_target),
        ];
        for (frame, p) in frames {
            if let Some(p) = p {
                out.push_str(&format!(
                    "{:<4} {frame:<7} {:<30} {}\n",
                    i + 1,
                    numbers(&p.translation_mm, 3),
                    numbers(&p.rotation_deg, 4)
                ));
            }
        }
        if !pose.warnings.is_empty() {
            out.push_str(&format!("     warning: {}\n", pose.warnings.join("; ")));
        }
    }
    out
}

/// The header of the `compensate` table.
const COMPENSATE_HEADER: &str =
    "target  joints (deg)                                  residual (mm)\n";

/// One target's row of the `compensate` table (numbered from 1).
pub fn compensate_row(line: &CompensateLine) -> String {
    let residual = line.residual_mm.map_or("?".into(), |r| format!("{r:.4}"));
    let cells = match (&line.joints_deg, &line.error) {
        (Some(joints), _) => format!("{:<45} {residual}", numbers(joints, 4)),
        (None, Some(e)) => format!("no joints: {e}"),
        (None, None) => "no joints".into(),
    };
    format!("{:<7} {cells}\n", line.index + 1)
}

/// `compensate` as a table: per target the joints and the model's residual.
pub fn compensate_table(answer: &CompensateAnswer) -> String {
    let mut out = String::from(COMPENSATE_HEADER);
    for (index, joints) in answer.joints_deg.iter().enumerate() {
        out.push_str(&compensate_row(&CompensateLine {
            index,
            joints_deg: joints.clone(),
            residual_mm: answer.residual_mm.get(index).copied().flatten(),
            error: error_of(&answer.errors, index),
        }));
    }
    out
}

/// The server's answer as it wrote it (`--json`), or its table.
fn print_answer<T: DeserializeOwned>(
    set: &SetArgs,
    answer: &str,
    table: fn(&T) -> String,
) -> Result<(), ClientError> {
    if set.json {
        println!("{}", answer.trim_end());
    } else {
        print!("{}", table(&answer_of(answer)?));
    }
    Ok(())
}

pub async fn forward(client: &Client, args: &ForwardArgs) -> Result<(), ClientError> {
    let body = forward_body(args).map_err(ClientError::Local)?;
    let answer = client
        .evaluate(&args.set.serial, args.set.version, "forward", &body)
        .await?;
    print_answer(&args.set, &answer, forward_table)
}

/// `--json` prints the server's whole answer; the table streams: each row is
/// printed as the server sends its target (`Accept: application/x-ndjson`).
pub async fn compensate(client: &Client, args: &CompensateArgs) -> Result<(), ClientError> {
    let body = compensate_body(args).map_err(ClientError::Local)?;
    let (serial, version) = (&args.set.serial, args.set.version);
    if args.set.json {
        let answer = client
            .evaluate(serial, version, "compensate", &body)
            .await?;
        return print_answer(&args.set, &answer, compensate_table);
    }
    print!("{COMPENSATE_HEADER}");
    client
        .evaluate_lines(serial, version, "compensate", &body, |line| {
            print!("{}", compensate_row(&answer_of(line)?));
            Ok(())
        })
        .await
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set() -> SetArgs {
        SetArgs {
            serial: "R".into(),
            version: None,
            json: false,
        }
    }

    #[test]
    fn forward_rows_come_from_flags_and_a_table_file() {
        let mut file = tempfile::NamedTempFile::new().unwrap();
        std::io::Write::write_all(&mut file, b"# j1..j6\n1 2 3 4 5 6\n\n-1,-2,-3,-4,-5,-6\n")
            .unwrap();
        let args = ForwardArgs {
            set: set(),
            joints: vec!["0,10,10,0,60,0".into()],
            file: Some(file.path().to_path_buf()),
        };
        assert_eq!(
            forward_body(&args).unwrap(),
            ForwardBody {
                joints_deg: vec![
                    vec![0.0, 10.0, 10.0, 0.0, 60.0, 0.0],
                    vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0],
                    vec![-1.0, -2.0, -3.0, -4.0, -5.0, -6.0],
                ],
                tool: None,
            }
        );
    }

    #[test]
    fn a_json_file_is_the_request_body() {
        let mut file = tempfile::NamedTempFile::new().unwrap();
        let body = r#"{"targets": [{"translation_mm": [1, 2, 3], "rotation_deg": [0, 0, 0]}],
                       "tool": {"translation_mm": [0, 0, 100], "rotation_deg": [0, 0, 0]}}"#;
        std::io::Write::write_all(&mut file, body.as_bytes()).unwrap();
        let args = CompensateArgs {
            set: set(),
            targets: vec![],
            seed: Some("0,10,10,0,60,0".into()),
            file: Some(file.path().to_path_buf()),
        };
        let out = compensate_body(&args).unwrap();
        assert_eq!(
            out.tool,
            Some(pose_doc(&[0.0, 0.0, 100.0, 0.0, 0.0, 0.0], "tool").unwrap())
        );
        assert_eq!(
            out.targets,
            [pose_doc(&[1.0, 2.0, 3.0, 0.0, 0.0, 0.0], "target").unwrap()]
        );
        assert_eq!(
            out.seed_joints_deg,
            Some(Seeds::One(vec![0.0, 10.0, 10.0, 0.0, 60.0, 0.0]))
        );
    }

    #[test]
    fn bad_rows_name_the_flag_and_the_token() {
        let args = CompensateArgs {
            set: set(),
            targets: vec!["150,0,-790,3.5,3.7".into()],
            seed: None,
            file: None,
        };
        assert!(compensate_body(&args).unwrap_err().contains("6 numbers"));
        let args = ForwardArgs {
            set: set(),
            joints: vec!["0,ten".into()],
            file: None,
        };
        let e = forward_body(&args).unwrap_err();
        assert!(e.contains("--joints") && e.contains("\"ten\""), "{e}");
        let empty = ForwardArgs {
            set: set(),
            joints: vec![],
            file: None,
        };
        assert!(forward_body(&empty).unwrap_err().contains("no joints"));
    }

    #[test]
    fn tables_show_every_row() {
        let forward: ForwardAnswer = serde_json::from_str(
            r#"{"poses": [
            {"camera_in_target": {"translation_mm": [1.0, 2.0, 3.0], "rotation_deg": [4.0, 5.0, 6.0]},
             "warnings": ["joint 2 outside its limits"]},
            {"camera_in_target": {"translation_mm": [7.0, 8.0, 9.0], "rotation_deg": [0.0, 0.0, 0.0]},
             "tool_in_target": {"translation_mm": [1.5, 0.0, 0.0], "rotation_deg": [0.0, 0.0, 0.0]}}]}"#,
        )
        .unwrap();
        let t = forward_table(&forward);
        assert!(
            t.contains("1.000 2.000 3.000") && t.contains("7.000 8.000 9.000"),
            "{t}"
        );
        assert!(t.contains("tool") && t.contains("warning: joint 2"), "{t}");
        let comp: CompensateAnswer = serde_json::from_str(
            r#"{"joints_deg": [[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], null], "residual_mm": [0.00012, null],
                "errors": [{"index": 1, "message": "target out of reach"}]}"#,
        )
        .unwrap();
        let t = compensate_table(&comp);
        assert!(t.contains("1.0000 2.0000") && t.contains("0.0001"), "{t}");
        assert!(t.contains("2       no joints: target out of reach"), "{t}");
    }
}
