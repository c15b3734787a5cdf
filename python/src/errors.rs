//! The library's errors as Python exceptions. The classes live in `disco_layout/errors.py`
//! (so they can also derive from `ValueError` and `OSError`); each carries the fields of the
//! error it stands for and the exit code `disco` gives the same failure.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use disco_layout::Error;

/// An exception's attributes, by name.
type Fields<'a> = Vec<(&'a str, Py<PyAny>)>;

/// Raises `class` of `disco_layout.errors` with `message`, its attributes set from `fields`.
pub fn raise(py: Python<'_>, class: &str, message: &str, fields: &[(&str, Py<PyAny>)]) -> PyErr {
    let made = (|| -> PyResult<PyErr> {
        let cls = py.import("disco_layout.errors")?.getattr(class)?;
        let kwargs = PyDict::new(py);
        for (key, value) in fields {
            kwargs.set_item(key, value)?;
        }
        let exc = cls.call((message,), Some(&kwargs))?;
        Ok(PyErr::from_value(exc))
    })();
    made.unwrap_or_else(|e| e)
}

/// The Python exception for a library error.
pub fn to_py(py: Python<'_>, e: &Error) -> PyErr {
    let mut message = e.to_string();
    let text = |s: &str| s.into_pyobject(py).map(|o| o.into_any().unbind());
    let path = |p: &std::path::Path| text(&p.to_string_lossy());
    let fields: PyResult<(&str, Fields<'_>)> = (|| {
        Ok(match e {
            Error::Read { path: p, .. } | Error::Write { path: p, .. } => {
                ("FileError", vec![("path", path(p)?)])
            }
            Error::Invalid {
                path: p,
                field,
                reason,
            } => {
                let field = shown_field(p, field);
                message = format!("{}: {field}: {reason}", p.display());
                (
                    "ValidationError",
                    vec![
                        ("path", path(p)?),
                        ("field", text(field)?),
                        ("reason", text(reason)?),
                    ],
                )
            }
            Error::Scene { id, failure } => (
                "SceneError",
                vec![
                    ("scene_id", text(id)?),
                    ("reason", text(&failure.to_string())?),
                ],
            ),
            Error::Model { name, reason } => (
                "ModelError",
                vec![("model", text(name)?), ("reason", text(reason)?)],
            ),
            Error::Render(reason) => ("RenderError", vec![("reason", text(reason)?)]),
        })
    })();
    match fields {
        Ok((class, fields)) => raise(py, class, &message, &fields),
        Err(e) => e,
    }
}

/// The label of an agent graph passed as a dict.
pub const CONFIG_LABEL: &str = "<config>";

/// A field as the user should see it: for a graph given as a dict, without the line of the TOML
/// made from it (the user never saw that text), so `line 3, agents.designer.impl` becomes
/// `agents.designer.impl`.
fn shown_field<'a>(path: &std::path::Path, field: &'a str) -> &'a str {
    if path.as_os_str() != CONFIG_LABEL {
        return field;
    }
    match field.split_once(", ") {
        Some((line, rest)) if line.starts_with("line ") => rest,
        _ => field,
    }
}

/// `Result<T, disco_layout::Error>` into a `PyResult`.
pub trait IntoPy<T> {
    /// The value, or the error as its Python exception.
    fn py_err(self, py: Python<'_>) -> PyResult<T>;
}

impl<T> IntoPy<T> for disco_layout::Result<T> {
    fn py_err(self, py: Python<'_>) -> PyResult<T> {
        self.map_err(|e| to_py(py, &e))
    }
}
