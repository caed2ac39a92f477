//! The command-line definition (clap derive). Each subcommand's arguments
//! are turned into library options in `commands/`.

use clap::{Args, Parser, Subcommand};
use std::path::PathBuf;

const AFTER_HELP: &str = "\
Examples:
  immerse check curves/spiral-strip-540deg-n120.json
  immerse check drawing.svg --json

Exit codes: 0 success (or yes), 1 a negative answer (e.g. not self-overlapping),
2 bad input or usage; the cause is printed on one line to stderr.";

/// Tween closed curves that cross themselves, so that every in-between is
/// the boundary of an immersed disk.
#[derive(Debug, Parser)]
#[command(name = "immerse", version, about, long_about = None, after_help = AFTER_HELP)]
pub(crate) struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub(crate) command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub(crate) enum Command {
    /// Report the facts of a curve: points, turning number, simplicity.
    ///
    /// Reads a curve (.json, .txt or .svg), cleans it (drops a repeated
    /// closing point and consecutive duplicates) and orients it (a
    /// clockwise curve is reversed). Prints what was found; with --json,
    /// one JSON object on stdout.
    #[command(
        after_help = "Examples:\n  immerse check curves/letter-S-n62.json\n  immerse check ribbon.svg --json"
    )]
    Check(CheckArgs),
}

/// Arguments of `immerse check`.
#[derive(Debug, Args)]
pub(crate) struct CheckArgs {
    /// The curve file (.json, .txt, .csv, .xy or .svg).
    pub(crate) curve: PathBuf,
    /// Print one JSON object on stdout instead of text.
    ///
    /// Fields: points (count after cleaning), turning_number (of the curve
    /// as given), simple, reversed, self_overlapping, reason.
    #[arg(long)]
    pub(crate) json: bool,
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn cli_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn check_parses_json_flag() {
        let cli = Cli::try_parse_from(["immerse", "check", "a.json", "--json"]).unwrap();
        let Command::Check(args) = cli.command;
        assert!(args.json);
        assert_eq!(args.curve, PathBuf::from("a.json"));
    }
}
