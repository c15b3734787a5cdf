//! The prompt templates (`prompts/*.j2`, minijinja), built in and overridable per agent from the
//! config (`prompt = "my-designer.j2"`).

use std::collections::BTreeMap;
use std::path::Path;

use minijinja::Environment;
use serde_json::Value;

/// The built-in templates by name.
pub const BUILTIN: [(&str, &str); 9] = [
    ("system", include_str!("../../prompts/system.j2")),
    ("planner", include_str!("../../prompts/planner.j2")),
    ("designer", include_str!("../../prompts/designer.j2")),
    ("evaluator", include_str!("../../prompts/evaluator.j2")),
    (
        "evaluator_batch",
        include_str!("../../prompts/evaluator_batch.j2"),
    ),
    ("physical", include_str!("../../prompts/physical.j2")),
    ("srt", include_str!("../../prompts/srt.j2")),
    ("judge", include_str!("../../prompts/judge.j2")),
    ("open", include_str!("../../prompts/evaluator.j2")),
];

/// A set of templates: the built-in ones, some replaced by files.
#[derive(Debug, Clone)]
pub struct Prompts {
    sources: BTreeMap<String, String>,
}

impl Default for Prompts {
    fn default() -> Self {
        Prompts {
            sources: BUILTIN
                .iter()
                .map(|(n, s)| (n.to_string(), s.to_string()))
                .collect(),
        }
    }
}

impl Prompts {
    /// The built-in templates, with template `name` read from `path` instead.
    pub fn with_file(mut self, name: &str, path: &Path) -> disco_core::Result<Self> {
        let text = disco_core::io::read_text(path)?;
        // Fail now, naming the file, rather than at the first call.
        let mut env = Environment::new();
        env.add_template("t", &text)
            .map_err(|e| disco_core::Error::invalid(path, "template", e.to_string()))?;
        self.sources.insert(name.to_string(), text);
        Ok(self)
    }

    /// Renders template `name` with `ctx`.
    pub fn render(&self, name: &str, ctx: &Value) -> Result<String, String> {
        let source = self
            .sources
            .get(name)
            .ok_or_else(|| format!("no prompt template {name:?}"))?;
        let mut env = Environment::new();
        env.add_template(name, source)
            .map_err(|e| format!("prompt {name}: {e}"))?;
        env.get_template(name)
            .and_then(|t| t.render(minijinja::value::Serde(ctx)))
            .map(|s| s.trim().to_string())
            .map_err(|e| format!("prompt {name}: {e}"))
    }
}
