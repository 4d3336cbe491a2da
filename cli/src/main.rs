//! The `mpdem` command line: run, check and benchmark scenes, and verify
//! the engine against the paper's validation cases. One file per
//! subcommand; what they share is in `console.rs` and `failure.rs`.

mod bench;
mod check;
mod console;
mod failure;
mod mpi_job;
mod run;
mod signals;
mod verify;

use clap::{Parser, Subcommand};
use failure::Failure;
use mpdem::runner::RunError;
use std::process::ExitCode;

/// Material point method with DEM-enriched contact (2D: plane strain or
/// axisymmetric).
///
/// Exit status: 0 when the command did what it was asked; 1 on an error
/// (a refused scene, a failed run, an output that cannot be written; the
/// message says which); 2 on a command line it cannot read; 130 when a
/// run was stopped by Ctrl-C, SIGTERM or SIGHUP (its results up to the
/// stop are written). A closed standard output (`mpdem run ... | head`)
/// drops what is printed and changes no status.
#[derive(Parser)]
#[command(version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene and write its results (VTK, CSV, PNG).
    Run(run::RunArgs),
    /// Validate scenes without running them (each is checked; the status
    /// is 1 if any is refused).
    Check(check::CheckArgs),
    /// Measure particle-updates per second on the standard elastic block, without and with a rigid ground contact.
    Bench(bench::BenchArgs),
    /// Run the paper's validation cases at full size and measure each
    /// against its target (the table is also written to OUT/verify.csv;
    /// with --report, a Markdown report with figures too). Exits with
    /// failure if a target is missed. All cases take about an hour and a half on 2
    /// cores.
    Verify(verify::VerifyArgs),
}

impl Command {
    /// The subcommand's name on the command line.
    fn name(&self) -> &'static str {
        match self {
            Command::Run(_) => "run",
            Command::Check(_) => "check",
            Command::Bench(_) => "bench",
            Command::Verify(_) => "verify",
        }
    }
}

/// The exit status of a run stopped by a signal, as a shell reports a
/// command interrupted by Ctrl-C.
const STOPPED_STATUS: u8 = 130;

fn main() -> ExitCode {
    let command = Cli::parse().command;
    let job = mpi_job::job().filter(|&(_, size)| size > 1);
    if let Some((rank, size)) = job {
        if let Some(refusal) = mpi_job::refusal(command.name(), size) {
            // One message for the job, from its first rank.
            if rank == 0 {
                eprintln!("{refusal}");
            }
            return ExitCode::FAILURE;
        }
        // The job speaks through its first rank.
        if rank > 0 {
            console::silence();
        }
    }
    let result = match command {
        Command::Check(_) if job.is_some_and(|(rank, _)| rank > 0) => Ok(()),
        Command::Run(args) => run::run(args, job.is_some()),
        Command::Check(args) => check::check_all(&args.scenes),
        Command::Bench(args) => bench::bench(args),
        Command::Verify(args) => verify::verify(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(stopped @ Failure::Run(RunError::Stopped { .. } | RunError::CutShort { .. })) => {
            console::say_err(&stopped.to_string());
            ExitCode::from(STOPPED_STATUS)
        }
        Err(failure) => {
            console::say_err(&format!("error: {failure}"));
            ExitCode::FAILURE
        }
    }
}
