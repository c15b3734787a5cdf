//! Reading JSON inputs with errors that point at the field, writing outputs atomically, and
//! messages on stderr that a closed pipe cannot turn into a panic.

use std::path::{Path, PathBuf};

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::error::{Error, Result};

/// The largest input file read: a scene, layout or config larger than this is surely a mistake.
pub const MAX_INPUT_BYTES: u64 = 64 * 1024 * 1024;

/// Reads a whole text file, naming it in the error. Only regular files are read (a FIFO or a
/// device would block or never end), at most [`MAX_INPUT_BYTES`]; a UTF-8 byte-order mark is
/// dropped.
pub fn read_text(path: &Path) -> Result<String> {
    let bytes = read_bytes(path, MAX_INPUT_BYTES)?;
    let mut text = String::from_utf8(bytes).map_err(|e| {
        Error::invalid(
            path,
            format!("byte {}", e.utf8_error().valid_up_to()),
            "the file is not UTF-8 text",
        )
    })?;
    if text.starts_with('\u{feff}') {
        text.drain(..'\u{feff}'.len_utf8());
    }
    Ok(text)
}

/// Reads a whole regular file of at most `limit` bytes, naming it in the error.
pub fn read_bytes(path: &Path, limit: u64) -> Result<Vec<u8>> {
    use std::io::Read;
    let err = |source| Error::Read {
        path: path.to_path_buf(),
        source,
    };
    let meta = std::fs::metadata(path).map_err(err)?;
    if !meta.is_file() {
        return Err(Error::invalid(
            path,
            "(file)",
            "not a regular file (a folder, FIFO or device cannot be read as input)",
        ));
    }
    if meta.len() > limit {
        return Err(Error::invalid(
            path,
            "(file)",
            format!("{} bytes is over the limit of {limit}", meta.len()),
        ));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)
        .map_err(err)?
        .take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(err)?;
    if bytes.len() as u64 > limit {
        return Err(Error::invalid(
            path,
            "(file)",
            format!("grew over the limit of {limit} bytes while being read"),
        ));
    }
    Ok(bytes)
}

/// A file name stem for `id` that stays inside its folder and differs for different ids: letters,
/// digits, `-`, `_` and `.` are kept, every other byte becomes `%XX` (so `a/b`, `a_b` and `a?b`
/// stay apart), `.` and `..` are escaped, and a stem over 120 bytes is cut and given a hash of the
/// whole id.
pub fn safe_file_stem(id: &str) -> String {
    use std::fmt::Write;
    let mut out = String::with_capacity(id.len());
    for c in id.chars() {
        if c.is_alphanumeric() || "-_".contains(c) || (c == '.' && !out.is_empty()) {
            out.push(c);
        } else {
            let mut buf = [0u8; 4];
            for b in c.encode_utf8(&mut buf).bytes() {
                let _ = write!(out, "%{b:02X}");
            }
        }
    }
    if out.is_empty() {
        out.push_str("%00");
    }
    const MAX: usize = 120;
    if out.len() > MAX {
        use sha2::{Digest, Sha256};
        let mut cut = MAX - 17;
        while !out.is_char_boundary(cut) {
            cut -= 1;
        }
        let hash = Sha256::digest(id.as_bytes());
        let hex: String = hash[..8].iter().map(|b| format!("{b:02x}")).collect();
        out = format!("{}-{hex}", &out[..cut]);
    }
    out
}

