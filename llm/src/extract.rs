//! Reading what a model meant: strip reasoning blocks and code fences, cut the JSON out of the
//! surrounding chatter, and map the names it used to the scene's.

use serde_json::Value;

/// The JSON value in a model's answer: `<think>...</think>` blocks and Markdown fences removed,
/// then the first complete JSON object or array. A value cut short (the model ran out of tokens)
/// is an error that says so.
pub fn extract_json(text: &str) -> Result<Value, String> {
    let mut t = text.to_string();
    for (open, close) in [("<think>", "</think>"), ("<reasoning>", "</reasoning>")] {
        while let Some(a) = t.find(open) {
            match t[a..].find(close) {
                Some(b) => t.replace_range(a..a + b + close.len(), ""),
                None => t.truncate(a),
            }
        }
    }
    let t = t.replace("```json", "```").replace("```JSON", "```");
    // Inside a fence, if there is one.
    let body = match t.split("```").nth(1) {
        Some(inner) if inner.contains(['{', '[']) => inner.to_string(),
        _ => t.clone(),
    };
    let start = body
        .find(['{', '['])
        .ok_or_else(|| format!("no JSON object in the answer: {}", preview(text)))?;
    let mut stream = serde_json::Deserializer::from_str(&body[start..]).into_iter::<Value>();
    match stream.next() {
        Some(Ok(v)) => Ok(v),
        Some(Err(e)) if e.is_eof() => Err(format!(
            "the JSON is cut short (the answer ended at {}); answer with the complete JSON",
            preview(&body[start..])
        )),
        Some(Err(e)) => Err(format!("the JSON is invalid: {e}")),
        None => Err(format!("no JSON object in the answer: {}", preview(text))),
    }
}

fn preview(s: &str) -> String {
    let s = s.trim();
    if s.chars().count() <= 120 {
        format!("{s:?}")
    } else {
        let tail: String = s
            .chars()
            .rev()
            .take(60)
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        let head: String = s.chars().take(60).collect();
        format!("{head:?} ... {tail:?}")
    }
}

/// Maps names a model wrote to the scene's names: exact, then ignoring case, spaces, dashes and
/// underscores, then the nearest (edit distance) among names not yet used. A name too far from
/// every candidate is refused: the model invented it.
#[derive(Debug, Clone)]
pub struct NameMap {
    names: Vec<String>,
    used: Vec<bool>,
}

fn squash(s: &str) -> String {
    s.chars()
        .filter(|c| c.is_alphanumeric())
        .flat_map(char::to_lowercase)
        .collect()
}

impl NameMap {
    /// A map onto `names`.
    pub fn new(names: impl IntoIterator<Item = String>) -> Self {
        let names: Vec<String> = names.into_iter().collect();
        let used = vec![false; names.len()];
        NameMap { names, used }
    }

    /// The scene name `written` stands for, marked used; `None` when it names nothing here or
    /// only names already used.
    pub fn take(&mut self, written: &str) -> Option<String> {
        let i = self.find(written)?;
        self.used[i] = true;
        Some(self.names[i].clone())
    }

    /// The scene name `written` stands for, without marking it (any name, used or not).
    pub fn resolve(&self, written: &str) -> Option<String> {
        if let Some(i) = self.names.iter().position(|n| n == written) {
            return Some(self.names[i].clone());
        }
        let w = squash(written);
        self.names.iter().find(|n| squash(n) == w).cloned()
    }

    fn find(&self, written: &str) -> Option<usize> {
        let free = |i: &usize| !self.used[*i];
        if let Some(i) = (0..self.names.len())
            .filter(free)
            .find(|&i| self.names[i] == written)
        {
            return Some(i);
        }
        let w = squash(written);
        if w.is_empty() {
            return None;
        }
        if let Some(i) = (0..self.names.len())
            .filter(free)
            .find(|&i| squash(&self.names[i]) == w)
        {
            return Some(i);
        }
        // An exact name already used is a duplicate, not a near miss.
        if self.names.iter().any(|n| squash(n) == w) {
            return None;
        }
        (0..self.names.len())
            .filter(free)
            .map(|i| (strsim::levenshtein(&squash(&self.names[i]), &w), i))
            .filter(|(d, i)| *d <= (squash(&self.names[*i]).len() / 4).max(1))
            .min()
            .map(|(_, i)| i)
    }

    /// Names never taken.
    pub fn missing(&self) -> Vec<String> {
        (0..self.names.len())
            .filter(|&i| !self.used[i])
            .map(|i| self.names[i].clone())
            .collect()
    }
}

/// A number from a JSON value: a number, or a string holding one ("120", "120cm"); `None`
/// for anything else or a non-finite result.
pub fn number(v: &Value) -> Option<f64> {
    let x = match v {
        Value::Number(n) => n.as_f64()?,
        Value::String(s) => s
            .trim()
            .trim_end_matches("cm")
            .trim_end_matches('°')
            .trim()
            .parse()
            .ok()?,
        _ => return None,
    };
    x.is_finite().then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn json_out_of_chatter() {
        assert_eq!(
            extract_json("<think>hmm {not this}</think>Sure! ```json\n{\"a\": 1}\n``` done")
                .unwrap(),
            json!({"a": 1})
        );
        assert_eq!(
            extract_json("Here: {\"a\": [1, 2]} and more {\"b\": 2}").unwrap(),
            json!({"a": [1, 2]})
        );
        assert!(
            extract_json("{\"objects\": [{\"name\": \"bed")
                .unwrap_err()
                .contains("cut short")
        );
        assert!(
            extract_json("I cannot do that.")
                .unwrap_err()
                .contains("no JSON")
        );
        assert!(
            extract_json("{\"a\": 1,, }")
                .unwrap_err()
                .contains("invalid")
        );
    }

    #[test]
    fn names_exact_then_loose_then_near_and_no_inventions() {
        let mut m = NameMap::new(["bed-0", "nightstand-0", "nightstand-1"].map(String::from));
        assert_eq!(m.take("Bed 0").as_deref(), Some("bed-0"));
        assert_eq!(m.take("bed-0"), None, "a duplicate is refused");
        assert_eq!(m.take("nightstand-0").as_deref(), Some("nightstand-0"));
        assert_eq!(m.take("nighstand-1").as_deref(), Some("nightstand-1"));
        assert_eq!(m.take("wardrobe-0"), None, "an invented object is refused");
        assert!(m.missing().is_empty());
    }

    #[test]
    fn numbers_leniently() {
        assert_eq!(number(&json!(12.5)), Some(12.5));
        assert_eq!(number(&json!("120cm")), Some(120.0));
        assert_eq!(number(&json!("NaN")), None);
        assert_eq!(number(&json!(null)), None);
    }
}
