//! The verdict of a FANUC → Sinumerik proof made of several runs (the main program's, each
//! called macro's alone: `nctrans::translate::called`), printed for `nctrans --to sinumerik`.

use nctrans::diag;
use nctrans::span::SourceDb;
use std::process::ExitCode;

/// Prints the combined verdict of the main run and each macro's runs alone: the first one
/// not equivalent as `cli::translate::job::verdict` does, named; `render` shows the diagnostics.
pub fn combined(
    c: nctrans::translate::called::Combined,
    render: &dyn Fn(&SourceDb, &[diag::Diagnostic]) -> String,
) -> ExitCode {
    use nctrans::translate::called::Combined;
    match c {
        Combined::Equivalent { events, runs, excluded } => {
            eprintln!("{}", Combined::summary(events, runs, &excluded));
            ExitCode::SUCCESS
        }
        Combined::Not(label, report) => {
            if !label.is_empty() {
                // (The main run's are shown.)
                eprint!("{}", render(&report.db, &report.diags));
                eprintln!("in the run{label}:");
            }
            crate::cli::translate::job::verdict(report.verdict, &report.diff)
        }
    }
}
