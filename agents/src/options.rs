//! Reading an agent's `options` table: numbers with defaults, and a refusal of unknown keys, so
//! every implementation reports a typo in the same words.

/// Number `key` of `options`, `default` when absent; it must be finite and at least `min`.
pub fn number(options: &toml::Table, key: &str, default: f64, min: f64) -> Result<f64, String> {
    match options.get(key) {
        None => Ok(default),
        Some(v) => v
            .as_float()
            .or_else(|| v.as_integer().map(|i| i as f64))
            .filter(|x| x.is_finite() && *x >= min)
            .ok_or_else(|| format!("options.{key} must be a number of at least {min}")),
    }
}

/// Refuses any key of `options` not in `known`.
pub fn only_known(options: &toml::Table, known: &[&str]) -> Result<(), String> {
    match options.keys().find(|k| !known.contains(&k.as_str())) {
        Some(key) => Err(format!(
            "unknown option {key:?}; known: {}",
            known.join(", ")
        )),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_default_convert_and_refuse() {
        let t: toml::Table = toml::from_str("a = 3\nb = 2.5\nc = -1\nd = \"x\"").unwrap();
        assert_eq!(number(&t, "a", 0.0, 0.0), Ok(3.0));
        assert_eq!(number(&t, "b", 0.0, 0.0), Ok(2.5));
        assert_eq!(number(&t, "zz", 7.0, 0.0), Ok(7.0));
        assert!(number(&t, "c", 0.0, 0.0).unwrap_err().contains("options.c"));
        assert!(number(&t, "d", 0.0, 0.0).is_err());
        assert!(
            only_known(&t, &["a", "b", "c"])
                .unwrap_err()
                .contains("\"d\"")
        );
        assert!(only_known(&t, &["a", "b", "c", "d"]).is_ok());
    }
}
