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

/// The most steps (minijinja's fuel: about one per instruction) rendering one prompt may take.
/// The size cap ([`MAX_PROMPT_BYTES`]) stops a template that writes too much; this stops one
/// that loops long without writing (nested loops over `range`) within a few seconds, where it
/// would otherwise run for minutes or hours. The built-in templates take under 0.3% of it for a
/// room of 500 objects (the designer's: about 58,000 steps).
pub const PROMPT_FUEL: u64 = 20_000_000;

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

    /// Renders template `name` with `ctx`; a prompt over `MAX_PROMPT_BYTES`, or a template
    /// that takes more than `PROMPT_FUEL` steps, is an error naming the template.
    pub fn render(&self, name: &str, ctx: &Value) -> Result<String, String> {
        self.render_capped(name, ctx, MAX_PROMPT_BYTES, PROMPT_FUEL)
    }

    /// Renders template `name` with `ctx`, stopping with an error once the text passes `cap`
    /// bytes or the template has taken `fuel` steps.
    fn render_capped(
        &self,
        name: &str,
        ctx: &Value,
        cap: usize,
        fuel: u64,
    ) -> Result<String, String> {
        let source = self
            .sources
            .get(name)
            .ok_or_else(|| format!("no prompt template {name:?}"))?;
        let mut env = Environment::new();
        env.set_fuel(Some(fuel));
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
        rendered.map_err(|e| match e.kind() {
            minijinja::ErrorKind::OutOfFuel => format!(
                "prompt {name}: the template ran out of fuel (more than {fuel} steps) before it \
                 was done; check it for a loop that runs too long"
            ),
            _ => format!("prompt {name}: {e}"),
        })?;
        let text = String::from_utf8_lossy(&out.text);
        Ok(text.trim().to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What any built-in template reads, for a room of `n` objects: each list `n` long.
    fn big_context(n: usize) -> Value {
        let object = |i: usize| {
            serde_json::json!({
                "name": format!("chair-{i}"), "category": "chair", "size": [45, 50, 90],
                "position": [100.5, 200.5], "rotation": 90,
                "constraints": ["against a wall", "facing table-0"],
                "rules": ["keep 60 cm in front"],
            })
        };
        let objects: Vec<Value> = (0..n).map(object).collect();
        let question = |i: usize| {
            serde_json::json!({
                "id": i, "text": "Is chair-0 facing table-0?", "question": "Is it?",
                "means": "the front points at it", "measured": "turned 12 degrees away",
                "reason": "it is turned away",
            })
        };
        let lines: Vec<String> = (0..n).map(|i| format!("chair-{i} moved 20 cm")).collect();
        let names: Vec<String> = (0..n).map(|i| format!("chair-{i}")).collect();
        serde_json::json!({
            "room": {"width": 800, "depth": 600, "outline": "an L-shaped room"},
            "prompt": "a big hall", "room_type": "hall", "a_room_type": "a hall",
            "assets": objects, "group": objects, "placed": objects, "objects": objects,
            "moved": lines, "formations": lines, "words": lines, "rules": lines,
            "questions": (0..n).map(question).collect::<Vec<_>>(),
            "failed": (0..n).map(question).collect::<Vec<_>>(),
            "question": "Is chair-0 facing table-0?", "means": "m", "measured": "x",
            "against_wall": names, "movable": names, "has_image": true,
        })
    }

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
            .render_capped("t", &serde_json::json!({}), 5000, PROMPT_FUEL)
            .unwrap_err();
        assert!(e.contains("over 5000 bytes"), "{e}");
        let small = with_source("t", "  {{ 'ab' * 3 }}  ");
        assert_eq!(small.render("t", &serde_json::json!({})).unwrap(), "ababab");
        assert_eq!(
            small
                .render_capped("t", &serde_json::json!({}), 10, PROMPT_FUEL)
                .unwrap(),
            "ababab",
            "a text exactly at the cap (with the spaces) is kept"
        );
    }

    #[test]
    fn a_template_that_loops_without_writing_runs_out_of_fuel_quickly() {
        // Ten billion steps that write nothing: the size cap never bites.
        let p = with_source(
            "designer",
            "{% for i in range(100000) %}{% for j in range(100000) %}{% endfor %}{% endfor %}",
        );
        let t0 = std::time::Instant::now();
        let e = p.render("designer", &serde_json::json!({})).unwrap_err();
        assert!(
            e.starts_with(
                "prompt designer: the template ran out of fuel (more than 20000000 steps)"
            ),
            "{e}"
        );
        assert!(
            t0.elapsed() < std::time::Duration::from_secs(30),
            "{:?}",
            t0.elapsed()
        );
        let e = p
            .render_capped("designer", &serde_json::json!({}), MAX_PROMPT_BYTES, 1000)
            .unwrap_err();
        assert!(e.contains("more than 1000 steps"), "{e}");
    }

    #[test]
    fn the_built_in_templates_of_a_big_room_stay_far_from_the_fuel_limit() {
        let ctx = big_context(500);
        for (name, _) in BUILTIN {
            Prompts::default()
                .render_capped(name, &ctx, MAX_PROMPT_BYTES, PROMPT_FUEL / 100)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
}
