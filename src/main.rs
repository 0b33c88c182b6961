//! The `robocal` command line: each subcommand is a few lines over the library.

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use robocal::config::{LogFormat, ServeConfig};
use robocal::domain::Scope;

#[derive(Parser)]
#[command(name = "robocal", version, about = "Robot calibration service")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
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
        /// Output directory (campaign.json, poses.json, images/, truth.json).
        dir: std::path::PathBuf,
    },
    /// Create the robot (when it does not exist) and a session, and upload a
    /// campaign directory; prints the session id.
    Upload {
        /// Robot serial number.
        #[arg(long)]
        serial: String,
        /// Replace an existing robot's kinematics with the campaign's
        /// (without it an existing robot is left as it is).
        #[arg(long)]
        replace_robot: bool,
        /// Campaign directory (as written by `robocal simulate`).
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
        #[command(flatten)]
        server: ServerArgs,
    },
    /// List jobs, newest first.
    Jobs {
        /// How many jobs to show (1 to 1000).
        #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..=1000))]
        limit: u32,
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
        args: robocal::cli::evaluate::ForwardArgs,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Compensated joints: the joints that put the tool (default: the
    /// camera) on each target according to a calibrated parameter set.
    Compensate {
        #[command(flatten)]
        args: robocal::cli::evaluate::CompensateArgs,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Filtered targets for a controller that runs the nominal model: the
    /// flange poses to send so that the real robot puts the tool on each
    /// target of FILE (CSV in, CSV out; columns below).
    Filter {
        #[command(flatten)]
        args: robocal::cli::filter::FilterArgs,
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
        #[arg(long, value_parser = robocal::export::ExportFormat::NAMES)]
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
        args: robocal::cli::plan::PlanArgs,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Run the whole pipeline on a campaign directory without a server.
    CalibrateLocal {
        /// Campaign directory (as written by `robocal simulate`).
        dir: std::path::PathBuf,
        /// Also write the printable report here.
        #[arg(long)]
        html: Option<std::path::PathBuf>,
    },
}

#[derive(clap::Args)]
struct ServerArgs {
    /// The service's base URL.
    #[arg(long, env = "ROBOCAL_URL", default_value = "http://127.0.0.1:8080")]
    url: String,
    /// Bearer token, needed once the server has tokens.
    #[arg(long, env = "ROBOCAL_TOKEN")]
    token: Option<String>,
    /// PEM certificate(s) to trust for an `https://` URL, besides the public
    /// roots (a private CA, or a self-signed server certificate).
    #[arg(long, env = "ROBOCAL_CA_CERT")]
    ca_cert: Option<std::path::PathBuf>,
}

impl ServerArgs {
    fn client(&self) -> Result<robocal::cli::client::Client, String> {
        robocal::cli::client::Client::with_ca_cert(
            &self.url,
            self.token.clone(),
            self.ca_cert.as_deref(),
        )
        .map_err(|e| e.to_string())
    }
}

#[derive(clap::Args)]
struct DatabaseArg {
    /// The server's database (as `robocal serve --database-url`).
    #[arg(long, env = "DATABASE_URL", default_value = "sqlite://robocal.db")]
    database_url: String,
}

#[derive(Subcommand)]
enum TokenCommand {
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

fn init_logging(format: LogFormat) {
    let filter = tracing_subscriber::EnvFilter::try_from_default_env()
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info,sqlx=warn"));
    let ansi = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let builder = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_ansi(ansi)
        .with_writer(std::io::stderr);
    match format {
        LogFormat::Json => builder.json().init(),
        LogFormat::Text => builder.init(),
    }
}

#[tokio::main]
async fn main() -> ExitCode {
    let cli = Cli::parse();
    let result: Result<(), String> = match cli.command {
        Command::Serve(config) => {
            init_logging(config.log_format);
            robocal::server::run(config)
                .await
                .map_err(|e| e.to_string())
        }
        Command::Token(TokenCommand::Create {
            scope,
            name,
            expires_in,
            db,
        }) => {
            let scope = Scope::parse(&scope).unwrap_or(Scope::Read);
            robocal::api::tokens::create_from_cli(&db.database_url, &name, scope, expires_in).await
        }
        Command::Token(TokenCommand::List { db }) => {
            robocal::api::tokens::list_from_cli(&db.database_url).await
        }
        Command::Token(TokenCommand::Revoke { id, db }) => {
            robocal::api::tokens::revoke_from_cli(&db.database_url, &id).await
        }
        Command::Target { spec, out } => robocal::print::render_args(&spec)
            .and_then(|bytes| robocal::cli::write_output(out.as_deref(), &bytes)),
        Command::Openapi => {
            println!("{}", robocal::api::openapi_json());
            Ok(())
        }
        Command::Simulate {
            robot,
            cal,
            val,
            seed,
            dir,
        } => robocal::cli::campaign::simulate(&robot, &dir, cal, val, seed)
            .map(|_| eprintln!("campaign written to {}", dir.display())),
        Command::Upload {
            serial,
            replace_robot,
            dir,
            server,
        } => match server.client() {
            Ok(client) => robocal::cli::upload(
                &client,
                &serial,
                &dir,
                if replace_robot {
                    robocal::cli::RobotPolicy::Replace
                } else {
                    robocal::cli::RobotPolicy::CreateIfMissing
                },
            )
            .await
            .map(|id| println!("{id}"))
            .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Calibrate {
            serial,
            session,
            wait,
            server,
        } => match server.client() {
            Ok(client) => robocal::cli::calibrate(&client, &serial, &session, wait)
                .await
                .map(|job| println!("{job}"))
                .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Jobs { limit, server } => match server.client() {
            Ok(client) => robocal::cli::jobs(&client, limit)
                .await
                .map(|table| print!("{table}"))
                .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Report {
            serial,
            version,
            server,
        } => match server.client() {
            Ok(client) => client
                .report(&serial, version)
                .await
                .map(|r| print!("{}", robocal::report::render_table(&r)))
                .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Forward { args, server } => match server.client() {
            Ok(client) => robocal::cli::evaluate::forward(&client, &args)
                .await
                .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Compensate { args, server } => match server.client() {
            Ok(client) => robocal::cli::evaluate::compensate(&client, &args)
                .await
                .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Filter { args, server } => match server.client() {
            Ok(client) => robocal::cli::filter::filter(&client, &args)
                .await
                .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Export {
            serial,
            version,
            format,
            out,
            server,
        } => match server.client() {
            Ok(client) => client
                .export(&serial, version, &format)
                .await
                .map_err(|e| e.to_string())
                .and_then(|bytes| robocal::cli::write_output(out.as_deref(), &bytes)),
            Err(e) => Err(e),
        },
        Command::Plan { args, server } => match server.client() {
            Ok(client) => robocal::cli::plan::plan(&client, &args).await,
            Err(e) => Err(e),
        },
        Command::CalibrateLocal { dir, html } => {
            robocal::cli::campaign::calibrate_local(&dir, "local").and_then(|report| {
                print!("{}", robocal::report::render_table(&report));
                match html {
                    Some(path) => std::fs::write(&path, robocal::report::render_html(&report))
                        .map_err(|e| format!("{}: {e}", path.display())),
                    None => Ok(()),
                }
            })
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("robocal: {e}");
            ExitCode::FAILURE
        }
    }
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
}
