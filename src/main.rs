//! The `robocal` command line: each subcommand (defined in
//! `robocal::cli::command`) is a few lines over the library.

use std::process::ExitCode;

use clap::Parser;
use robocal::cli::command::{Cli, Command, TokenCommand};
use robocal::config::LogFormat;
use robocal::domain::Scope;

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
            target,
            dir,
        } => robocal::cli::campaign::SimBoard::parse(&target)
            .and_then(|board| {
                robocal::cli::campaign::simulate_board(&robot, &dir, cal, val, seed, board)
            })
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
            json,
            server,
        } => match server.client() {
            Ok(client) => robocal::cli::calibrate(&client, &serial, &session, wait)
                .await
                .map(|job| match json {
                    true => println!("{}", job.json()),
                    false => println!("{job}"),
                })
                .map_err(|e| e.to_string()),
            Err(e) => Err(e),
        },
        Command::Release(command) => robocal::cli::release::run(command).await,
        Command::Jobs {
            limit,
            filters,
            server,
        } => match server.client() {
            Ok(client) => robocal::cli::jobs(&client, limit, &filters)
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
