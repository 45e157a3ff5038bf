//! Printing to stdout that ends quietly when the reader has gone (`| head`, `| true`): a
//! closed pipe (`EPIPE`) is not an error of the study, so the text is dropped and the exit
//! code stays that of the study. `println!` would panic ("failed printing to stdout").

use std::io::{ErrorKind, Write};

/// Write `text` to stdout and flush. A closed pipe (`BrokenPipe`) is success; any other
/// write error is returned.
pub fn print_stdout(text: &str) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}
