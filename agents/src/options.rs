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
        Some(key) => Err(unknown_option(key, known)),
        None => Ok(()),
    }
}

/// The refusal of option `key`: the known names, and the nearest one when it looks like a typo.
pub fn unknown_option(key: &str, known: &[&str]) -> String {
    let known_list = if known.is_empty() {
        "this implementation takes no options".to_string()
    } else {
        format!("known: {}", known.join(", "))
    };
    format!(
        "unknown option {key:?}; {known_list}{}",
        did_you_mean(key, known)
    )
}

/// The candidate nearest to `word` when it is close enough to be a typo of it (a letter or two
/// wrong, missing, extra or swapped), else `None`.
pub fn closest<'a, S: AsRef<str>>(word: &str, candidates: &'a [S]) -> Option<&'a str> {
    let allowed = (word.chars().count() / 3).max(1);
    candidates
        .iter()
        .map(|c| (strsim::damerau_levenshtein(word, c.as_ref()), c.as_ref()))
        .filter(|(d, c)| *d <= allowed && *c != word)
        .min_by_key(|(d, _)| *d)
        .map(|(_, c)| c)
}

/// `"; did you mean NAME?"` for the candidate nearest to `word`, or an empty string.
pub fn did_you_mean<S: AsRef<str>>(word: &str, candidates: &[S]) -> String {
    closest(word, candidates)
        .map(|c| format!("; did you mean {c}?"))
        .unwrap_or_default()
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

    #[test]
    fn typos_get_the_nearest_name_and_strangers_none() {
        assert_eq!(
            closest("desinger", &["planner", "designer"]),
            Some("designer")
        );
        assert_eq!(
            closest("max_roundz", &["max_rounds", "final_prt"]),
            Some("max_rounds")
        );
        assert_eq!(closest("bogus", &["seed", "shift_cm", "turn_deg"]), None);
        let t: toml::Table = toml::from_str("sede = 1").unwrap();
        let e = only_known(&t, &["seed", "shift_cm"]).unwrap_err();
        assert_eq!(
            e,
            "unknown option \"sede\"; known: seed, shift_cm; did you mean seed?"
        );
        let e = only_known(&t, &[]).unwrap_err();
        assert!(e.contains("takes no options"), "{e}");
    }
}
