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

/// The longest prompt a template may render to, in bytes, like the longest answer read
/// ([`crate::MAX_BODY_BYTES`]): a small template can expand into a huge text (a loop, a
/// repeated string), and no model reads a prompt that long. Rendering stops there, with an
/// error, having held at most this much.
pub const MAX_PROMPT_BYTES: usize = 8 * 1024 * 1024;

/// A sink for a rendered prompt that refuses to grow past its cap.
struct CappedText {
    text: Vec<u8>,
    cap: usize,
    over: bool,
}

impl std::io::Write for CappedText {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.text.len() + buf.len() > self.cap {
            self.over = true;
            return Err(std::io::Error::other("the prompt passed its cap"));
        }
        self.text.extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

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

    /// Renders template `name` with `ctx`; a prompt over `MAX_PROMPT_BYTES` is an error.
    pub fn render(&self, name: &str, ctx: &Value) -> Result<String, String> {
        self.render_capped(name, ctx, MAX_PROMPT_BYTES)
    }

    /// Renders template `name` with `ctx`, stopping with an error once the text passes `cap`
    /// bytes.
    fn render_capped(&self, name: &str, ctx: &Value, cap: usize) -> Result<String, String> {
        let source = self
            .sources
            .get(name)
            .ok_or_else(|| format!("no prompt template {name:?}"))?;
        let mut env = Environment::new();
        env.add_template(name, source)
            .map_err(|e| format!("prompt {name}: {e}"))?;
        let mut out = CappedText {
            text: Vec::new(),
            cap,
            over: false,
        };
        let rendered = env
            .get_template(name)
            .and_then(|t| t.render_captured_to(minijinja::value::Serde(ctx), &mut out));
        if out.over {
            let mib = match cap >= 1024 * 1024 {
                true => format!(" ({} MiB)", cap / (1024 * 1024)),
                false => String::new(),
            };
            return Err(format!(
                "prompt {name}: the rendered prompt is over {cap} bytes{mib}, more than any \
                 model reads; check the template for a loop or a repeated string"
            ));
        }
        rendered.map_err(|e| format!("prompt {name}: {e}"))?;
        let text = String::from_utf8_lossy(&out.text);
        Ok(text.trim().to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with_source(name: &str, source: &str) -> Prompts {
        let mut p = Prompts::default();
        p.sources.insert(name.into(), source.into());
        p
    }

    #[test]
    fn a_template_that_expands_past_the_cap_is_an_error_not_a_huge_prompt() {
        let p = with_source(
            "t",
            "{% for i in range(10000) %}{{ 'x' * 1000 }}{% endfor %}",
        );
        let e = p.render("t", &serde_json::json!({})).unwrap_err();
        assert!(e.contains("over 8388608 bytes (8 MiB)"), "{e}");
        let e = p
            .render_capped("t", &serde_json::json!({}), 5000)
            .unwrap_err();
        assert!(e.contains("over 5000 bytes"), "{e}");
        let small = with_source("t", "  {{ 'ab' * 3 }}  ");
        assert_eq!(small.render("t", &serde_json::json!({})).unwrap(), "ababab");
        assert_eq!(
            small
                .render_capped("t", &serde_json::json!({}), 10)
                .unwrap(),
            "ababab",
            "a text exactly at the cap (with the spaces) is kept"
        );
    }
}
