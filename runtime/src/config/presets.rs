//! The agent graphs shipped in `config/*.toml`, built into the binary: an installed `disco` has
//! them without the source tree (`--config local-llm`, `disco config show local-llm`).

use disco_agents::options::did_you_mean;

/// One built-in agent graph.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Preset {
    /// Its name: the file stem in `config/`.
    pub name: &'static str,
    /// The TOML text, comments and all.
    pub text: &'static str,
}

/// Every preset, the default first.
pub const PRESETS: &[Preset] = &[
    Preset {
        name: "default",
        text: super::DEFAULT_TOML,
    },
    Preset {
        name: "local-llm",
        text: include_str!("../../../config/local-llm.toml"),
    },
    Preset {
        name: "ollama",
        text: include_str!("../../../config/ollama.toml"),
    },
    Preset {
        name: "openai",
        text: include_str!("../../../config/openai.toml"),
    },
    Preset {
        name: "vllm",
        text: include_str!("../../../config/vllm.toml"),
    },
];

impl Preset {
    /// The preset named `name` (a trailing `.toml` is allowed).
    pub fn named(name: &str) -> Option<Preset> {
        let name = name.strip_suffix(".toml").unwrap_or(name);
        PRESETS.iter().copied().find(|p| p.name == name)
    }

    /// The preset named `name`, or why not: the known names and the nearest one.
    pub fn lookup(name: &str) -> Result<Preset, String> {
        Preset::named(name).ok_or_else(|| {
            let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
            format!(
                "no built-in agent graph named {name:?}; known: {}{}",
                names.join(", "),
                did_you_mean(name, &names)
            )
        })
    }

    /// What it is for, in one line: the first line of its opening comment.
    pub fn description(&self) -> &'static str {
        self.text
            .lines()
            .find_map(|l| l.strip_prefix('#'))
            .map(|l| l.trim().trim_end_matches(':'))
            .unwrap_or("")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::GraphConfig;
    use std::path::Path;

    #[test]
    fn every_preset_loads_and_says_what_it_is() {
        for p in PRESETS {
            GraphConfig::from_toml(Path::new(p.name), p.text, &[])
                .unwrap_or_else(|e| panic!("{}: {e}", p.name));
            assert!(
                p.description().len() > 20,
                "{}: {:?}",
                p.name,
                p.description()
            );
        }
        assert!(
            Preset::named("local-llm.toml")
                .unwrap()
                .description()
                .contains("llama.cpp")
        );
        let e = Preset::lookup("olama").unwrap_err();
        assert!(e.ends_with("did you mean ollama?"), "{e}");
    }

    #[test]
    fn a_preset_name_is_a_config_when_no_such_file_exists() {
        let g = GraphConfig::load(Some(Path::new("local-llm")), &[]).unwrap();
        assert!(g.models.contains_key("main"), "{:?}", g.models.keys());
        assert!(g.source.to_string_lossy().contains("local-llm (built in)"));
        let e = GraphConfig::load(Some(Path::new("no/such/graph.toml")), &[]).unwrap_err();
        assert!(e.to_string().contains("cannot read"), "{e}");
    }
}
