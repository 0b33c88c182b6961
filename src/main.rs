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
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("robocal: {e}");
            ExitCode::FAILURE
        }
    }
}