/// Removes temporary files that an interrupted write left in `dir` (`.disco-*.tmp`, older than a
/// minute, so a write in progress elsewhere is left alone). Returns how many were removed.
pub fn clean_stale_temp_files(dir: &Path) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    let minute = std::time::Duration::from_secs(60);
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let stale = entry
            .metadata()
            .ok()
            .filter(|m| m.is_file())
            .and_then(|m| m.modified().ok())
            .and_then(|t| t.elapsed().ok())
            .is_some_and(|age| age > minute);
        if name.starts_with(".disco-")
            && name.ends_with(".tmp")
            && stale
            && std::fs::remove_file(entry.path()).is_ok()
        {
            removed += 1;
        }
    }
    removed
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
        Category::Syntax if strip_position(e) == "trailing characters" && field.is_some() => {
            Error::invalid(
                path,
                at,
                "too many values in this list (a size has 3: [width, depth, height]; a position 2: [x, y])",
            )
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

/// Held (shared) by every [`write_atomic`] while its temporary file exists; [`stop_writes`]
/// takes it for good.
static WRITES: std::sync::RwLock<()> = std::sync::RwLock::new(());

/// Waits for the atomic writes in progress to finish (renamed into place, no temporary file left)
/// and blocks every later one, for good. For the binary's SIGTERM/SIGINT handler, just before it
/// exits: what is finished is written whole, and nothing is half-written.
pub fn stop_writes() {
    let held = WRITES.write().unwrap_or_else(|e| e.into_inner());
    std::mem::forget(held);
}

/// Writes `bytes` to `path` atomically: a temporary file in the same folder, then a rename, so a
/// reader never sees a half-written output and an interrupted run leaves the old file intact.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write;
    let _writing = WRITES.read().unwrap_or_else(|e| e.into_inner());
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

/// A file a command reads or writes, with the flag or argument that names it (`-o`, `--glb`,
/// `SCENE`), for [`refuse_clobbering`]'s messages.
#[derive(Debug, Clone, Copy)]
pub struct NamedPath<'a> {
    /// How the command line names it: a flag (`--glb`) or an argument (`SCENE`).
    pub flag: &'a str,
    /// The path as given.
    pub path: &'a Path,
}

impl<'a> NamedPath<'a> {
    /// `path` as named by `flag`.
    pub fn new(flag: &'a str, path: &'a Path) -> Self {
        NamedPath { flag, path }
    }
}

/// Refuses a command whose outputs would replace one of its inputs or each other, before
/// anything is written: two paths are the same file when they resolve to the same place
/// (through `..`, symbolic links, or a folder reached two ways) or are hard links of one file
/// (same device and inode). `folders` are output folders a command fills wholesale (e.g.
/// `--renders DIR` writes `DIR/<id>/`): nothing read or written elsewhere may lie inside one.
/// The error names the output's path and both flags.
pub fn refuse_clobbering(
    inputs: &[NamedPath],
    outputs: &[NamedPath],
    folders: &[NamedPath],
) -> Result<()> {
    let refuse = |out: &NamedPath, why: String| Err(Error::invalid(out.path, out.flag, why));
    for (k, out) in outputs.iter().enumerate() {
        if let Some(input) = inputs.iter().find(|i| same_file(i.path, out.path)) {
            return refuse(
                out,
                format!(
                    "is the same file as the input {} ({}): an output must not replace an input; choose another path",
                    input.flag,
                    input.path.display()
                ),
            );
        }
        if let Some(other) = outputs[..k].iter().find(|o| same_file(o.path, out.path)) {
            return refuse(
                out,
                format!(
                    "is the same file as {} ({}): two outputs of one command cannot share a file; choose another path",
                    other.flag,
                    other.path.display()
                ),
            );
        }
    }
    for folder in folders {
        let inside = |p: &NamedPath| p.path != folder.path && lies_within(p.path, folder.path);
        if let Some(input) = inputs.iter().find(|i| inside(i)) {
            return refuse(
                folder,
                format!(
                    "would fill a folder holding the input {} ({}); choose another folder",
                    input.flag,
                    input.path.display()
                ),
            );
        }
        if let Some(other) = outputs.iter().chain(folders).find(|o| inside(o)) {
            return refuse(
                folder,
                format!(
                    "would fill a folder holding the output of {} ({}); choose another folder",
                    other.flag,
                    other.path.display()
                ),
            );
        }
    }
    Ok(())
}

/// Refuses `folder`, an output folder a command fills, when it is one of `inputs` (a file or a
/// folder), lies inside an input folder, or holds an input, once paths are resolved (`..`,
/// symbolic links) and hard links compared: its files would mix with the inputs, and the next
/// run would read them as inputs. The error names the folder, its flag and the input's.
pub fn refuse_folder_over_inputs(inputs: &[NamedPath], folder: &NamedPath) -> Result<()> {
    let refuse = |why: String| Err(Error::invalid(folder.path, folder.flag, why));
    for input in inputs {
        let (flag, shown) = (input.flag, input.path.display());
        if same_file(input.path, folder.path) {
            return refuse(format!(
                "is the input {flag} ({shown}): an output folder must not be an input; choose another folder"
            ));
        }
        if lies_within(folder.path, input.path) {
            return refuse(format!(
                "lies inside the input folder {flag} ({shown}): its files would mix with the inputs; choose another folder"
            ));
        }
        if lies_within(input.path, folder.path) {
            return refuse(format!(
                "would fill a folder holding the input {flag} ({shown}); choose another folder"
            ));
        }
    }
    Ok(())
}

