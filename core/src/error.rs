//! The library's error type: every failure names the file and, where it can, the field and the reason.

use std::path::{Path, PathBuf};

/// Everything that can go wrong in the library, with enough context to act on it.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read.
    #[error("{}: cannot read the file: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// A file could not be written (nothing is left half-written: outputs are replaced atomically).
    #[error("{}: cannot write the file: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// An input (scene spec, layout, plan) is malformed or impossible.
    #[error("{}: {field}: {reason}", path.display())]
    Invalid {
        /// The file the input came from (or a label such as `<scene>` for in-memory input).
        path: PathBuf,
        /// Where in the document: a JSON path such as `assets[2].size`, or `line 3, column 7`.
        field: String,
        /// What is wrong, in words.
        reason: String,
    },
    /// A scene could not be finished (a role failed beyond its retries and fallback, or the scene
    /// missed its deadline).
    #[error("scene {id}: {failure}")]
    Scene {
        /// The scene's id.
        id: String,
        /// What went wrong, typed: the runtime's `SceneFailure` (`disco_runtime::supervisor::
        /// SceneFailure`), which a caller can inspect with `downcast_ref`; its text is the reason.
        #[source]
        failure: Box<dyn std::error::Error + Send + Sync + 'static>,
    },
    /// A model server cannot be used (unreachable, key refused, no key).
    #[error("model {name}: {reason}")]
    Model {
        /// The model's name in the graph (`[models.NAME]`).
        name: String,
        /// What is wrong, with what the server said.
        reason: String,
    },
    /// A picture could not be produced.
    #[error("render: {0}")]
    Render(String),
}

impl Error {
    /// An [`Error::Invalid`] for `path`, `field` and `reason`.
    pub fn invalid(path: &Path, field: impl Into<String>, reason: impl Into<String>) -> Self {
        Error::Invalid {
            path: path.to_path_buf(),
            field: field.into(),
            reason: reason.into(),
        }
    }
}

/// The library's result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
