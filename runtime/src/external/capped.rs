//! Reads from agents that cost a bounded amount of memory: a line (a process agent's stdout or
//! stderr) or a body (an HTTP agent's) is read chunk by chunk and stops at a cap, so that an
//! agent writing forever (`cat /dev/zero`) or a 3 GB line without a newline costs the cap and no
//! more.

use tokio::io::{AsyncBufRead, AsyncBufReadExt};

/// The default cap of one reply of an external agent, the same as a model answer's
/// ([`disco_llm::MAX_BODY_BYTES`]); `max_reply_bytes` in the agent's section changes it.
pub const MAX_REPLY_BYTES: usize = disco_llm::MAX_BODY_BYTES;

/// The smallest `max_reply_bytes` the graph accepts.
pub const MIN_REPLY_CAP: usize = 1024;

/// The largest `max_reply_bytes` the graph accepts (a reply is parsed in memory, several times
/// its size).
pub const MAX_REPLY_CAP: usize = 256 * 1024 * 1024;

/// How a capped line read ended.
#[derive(Debug, PartialEq, Eq)]
pub enum Line {
    /// A whole line (without its newline); also the last bytes before the end of the stream
    /// when they had no newline.
    Line(Vec<u8>),
    /// The stream ended with nothing more to read.
    End,
    /// The line passed the cap; what came first (at most the cap) is kept, the rest of the
    /// line is left unread.
    TooLong(Vec<u8>),
}

/// Reads one line of at most `cap` bytes from `reader`, `fill_buf` chunk by chunk: it never
/// holds more than `cap` bytes plus the reader's buffer.
pub async fn read_line<R: AsyncBufRead + Unpin>(
    reader: &mut R,
    cap: usize,
) -> std::io::Result<Line> {
    let mut line = Vec::new();
    loop {
        let chunk = reader.fill_buf().await?;
        if chunk.is_empty() {
            return Ok(match line.is_empty() {
                true => Line::End,
                false => Line::Line(line),
            });
        }
        let (take, newline) = match chunk.iter().position(|b| *b == b'\n') {
            Some(i) => (i, true),
            None => (chunk.len(), false),
        };
        if line.len() + take > cap {
            let room = cap - line.len();
            line.extend_from_slice(&chunk[..room]);
            reader.consume(room);
            return Ok(Line::TooLong(line));
        }
        line.extend_from_slice(&chunk[..take]);
        reader.consume(take + usize::from(newline));
        if newline {
            return Ok(Line::Line(line));
        }
    }
}

/// Skips the rest of the current line (after a [`Line::TooLong`]); returns how many bytes it
/// skipped. Reads chunk by chunk, keeping none of them.
pub async fn skip_line<R: AsyncBufRead + Unpin>(reader: &mut R) -> std::io::Result<u64> {
    let mut skipped = 0u64;
    loop {
        let chunk = reader.fill_buf().await?;
        if chunk.is_empty() {
            return Ok(skipped);
        }
        match chunk.iter().position(|b| *b == b'\n') {
            Some(i) => {
                reader.consume(i + 1);
                return Ok(skipped + i as u64);
            }
            None => {
                let n = chunk.len();
                reader.consume(n);
                skipped += n as u64;
            }
        }
    }
}

/// `cap` bytes for a message: "8 MiB", "1.5 KiB" or "100 bytes".
pub fn shown(cap: usize) -> String {
    const KIB: usize = 1024;
    const MIB: usize = 1024 * 1024;
    match cap {
        c if c >= MIB && c % MIB == 0 => format!("{} MiB", c / MIB),
        c if c >= MIB => format!("{:.1} MiB", c as f64 / MIB as f64),
        c if c >= KIB && c % KIB == 0 => format!("{} KiB", c / KIB),
        c => format!("{c} bytes"),
    }
}

/// The message of a reply over its cap.
pub fn too_long(cap: usize) -> String {
    format!(
        "its reply is over {} (the agent's `max_reply_bytes`), so it is unusable; the rest was \
         not read",
        shown(cap)
    )
}

/// A reply as text, or why it is not UTF-8 (where the first bad byte is).
pub fn utf8(bytes: Vec<u8>) -> Result<String, String> {
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let bad = e.as_bytes().get(at).copied().unwrap_or(0);
        format!("its reply is not UTF-8 (byte {bad:#04x} at offset {at})")
    })
}