/// Whether `a` and `b` name the same file: the same place once resolved, or (for existing
/// files) the same device and inode, as hard links are.
pub fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b))
            && (ma.dev(), ma.ino()) == (mb.dev(), mb.ino())
        {
            return true;
        }
    }
    resolve_path(a) == resolve_path(b)
}

/// Whether `path` is `dir` or lies somewhere inside it, once both are resolved.
pub fn lies_within(path: &Path, dir: &Path) -> bool {
    resolve_path(path).starts_with(resolve_path(dir))
}

/// Where `path` leads: its canonical form when it exists; otherwise its longest existing
/// ancestor made canonical (symbolic links followed) and the rest appended, `.` and `..`
/// resolved by name. Relative paths are taken from the current folder.
pub fn resolve_path(path: &Path) -> PathBuf {
    use std::path::Component;
    if let Ok(c) = path.canonicalize() {
        return c;
    }
    let absolute = match std::env::current_dir() {
        Ok(cwd) if path.is_relative() => cwd.join(path),
        _ => path.to_path_buf(),
    };
    // Walk up to an ancestor that exists, keeping the names below it.
    let mut base = absolute.as_path();
    let mut rest: Vec<&std::ffi::OsStr> = Vec::new();
    let mut resolved = loop {
        if let Ok(c) = base.canonicalize() {
            break c;
        }
        match (base.parent(), base.file_name()) {
            (Some(parent), Some(name)) => {
                rest.push(name);
                base = parent;
            }
            // `..` as the last component, or the root: resolve by name from here.
            _ => break PathBuf::new(),
        }
    };
    if resolved.as_os_str().is_empty() {
        for c in absolute.components() {
            match c {
                Component::ParentDir => {
                    resolved.pop();
                }
                Component::CurDir => {}
                other => resolved.push(other.as_os_str()),
            }
        }
        return resolved;
    }
    for name in rest.into_iter().rev() {
        match Path::new(name).components().next() {
            Some(Component::ParentDir) => {
                resolved.pop();
            }
            Some(Component::CurDir) | None => {}
            Some(_) => resolved.push(name),
        }
    }
    resolved
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

/// Writes `text` to stderr as `eprint!` would, but never panics: a stderr whose reader has gone
/// away (a closed pipe, EPIPE) or that cannot be written at all drops the text, since there is
/// nowhere left to say anything. Every message of the `disco` binary and the runtime goes
/// through here.
pub fn to_stderr(text: &str) {
    use std::io::Write;
    let mut stderr = std::io::stderr().lock();
    let _ = stderr
        .write_all(text.as_bytes())
        .and_then(|()| stderr.flush());
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn file_stems_stay_in_their_folder_and_apart() {
        assert_eq!(safe_file_stem("bedroom-01"), "bedroom-01");
        assert_eq!(safe_file_stem("a.b_c"), "a.b_c");
        let stems: Vec<String> = ["a/b", "a_b", "a?b", "..", ".", "", "a\\b"]
            .iter()
            .map(|id| safe_file_stem(id))
            .collect();
        for (i, a) in stems.iter().enumerate() {
            assert!(
                !a.contains('/') && !a.contains('\\') && a != "." && a != "..",
                "{a}"
            );
            assert!(!a.is_empty() && !a.starts_with('.'), "{a}");
            for b in &stems[i + 1..] {
                assert_ne!(a, b);
            }
        }
        let long = "x".repeat(300);
        let stem = safe_file_stem(&long);
        assert!(stem.len() <= 120, "{}", stem.len());
        assert_ne!(stem, safe_file_stem(&"x".repeat(301)));
    }

    #[test]
    fn only_regular_files_are_read_and_a_bom_is_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let e = read_text(dir.path()).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{e}");
        let f = dir.path().join("bom.json");
        std::fs::write(&f, "\u{feff}{}").unwrap();
        assert_eq!(read_text(&f).unwrap(), "{}");
        let big = dir.path().join("big");
        std::fs::write(&big, vec![b' '; 100]).unwrap();
        assert!(
            read_bytes(&big, 99)
                .unwrap_err()
                .to_string()
                .contains("over the limit")
        );
        #[cfg(unix)]
        {
            let fifo = dir.path().join("fifo");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            if made.is_ok_and(|s| s.success()) {
                let e = read_text(&fifo).unwrap_err().to_string();
                assert!(e.contains("not a regular file"), "{e}");
            }
        }
    }

    #[test]
    fn an_output_over_an_input_is_refused_by_path_link_or_inode() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let scene = d.join("scene.json");
        std::fs::write(&scene, "{}").unwrap();
        std::fs::create_dir(d.join("sub")).unwrap();
        let input = [NamedPath::new("SCENE", &scene)];
        let refused = |out: &Path| {
            refuse_clobbering(&input, &[NamedPath::new("--glb", out)], &[])
                .unwrap_err()
                .to_string()
        };
        let e = refused(&d.join("sub/../scene.json"));
        assert!(
            e.contains("--glb: is the same file as the input SCENE"),
            "{e}"
        );
        #[cfg(unix)]
        {
            let link = d.join("link.json");
            std::os::unix::fs::symlink(&scene, &link).unwrap();
            refused(&link);
            let hard = d.join("hard.json");
            std::fs::hard_link(&scene, &hard).unwrap();
            refused(&hard);
            let linked_dir = d.join("again");
            std::os::unix::fs::symlink(d, &linked_dir).unwrap();
            refused(&linked_dir.join("scene.json"));
        }
        let fine = d.join("out/layout.json");
        refuse_clobbering(&input, &[NamedPath::new("-o", &fine)], &[]).unwrap();
    }

    #[test]
    fn two_outputs_on_one_file_and_files_inside_an_output_folder_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let (a, b) = (d.join("new/room.json"), d.join("new/./x/../room.json"));
        let e = refuse_clobbering(
            &[],
            &[NamedPath::new("-o", &a), NamedPath::new("--glb", &b)],
            &[],
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("--glb: is the same file as -o"), "{e}");
        let scene = d.join("renders/room/scene.json");
        let e = refuse_clobbering(
            &[NamedPath::new("SCENE", &scene)],
            &[],
            &[NamedPath::new("--renders", &d.join("renders/room"))],
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("--renders: would fill a folder holding the input SCENE"),
            "{e}"
        );
        let beside = d.join("renders/scene.json");
        refuse_clobbering(
            &[NamedPath::new("SCENE", &beside)],
            &[NamedPath::new("-o", &a)],
            &[NamedPath::new("--renders", &d.join("renders/room"))],
        )
        .unwrap();
    }

    #[test]
    fn an_output_folder_that_is_inside_or_holds_an_input_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        let scenes = d.join("scenes");
        std::fs::create_dir(&scenes).unwrap();
        let one = d.join("one.json");
        std::fs::write(&one, "{}").unwrap();
        let inputs = [
            NamedPath::new("--scenes", &scenes),
            NamedPath::new("--scenes", &one),
        ];
        let refused = |out: &Path| {
            refuse_folder_over_inputs(&inputs, &NamedPath::new("--out", out))
                .unwrap_err()
                .to_string()
        };
        let e = refused(&scenes);
        assert!(e.contains("--out: is the input --scenes"), "{e}");
        assert!(refused(&d.join("scenes/./")).contains("is the input --scenes"));
        let e = refused(&scenes.join("results"));
        assert!(
            e.contains("--out: lies inside the input folder --scenes"),
            "{e}"
        );
        let e = refused(d);
        assert!(
            e.contains("--out: would fill a folder holding the input --scenes"),
            "{e}"
        );
        assert!(refused(&one).contains("is the input --scenes"));
        #[cfg(unix)]
        {
            let link = d.join("linked");
            std::os::unix::fs::symlink(&scenes, &link).unwrap();
            assert!(refused(&link).contains("is the input --scenes"));
            assert!(refused(&link.join("out")).contains("lies inside the input folder"));
        }
        refuse_folder_over_inputs(&inputs, &NamedPath::new("--out", &d.join("results"))).unwrap();
        refuse_folder_over_inputs(&inputs, &NamedPath::new("--out", &d.join("scenes-out")))
            .unwrap();
    }

    #[test]
    fn stale_temp_files_are_cleaned_and_fresh_ones_kept() {
        let dir = tempfile::tempdir().unwrap();
        let old = dir.path().join(".disco-abc.tmp");
        let fresh = dir.path().join(".disco-def.tmp");
        std::fs::write(&old, b"x").unwrap();
        std::fs::write(&fresh, b"x").unwrap();
        let past = std::time::SystemTime::now() - std::time::Duration::from_secs(3600);
        std::fs::File::options()
            .write(true)
            .open(&old)
            .unwrap()
            .set_modified(past)
            .unwrap();
        assert_eq!(clean_stale_temp_files(dir.path()), 1);
        assert!(!old.exists() && fresh.exists());
    }
}
