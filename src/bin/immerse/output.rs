//! Everything the tool says to people goes through here (stderr); stdout
//! carries only data (text reports here; JSON and images through the
//! render crate's `OutputFile`, via `commands::write_json` and the image
//! writers).

use std::io::Write;

/// Prints the error chain on one line: `immerse: cause: cause`.
pub(crate) fn error(err: &anyhow::Error) {
    let _ = writeln!(std::io::stderr().lock(), "immerse: {}", one_line(err));
}

/// The error chain on one line, `error: cause: cause`, leaving out a cause
/// whose text the message already holds (errors whose message quotes their
/// source would otherwise print it twice).
fn one_line(err: &anyhow::Error) -> String {
    let mut line = String::new();
    for cause in err.chain() {
        let text = cause.to_string();
        if line.is_empty() {
            line = text;
        } else if !line.contains(&text) {
            line.push_str(": ");
            line.push_str(&text);
        }
    }
    line
}

/// Prints a one-line notice to stderr.
pub(crate) fn note(message: &str) {
    let _ = writeln!(std::io::stderr().lock(), "immerse: {message}");
}

/// Writes `text` and a newline to stdout.
pub(crate) fn print(text: &str) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.write_all(b"\n")?;
    out.flush()?;
    Ok(())
}
