//! The `robocal` command line's grammar: every subcommand with its
//! arguments and their help texts. `main.rs` parses it and calls the
//! library for each subcommand.

use clap::{Parser, Subcommand};

use super::client::Client;
use crate::config::ServeConfig;

#[derive(Parser)]
#[command(name = "robocal", version, about = "Robot calibration service")]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Run the HTTP service and its job workers.
    Serve(ServeConfig),
    /// Manage bearer tokens (directly in the server's database).
    #[command(subcommand, visible_alias = "tokens")]
    Token(TokenCommand),
    /// Print the OpenAPI document (JSON).
    Openapi,
    /// Write a printable target page (1:1, scale bar, spec in the margin),
    /// e.g. `robocal target rows=9 cols=9 pitch_mm=25 dot_diameter_mm=8
    /// origin_marker_diameter_mm=12 format=pdf --out board.pdf`. The keys are
    /// those of `GET /v1/targets/render`.
    Target {
        /// The target's fields as KEY=VALUE (kind, rows, cols, ..., format).
        #[arg(required = true)]
        spec: Vec<String>,
        /// Output file (standard output when absent).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
    },
    /// Simulate a campaign (robot with perturbed kinematics, flange camera,
    /// rendered images and the truth) into a directory.
    Simulate {
        /// Robot preset: the IRB-2400 with a 1280x1024 camera, or the
        /// PUMA-560 with the paper's 752x582 camera.
        #[arg(long, value_parser = ["irb2400", "puma560"], default_value = "irb2400")]
        robot: String,
        /// Calibration poses (images used for the fit).
        #[arg(long, default_value_t = 60)]
        cal: usize,
        /// Validation poses (images held out to measure the accuracy).
        #[arg(long, default_value_t = 30)]
        val: usize,
        /// Random seed of the perturbations, poses and image noise.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// The board the images show: the 9x9 dot grid, an 8x7-corner
        /// chessboard or a 10x8-square ChArUco board (DICT_5X5_100), all
        /// on a 25 mm pitch; campaign.json describes it.
        #[arg(long, value_parser = super::sim_board::SimBoard::NAMES, default_value = "dots")]
        target: String,
        /// Output directory (campaign.json, poses.json, images/, truth.json).
        dir: std::path::PathBuf,
    },
    /// Create the robot (when it does not exist) and a session, and upload a
    /// campaign directory (or a zip of one); prints the session id. Its
    /// poses.json gives each image's joints_deg or, for a hand–eye
    /// campaign, the controller's flange_pose.
    Upload {
        /// Robot serial number.
        #[arg(long)]
        serial: String,
        /// Replace an existing robot's kinematics with the campaign's
        /// (without it an existing robot is left as it is).
        #[arg(long)]
        replace_robot: bool,
        /// Campaign directory (as written by `robocal simulate`: campaign.json,
        /// poses.json, images), or a zip holding those files.
        dir: std::path::PathBuf,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Start a calibration job for a session; prints the job (id, or its
    /// final state with --wait).
    Calibrate {
        /// Robot serial number: the session must belong to this robot.
        #[arg(long)]
        serial: String,
        /// Session id (printed by `robocal upload`).
        #[arg(long)]
        session: String,
        /// Show progress until the job ends.
        #[arg(long)]
        wait: bool,
        /// Print the finished job's whole JSON document (`GET
        /// /v1/jobs/{id}`) instead of the summary.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// List jobs, newest first: id, kind, state, robot, session, and why
    /// a job failed.
    Jobs {
        /// How many jobs to show (1 to 1000).
        #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..=1000))]
        limit: u32,
        #[command(flatten)]
        filters: super::JobFilters,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Print a parameter set's accuracy report as a table.
    Report {
        /// Robot serial number.
        #[arg(long)]
        serial: String,
        /// Version number (default: the latest).
        #[arg(long)]
        version: Option<i64>,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Forward kinematics of a calibrated parameter set: the camera (or
    /// tool) pose at given joints.
    Forward {
        #[command(flatten)]
        args: super::evaluate::ForwardArgs,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Compensated joints: the joints that put the tool (default: the
    /// camera) on each target according to a calibrated parameter set.
    Compensate {
        #[command(flatten)]
        args: super::evaluate::CompensateArgs,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Filtered targets for a controller that runs the nominal model: the
    /// flange poses to send so that the real robot puts the tool on each
    /// target of FILE (CSV in, CSV out; columns below).
    Filter {
        #[command(flatten)]
        args: super::filter::FilterArgs,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// A parameter set for the controller or the off-line programming tool:
    /// URDF, the identified table as JSON (`dh-json`) or CSV.
    Export {
        /// Robot serial number.
        #[arg(long)]
        serial: String,
        /// Parameter-set version (default: the latest).
        #[arg(long)]
        version: Option<i64>,
        /// `urdf`, `dh-json` or `csv`.
        #[arg(long, value_parser = crate::export::ExportFormat::NAMES)]
        format: String,
        /// Output file (standard output when absent).
        #[arg(long)]
        out: Option<std::path::PathBuf>,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Plan a campaign (which poses to shoot, the predicted accuracy) and
    /// write it as a URScript / RAPID / KRL program, CSV or JSON.
    Plan {
        #[command(flatten)]
        args: super::plan::PlanArgs,
        #[command(flatten)]
        server: ServerArgs,
    },
    #[command(flatten)]
    Release(ReleaseCommand),
    /// Run the whole pipeline on a campaign directory without a server.
    CalibrateLocal {
        /// Campaign directory (as written by `robocal simulate`: campaign.json,
        /// poses.json with joints or flange poses, images).
        dir: std::path::PathBuf,
        /// Also write the printable report here.
        #[arg(long)]
        html: Option<std::path::PathBuf>,
    },
}

#[derive(clap::Args)]
pub struct ServerArgs {
    /// The service's base URL.
    #[arg(long, env = "ROBOCAL_URL", default_value = "http://127.0.0.1:8080")]
    pub url: String,
    /// Bearer token, needed once the server has tokens.
    #[arg(long, env = "ROBOCAL_TOKEN")]
    pub token: Option<String>,
    /// PEM certificate(s) to trust for an `https://` URL, besides the public
    /// roots (a private CA, or a self-signed server certificate).
    #[arg(long, env = "ROBOCAL_CA_CERT")]
    pub ca_cert: Option<std::path::PathBuf>,
}

impl ServerArgs {
    /// The HTTP client for these arguments.
    pub fn client(&self) -> Result<Client, String> {
        Client::with_ca_cert(&self.url, self.token.clone(), self.ca_cert.as_deref())
            .map_err(|e| e.to_string())
    }
}

#[derive(clap::Args)]
pub struct DatabaseArg {
    /// The server's database (as `robocal serve --database-url`).
    #[arg(long, env = "DATABASE_URL", default_value = "sqlite://robocal.db")]
    pub database_url: String,
}

#[derive(Subcommand)]
pub enum TokenCommand {
    /// Create a token, store its hash and print the token once.
    Create {
        /// `read` (GET, report links), `write` (also uploads, jobs) or `admin` (also tokens).
        #[arg(long, value_parser = ["read", "write", "admin"])]
        scope: String,
        /// Who or what uses the token (shown by `tokens list`).
        #[arg(long, default_value = "cli")]
        name: String,
        /// The token stops working after this long, e.g. `30d`, `12h` (default: never).
        #[arg(long, value_parser = humantime::parse_duration)]
        expires_in: Option<std::time::Duration>,
        #[command(flatten)]
        db: DatabaseArg,
    },
    /// List tokens: id, name, scope, state, expiry and last use (never secrets).
    List {
        #[command(flatten)]
        db: DatabaseArg,
    },
    /// Revoke a token by id: it is refused from now on.
    Revoke {
        /// The token's id (from `tokens list`).
        id: String,
        #[command(flatten)]
        db: DatabaseArg,
    },
}

/// The release workflow's commands (run by `super::release`).
#[derive(Subcommand)]
pub enum ReleaseCommand {
    /// Approve a parameter set (it becomes `latest` when it is the newest
    /// approved one), recorded with who and why.
    Approve(Decision),
    /// Reject a parameter set (never served as `latest`), recorded with who and why.
    Reject(Decision),
    /// Quick re-check of a session (5 to 10 poses) against the robot's
    /// latest approved set; prints the job id, or with --wait its verdict
    /// (pass, drift, base_moved).
    Recheck {
        /// The session to judge (its robot's latest approved set is the reference).
        #[arg(long)]
        session: String,
        /// Wait for the verdict.
        #[arg(long)]
        wait: bool,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// List the robots: serial, model, preset, last change.
    Robots {
        #[command(flatten)]
        server: ServerArgs,
    },
    /// List a robot's measurement sessions: id, instrument, poses, creation.
    Sessions {
        /// Robot serial number.
        #[arg(long)]
        serial: String,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Delete a robot with its sessions, parameter sets and jobs.
    DeleteRobot {
        /// Robot serial number.
        #[arg(long)]
        serial: String,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Webhook subscriptions: list, create (prints the signing secret once), delete.
    #[command(subcommand)]
    Webhooks(WebhookCommand),
}

#[derive(clap::Args)]
pub struct Decision {
    /// Robot serial number.
    #[arg(long)]
    pub serial: String,
    /// The version decided on (a number: a decision names one set).
    #[arg(long)]
    pub version: i64,
    /// Why (recorded with the decision and shown in every report).
    #[arg(long)]
    pub reason: Option<String>,
    #[command(flatten)]
    pub server: ServerArgs,
}

#[derive(Subcommand)]
pub enum WebhookCommand {
    /// Every subscription: id, URL, events.
    List {
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Subscribe HOOK_URL to events (repeat --event: job.finished,
    /// check.finished, set.approved); prints the id and the signing secret.
    Create {
        /// Where deliveries are POSTed (http or https).
        #[arg(value_name = "HOOK_URL")]
        hook_url: String,
        /// An event to deliver (repeat for several).
        #[arg(long = "event", required = true)]
        events: Vec<String>,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Remove a subscription.
    Delete {
        /// The subscription's id (from `webhooks list`).
        id: String,
        #[command(flatten)]
        server: ServerArgs,
    },
}

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    /// Every argument of every command says what it is (`--help`).
    #[test]
    fn every_argument_has_help_text() {
        fn check(command: &clap::Command, path: &str) {
            for arg in command.get_arguments() {
                let id = arg.get_id().as_str();
                if matches!(id, "help" | "version") {
                    continue;
                }
                assert!(arg.get_help().is_some(), "{path} {id}: no help text");
            }
            for sub in command.get_subcommands() {
                check(sub, &format!("{path} {}", sub.get_name()));
            }
        }
        check(&super::Cli::command(), "robocal");
    }

    /// Clap's own consistency checks (unique names, valid defaults) over
    /// every subcommand: a clash would only show when that command runs.
    #[test]
    fn the_grammar_is_consistent() {
        super::Cli::command().debug_assert();
    }
}
