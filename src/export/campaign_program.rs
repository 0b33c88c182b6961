//! A campaign plan as a program a cell runs (issue 16): it moves through
//! the planned poses in order and pauses at each a fixed time ([`EDIT_NOTE`]:
//! the cell replaces the pause with its capture handshake). URScript
//! `movej` (radians), ABB RAPID `MoveAbsJ` to a `jointtarget` (degrees),
//! KUKA KRL `PTP` to an `AXIS` (degrees), and the CSV a cell script reads.
//! The joints are the session's joints (`joints_deg` as the controller
//! reports them), so a campaign shot by these programs uploads unchanged.

use crate::schema::campaign_plan::CampaignPlanOut;

/// The KRL program's name (its `.src` file must carry it).
pub const KRL_PROGRAM: &str = "robocal_campaign";
/// Seconds the program waits at each pose for the image to be taken.
pub const IMAGE_WAIT_S: f64 = 1.0;
/// Decimals written: 1e-6 deg and 1e-8 rad round-trip far below any
/// encoder's resolution.
const DEG_DECIMALS: usize = 6;
const RAD_DECIMALS: usize = 8;
/// Axes of a RAPID `robax` and a KRL `AXIS`.
const CONTROLLER_AXES: usize = 6;
/// URScript joint speed (rad/s) and acceleration (rad/s^2): slow, a
/// calibration campaign is not a race.
const UR_SPEED_RAD_S: f64 = 0.5;
const UR_ACCEL_RAD_S2: f64 = 1.0;

/// The program formats of `GET …/campaign-plans/{id}?format=`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramFormat {
    Json,
    Csv,
    Urscript,
    Rapid,
    Krl,
}

impl ProgramFormat {
    pub const NAMES: [&'static str; 5] = ["json", "csv", "urscript", "rapid", "krl"];

    pub fn parse(name: &str) -> Option<Self> {
        match name {
            "json" => Some(Self::Json),
            "csv" => Some(Self::Csv),
            "urscript" => Some(Self::Urscript),
            "rapid" => Some(Self::Rapid),
            "krl" => Some(Self::Krl),
            _ => None,
        }
    }

    pub fn content_type(self) -> &'static str {
        match self {
            Self::Json => "application/json",
            Self::Csv => "text/csv",
            _ => "text/plain; charset=utf-8",
        }
    }

    pub fn extension(self) -> &'static str {
        match self {
            Self::Json => "json",
            Self::Csv => "csv",
            Self::Urscript => "script",
            Self::Rapid => "mod",
            Self::Krl => "src",
        }
    }

    /// Joints a program of this format can carry at most.
    pub fn max_joints(self) -> Option<usize> {
        match self {
            Self::Rapid | Self::Krl => Some(CONTROLLER_AXES),
            _ => None,
        }
    }
}

/// What a cell must edit before running a program: the pause at each pose
/// is a fixed time, not a handshake with the camera.
pub const EDIT_NOTE: &str = "EDIT BEFORE RUNNING: at each pose this program only pauses a fixed time; \
     replace each pause with your cell's capture handshake (trigger the camera, wait for its done signal, \
     record the joints) or lengthen it to cover your capture";

fn header(plan: &CampaignPlanOut) -> String {
    format!(
        "robocal campaign plan {} for {}: {} poses, predicted validation error {:.4} mm",
        plan.id,
        plan.serial,
        plan.poses.len(),
        plan.predicted.validation_error_mean_mm
    )
}

fn list(values: impl Iterator<Item = String>) -> String {
    values.collect::<Vec<_>>().join(",")
}

/// `pose,set,j1_deg,...`: one row per pose in path order.
pub fn write_csv(plan: &CampaignPlanOut) -> String {
    let n = plan.poses.first().map_or(0, |p| p.joints_deg.len());
    let mut out = format!("pose,set,{}\n", list((1..=n).map(|j| format!("j{j}_deg"))));
    for (i, p) in plan.poses.iter().enumerate() {
        out += &format!(
            "{},{},{}\n",
            i + 1,
            p.set.as_str(),
            list(p.joints_deg.iter().map(|q| format!("{q:.DEG_DECIMALS$}")))
        );
    }
    out
}

/// A URScript program: `movej` in radians, then `sleep` for the image.
pub fn write_urscript(plan: &CampaignPlanOut) -> String {
    let mut out = format!(
        "def robocal_campaign():\n  # {}\n  # {}\n",
        header(plan),
        EDIT_NOTE
    );
    for (i, p) in plan.poses.iter().enumerate() {
        let q = list(
            p.joints_deg
                .iter()
                .map(|d| format!("{:.RAD_DECIMALS$}", d.to_radians())),
        );
        out += &format!(
            "  # pose {} ({})\n  movej([{q}], a={UR_ACCEL_RAD_S2}, v={UR_SPEED_RAD_S})\n  sleep({IMAGE_WAIT_S:.1})\n",
            i + 1,
            p.set.as_str()
        );
    }
    out + "end\nrobocal_campaign()\n"
}

/// Six axis values in degrees, missing axes 0.
fn axes(joints_deg: &[f64]) -> Vec<String> {
    (0..CONTROLLER_AXES)
        .map(|k| {
            format!(
                "{:.DEG_DECIMALS$}",
                joints_deg.get(k).copied().unwrap_or(0.0)
            )
        })
        .collect()
}

/// An ABB RAPID module: a `jointtarget` per pose, `MoveAbsJ` and `WaitTime`.
pub fn write_rapid(plan: &CampaignPlanOut) -> String {
    let mut out = format!(
        "MODULE RobocalCampaign\n  ! {}\n  ! {}\n",
        header(plan),
        EDIT_NOTE
    );
    for (i, p) in plan.poses.iter().enumerate() {
        out += &format!(
            "  CONST jointtarget pose{} := [[{}],[9E9,9E9,9E9,9E9,9E9,9E9]];\n",
            i + 1,
            axes(&p.joints_deg).join(",")
        );
    }
    out += "  PROC main()\n";
    for (i, p) in plan.poses.iter().enumerate() {
        out += &format!(
            "    ! pose {} ({})\n    MoveAbsJ pose{}\\NoEOffs, v100, fine, tool0;\n    WaitTime {IMAGE_WAIT_S:.1};\n",
            i + 1,
            p.set.as_str(),
            i + 1
        );
    }
    out + "  ENDPROC\nENDMODULE\n"
}

/// A KUKA KRL program: `PTP` to an `AXIS` aggregate, `WAIT SEC`.
pub fn write_krl(plan: &CampaignPlanOut) -> String {
    let mut out = format!(
        "DEF {KRL_PROGRAM}()\n  ; {}\n  ; {}\n",
        header(plan),
        EDIT_NOTE
    );
    for (i, p) in plan.poses.iter().enumerate() {
        let a = axes(&p.joints_deg)
            .iter()
            .enumerate()
            .map(|(k, v)| format!("A{} {v}", k + 1))
            .collect::<Vec<_>>()
            .join(", ");
        out += &format!(
            "  ; pose {} ({})\n  PTP {{AXIS: {a}}}\n  WAIT SEC {IMAGE_WAIT_S:.1}\n",
            i + 1,
            p.set.as_str()
        );
    }
    out + "END\n"
}
