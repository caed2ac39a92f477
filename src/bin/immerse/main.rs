//! The `immerse` command-line tool: a thin layer over the library.
//!
//! Exit codes are decided here only: 0 success, 1 a negative answer (for
//! example a curve that is not self-overlapping), 2 bad input or usage.

mod args;
mod commands;
mod output;

use clap::Parser;
use std::process::ExitCode;

/// What a command concluded, when it did not fail.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Outcome {
    /// The command did its job (or answered yes).
    Success,
    /// The command answered no (exit code 1).
    Negative,
}

fn main() -> ExitCode {
    let cli = args::Cli::parse();
    match commands::run(cli) {
        Ok(Outcome::Success) => ExitCode::SUCCESS,
        Ok(Outcome::Negative) => ExitCode::from(1),
        Err(err) => {
            if is_broken_pipe(&err) {
                return ExitCode::SUCCESS;
            }
            output::error(&err);
            ExitCode::from(2)
        }
    }
}

fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}
