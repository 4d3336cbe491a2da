//! `mpdem verify`: run the validation cases, tabulate them and write the
//! report, with a progress bar per run.

use crate::console::{progress_bar, say, say_err, with_threads};
use crate::failure::Failure;
use mpdem_verify::report::write_report;
use mpdem_verify::{CASES, Case, CaseReport, Context, RunEvent, Tally};
use std::path::{Path, PathBuf};

/// The arguments of `mpdem verify`.
#[derive(clap::Args)]
pub struct VerifyArgs {
    /// Cases to run, by name [default: all]; see --list.
    cases: Vec<String>,
    /// List the cases with their cost and stop.
    #[arg(long)]
    list: bool,
    /// Folder of the scene files.
    #[arg(long, default_value = "scenes")]
    scenes: PathBuf,
    /// Output folder for verify.csv and the cases' plots.
    #[arg(long, default_value = "out/verify")]
    out: PathBuf,
    /// Worker threads [default: all cores]. Results do not depend on it.
    #[arg(long)]
    threads: Option<usize>,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// Also write DIR/verification.md, the cases' checks as a Markdown
    /// report, and a figure per case of its computed curves against
    /// their references in DIR/verification/ (e.g. --report docs/).
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
}

/// Lists the cases, or runs those asked for on the threads asked for.
pub fn verify(args: VerifyArgs) -> Result<(), Failure> {
    if args.list {
        return list_cases();
    }
    with_threads(args.threads, || run_cases(&args))
}

fn list_cases() -> Result<(), Failure> {
    let width = |f: fn(&Case) -> &str| CASES.iter().map(|c| f(c).chars().count()).max();
    let name = width(|c| c.name).unwrap_or(0);
    let source = width(|c| c.source).unwrap_or(0);
    for case in CASES {
        say(&format!(
            "{:<name$} {:<source$} ~{:>4.1} min  {}",
            case.name, case.source, case.minutes, case.about
        ))?;
    }
    Ok(())
}

/// The `mpdem verify` command line that reproduces a report: the cases
/// named, the scenes folder if not the default, and the report's folder.
fn verify_command(names: &[String], scenes: &Path, report: &Path) -> String {
    let mut command = vec!["mpdem verify".to_string()];
    command.extend(names.iter().cloned());
    if scenes != Path::new("scenes") {
        command.push(format!("--scenes {}", scenes.display()));
    }
    command.push(format!("--report {}", report.display()));
    command.join(" ")
}

fn run_cases(args: &VerifyArgs) -> Result<(), Failure> {
    let (names, scenes, out) = (&args.cases, &args.scenes, &args.out);
    let cases = if names.is_empty() {
        CASES.iter().collect()
    } else {
        names
            .iter()
            .map(|name| mpdem_verify::case(name).ok_or(Failure::UnknownCase { name: name.clone() }))
            .collect::<Result<Vec<_>, _>>()?
    };
    if !scenes.is_dir() {
        return Err(Failure::NoScenes(scenes.to_path_buf()));
    }
    let table = out.join("verify.csv");
    let progress = progress_bar(
        0,
        args.quiet,
        "{bar:40} step {pos}/{len} {msg} elapsed {elapsed} ETA {eta}",
    );
    let observe = |event: RunEvent| match event {
        RunEvent::Started { run, steps } => {
            // reset() also brings back a bar finished and cleared by the
            // previous case, and restarts its clock.
            progress.reset();
            progress.set_length(steps);
            progress.set_message(run.to_string());
        }
        RunEvent::Stepped { step } => progress.set_position(step),
    };
    let ctx = Context::new(scenes, out, &observe);
    let mut reports = Vec::new();
    for case in cases {
        let minutes = case.minutes;
        say_err(&format!(
            "{} ({}): {}, about {minutes} min",
            case.name, case.source, case.about
        ));
        let report = CaseReport::run(case, &ctx);
        progress.finish_and_clear();
        say(report.to_string().trim_end_matches('\n'))?;
        reports.push(report);
        mpdem_verify::write_table(&table, &reports).map_err(|source| Failure::VerifyTable {
            path: table.clone(),
            source,
        })?;
        if let Some(dir) = &args.report {
            write_report(dir, &verify_command(names, scenes, dir), &reports)?;
        }
    }
    if let Some(dir) = &args.report {
        say(&format!(
            "verify: report in {}",
            dir.join("verification.md").display()
        ))?;
    }
    let tally = Tally::of(&reports);
    say(&format!("verify: {tally}; table in {}", table.display()))?;
    if tally.passed() {
        Ok(())
    } else {
        Err(Failure::Verify(tally))
    }
}
