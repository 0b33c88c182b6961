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
    /// Manage bearer tokens.
    #[command(subcommand)]
    Token(TokenCommand),
    /// Print the OpenAPI document (JSON).
    Openapi,
    /// Simulate a campaign (robot with perturbed kinematics, flange camera,
    /// rendered images and the truth) into a directory.
    Simulate {
        #[arg(long, value_parser = ["irb2400", "puma560"], default_value = "irb2400")]
        robot: String,
        #[arg(long, default_value_t = 60)]
        cal: usize,
        #[arg(long, default_value_t = 30)]
        val: usize,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        dir: std::path::PathBuf,
    },
    /// Create the robot and a session, and upload a campaign directory.
    Upload {
        #[arg(long)]
        serial: String,
        dir: std::path::PathBuf,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Start a calibration job for a session.
    Calibrate {
        #[arg(long)]
        serial: String,
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
        #[arg(long)]
        serial: String,
        /// Version number (default: the latest).
        #[arg(long)]
        version: Option<i64>,
        #[command(flatten)]
        server: ServerArgs,
    },
    /// Run the whole pipeline on a campaign directory without a server.
    CalibrateLocal {
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
    /// Bearer token, when the server has tokens.
    #[arg(long, env = "ROBOCAL_TOKEN")]
    token: Option<String>,
}

impl ServerArgs {
    fn client(&self) -> Result<robocal::client::Client, String> {
        robocal::client::Client::new(&self.url, self.token.clone()).map_err(|e| e.to_string())
    }
}

#[derive(Subcommand)]
enum TokenCommand {
    /// Create a token, store its hash and print the token once.
    Create {
        #[arg(long, value_parser = ["read", "write", "admin"])]
        scope: String,
        #[arg(long, default_value = "cli")]
        name: String,
        #[arg(long, env = "DATABASE_URL", default_value = "sqlite://robocal.db")]
        database_url: String,
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
            database_url,
        }) => {
            let scope = Scope::parse(&scope).unwrap_or(Scope::Read);
            robocal::api::tokens::create_from_cli(&database_url, &name, scope).await
        }
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
        } => robocal::campaign::simulate(&robot, &dir, cal, val, seed)
            .map(|_| eprintln!("campaign written to {}", dir.display())),
        Command::Upload {
            serial,
            dir,
            server,
        } => match server.client() {
            Ok(client) => robocal::cli::upload(&client, &serial, &dir)
                .await
                .map(|id| println!("{id}"))
                .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Calibrate {
            serial: _,
            session,
            wait,
            server,
        } => match server.client() {
            Ok(client) => robocal::cli::calibrate(&client, &session, wait)
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
        Command::CalibrateLocal { dir, html } => robocal::campaign::calibrate_local(&dir, "local")
            .and_then(|report| {
                print!("{}", robocal::report::render_table(&report));
                match html {
                    Some(path) => std::fs::write(&path, robocal::report::render_html(&report))
                        .map_err(|e| format!("{}: {e}", path.display())),
                    None => Ok(()),
                }
            }),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("robocal: {e}");
            ExitCode::FAILURE
        }
    }
}
