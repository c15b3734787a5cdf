//! Reading JSON inputs with errors that point at the field, and writing outputs atomically.

use std::path::Path;

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::error::{Error, Result};

/// Reads a whole file, naming it in the error.
pub fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|source| Error::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// Parses `text` (the content of `path`) as `T`.
///
/// Syntax errors name the line and column (and say when the file looks truncated); data errors
/// name the JSON path of the offending field, e.g. `assets[1].size`.
pub fn parse_json<T: DeserializeOwned>(path: &Path, text: &str) -> Result<T> {
    let mut de = serde_json::Deserializer::from_str(text);
    let value: T = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let field = e.path().to_string();
        let inner = e.into_inner();
        json_error(path, Some(field), &inner)
    })?;
    de.end().map_err(|e| json_error(path, None, &e))?;
    Ok(value)
}

fn json_error(path: &Path, field: Option<String>, e: &serde_json::Error) -> Error {
    use serde_json::error::Category;
    let mut at = format!("line {}, column {}", e.line(), e.column());
    if let Some(f) = field.as_deref().filter(|f| *f != "." && !f.contains('?')) {
        at = format!("{f} ({at})");
    }
    match e.classify() {
        Category::Eof => {
            Error::invalid(path, at, "the JSON ends too early (is the file truncated?)")
        }
        Category::Syntax => {
            Error::invalid(path, at, format!("invalid JSON: {}", strip_position(e)))
        }
        Category::Data | Category::Io => {
            let field = match field {
                Some(f) if f != "." => f,
                _ => "(document)".to_string(),
            };
            Error::invalid(path, field, strip_position(e))
        }
    }
}

/// serde_json appends " at line L column C" to its messages; we report the position separately.
fn strip_position(e: &serde_json::Error) -> String {
    let msg = e.to_string();
    match msg.rfind(" at line ") {
        Some(i) => msg[..i].to_string(),
        None => msg,
    }
}

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, then a rename, so a
/// reader never sees a half-written output and an interrupted run leaves the old file intact.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write;
    let err = |source| Error::Write {
        path: path.to_path_buf(),
        source,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".disco-").suffix(".tmp");
    // Temporary files are private (0600) by default; an output should read like any other file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let mut tmp = builder.tempfile_in(dir).map_err(err)?;
    tmp.write_all(bytes).map_err(err)?;
    tmp.as_file().sync_all().map_err(err)?;
    tmp.persist(path).map_err(|e| err(e.error))?;
    Ok(())
}

/// Serialises `value` as pretty JSON and writes it atomically to `path`.
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let mut text = serde_json::to_string_pretty(value).map_err(|e| Error::Write {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    })?;
    text.push('\n');
    write_atomic(path, text.as_bytes())
}
