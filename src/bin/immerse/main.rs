//! The `immerse` command-line tool: a thin layer over the library.
//!
//! Exit codes are decided here only: 0 success, 1 a negative answer (for
//! example a curve that is not self-overlapping), 2 bad input or usage.

/// mimalloc instead of the system allocator: `morph` at 2,000 vertices
/// takes a fifth less time (docs/benchmarks.md).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

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

/// What Ctrl-C, SIGTERM and SIGHUP do instead of exiting, for a command
/// that stops by itself (`serve` finishes the requests in flight).
pub(crate) static ON_INTERRUPT: std::sync::OnceLock<Box<dyn Fn() + Send + Sync>> =
    std::sync::OnceLock::new();

/// Exit code after an interrupt (Ctrl-C, SIGTERM, SIGHUP): 128 + SIGINT,
/// as shells report it.
pub(crate) const INTERRUPTED: i32 = 130;

fn main() -> ExitCode {
    // On Ctrl-C, SIGTERM or SIGHUP remove what is half-written (temporary
    // files and folders of the outputs being written) and exit 130: an
    // interrupted run leaves no partial output. `ctrlc` runs the handler on
    // a thread of its own, where it may take locks and touch files.
    let _ = ctrlc::set_handler(|| {
        if let Some(stop) = ON_INTERRUPT.get() {
            stop();
            return;
        }
        let removed = immerse_render::remove_partial_outputs();
        output::note(&if removed > 0 {
            format!("interrupted; removed {removed} unfinished output(s)")
        } else {
            "interrupted".to_string()
        });
        std::process::exit(INTERRUPTED);
    });
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
