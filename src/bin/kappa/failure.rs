//! Failures of the tool: one line on stderr and exit code 2, and the file and stream helpers
//! that produce them.

use std::fmt::Display;
use std::io::{Read, Write};
use std::path::Path;
use std::process::ExitCode;

/// Exit code of every error (bad input, unreadable file, solver failure, usage error).
pub const EXIT_ERROR: u8 = 2;

/// An error that ends the program: printed as `kappa: error: <message>` on one line.
#[derive(Debug)]
pub struct Failure(String);

/// The result of the tool's operations.
pub type Result<T> = std::result::Result<T, Failure>;

impl Failure {
    /// A failure with this message.
    pub fn new(message: impl Display) -> Failure {
        Failure(message.to_string())
    }

    /// The same failure with `context: ` in front of its message.
    pub fn context(self, context: impl Display) -> Failure {
        Failure(format!("{context}: {}", self.0))
    }

    /// Prints the message and returns the error exit code.
    pub fn report(&self) -> ExitCode {
        eprintln!("kappa: error: {}", one_line(&self.0));
        ExitCode::from(EXIT_ERROR)
    }
}

/// `text` with its lines joined by `; `, so that a message is always a single line.
fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

/// Reports a command-line parsing error: `--help` and `--version` print as usual, everything
/// else (a bare `kappa` too) becomes one `kappa: error:` line with exit code 2.
pub fn usage_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            ExitCode::from(if e.use_stderr() { EXIT_ERROR } else { 0 })
        }
        // clap shows the whole help for a missing command; the contract is one line.
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            Failure::new("no command given; try 'kappa --help'").report()
        }
        _ => {
            // clap's message is the text before the "Usage:" or "For more information" line;
            // keep all of it (some messages continue on the next lines, and tips follow an
            // empty line).
            let text = e.to_string();
            let mut message = String::new();
            for line in text
                .lines()
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
                .map(str::trim)
                .filter(|l| !l.is_empty())
            {
                if !message.is_empty() {
                    message.push_str(if line.starts_with("tip:") { "; " } else { " " });
                }
                message.push_str(line.strip_prefix("error: ").unwrap_or(line));
            }
            Failure::new(format!("{message}; try 'kappa --help'")).report()
        }
    }
}

/// Makes a panic (a bug) print one `kappa: error:` line instead of the default report.
pub fn install_panic_hook() {
    std::panic::set_hook(Box::new(|info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".to_owned());
        let location = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        eprintln!(
            "kappa: error: internal error (please report this bug): {}{location}",
            one_line(&message)
        );
    }));
}

/// The whole text of a file.
pub fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path)
        .map_err(|e| Failure::new(format!("cannot read {}: {e}", path.display())))
}

/// The whole of stdin as text.
pub fn read_stdin() -> Result<String> {
    let mut text = String::new();
    std::io::stdin()
        .read_to_string(&mut text)
        .map_err(|e| Failure::new(format!("cannot read stdin: {e}")))?;
    Ok(text)
}

/// The extension of a file name, in lower case (`None` without one).
pub fn extension(path: &Path) -> Option<String> {
    path.extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
}

/// Writes `bytes` to the file at `path`, replacing it.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<()> {
    std::fs::write(path, bytes)
        .map_err(|e| Failure::new(format!("cannot write {}: {e}", path.display())))
}

/// Writes `text` to stdout and flushes it.
pub fn print_stdout(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| Failure::new(format!("cannot write to stdout: {e}")))
}

#[cfg(test)]
mod tests {
    use super::one_line;

    #[test]
    fn failure_messages_are_one_line() {
        assert_eq!(one_line("a\n\n  b\n"), "a; b");
        assert_eq!(one_line("single"), "single");
    }
}
