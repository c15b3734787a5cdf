//! Agent graphs in TOML: which implementation plays each role, with which model, prompt, deadline,
//! retries and fallback; the stages of each refinement round; and the run's settings.
//!
//! Every mistake is reported with the file, the line and the dotted key (or the `--set` argument
//! it was typed in), with the nearest known name when it looks like a typo. Any value can be
//! overridden for one run with `--set dotted.key=value`.
//!
//! The graph is checked once, where it is read, and kept typed: each agent under its [`AgentId`]
//! with its role settled ([`Agent`]), and the round as [`Stage`]s whose agents exist and play
//! the role their stage needs. Nothing downstream reads a name twice or asks what role an agent
//! plays.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use disco_agents::options::did_you_mean;
use disco_core::error::{Error, Result};
use disco_core::roles::RoleKind;

/// The built-in default graph (offline rule-based agents), also shipped as `config/default.toml`.
pub const DEFAULT_TOML: &str = include_str!("../../config/default.toml");

/// Settings of one run.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RunSettings {
    /// Evaluate-and-refine rounds per group at most.
    pub max_rounds: u32,
    /// Run the PRT once more over the whole layout at the end, so the result is always valid.
    pub final_prt: bool,
    /// Grid step of the PRT, in cm.
    pub grid_step_cm: f64,
    /// Deadline for a whole scene, in seconds.
    pub scene_deadline_s: f64,
    /// Restarts allowed per role within `restart_window_s` before the role counts as broken.
    pub max_restarts: u32,
    /// The window for `max_restarts`, in seconds.
    pub restart_window_s: f64,
    /// First retry delay, in milliseconds (doubling per retry).
    pub backoff_ms: u64,
    /// Record/replay folder for model answers (`--cache DIR`); none by default.
    pub cache: Option<String>,
    /// Design the whole room in one designer call (the plan's groups merged into one), the way
    /// single-shot methods such as LayoutGPT work; `false` designs group by group.
    pub single_shot: bool,
}

impl Default for RunSettings {
    fn default() -> Self {
        RunSettings {
            max_rounds: 3,
            final_prt: true,
            grid_step_cm: 5.0,
            scene_deadline_s: 600.0,
            max_restarts: 3,
            restart_window_s: 60.0,
            backoff_ms: 20,
            cache: None,
            single_shot: false,
        }
    }
}

/// `[pipeline]` as written: the stages of each evaluate-and-refine round, after the designer has
/// posed a group. Read into [`GraphConfig::round`] as [`Stage`]s.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct PipelineConfig {
    /// Stage names in order: `evaluate` first, then agents of role srt, prt or patch.
    round: Vec<String>,
}

impl Default for PipelineConfig {
    fn default() -> Self {
        PipelineConfig {
            round: vec!["evaluate".into(), "srt".into(), "prt".into()],
        }
    }
}

/// How the evaluator's questions go out.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EvalModeConfig {
    /// One call per question, `width` at once.
    #[default]
    Parallel,
    /// All questions in one call.
    Batch,
}

/// The evaluator's kind of questions.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum QuestionStyle {
    /// One yes/no question per constraint (the paper's method).
    #[default]
    Structured,
    /// One open question about the whole layout (the paper's ablation).
    Open,
}

/// When a custom (patch) stage runs within a round.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum When {
    /// Every round.
    #[default]
    Always,
    /// When some question was answered "no".
    SemanticFailed,
    /// When the evaluator asked for physical refinement.
    PhysicalFailed,
}

/// One `[agents.NAME]` section, as written; the graph keeps it in an [`Agent`], whose role is
/// settled.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AgentConfig {
    /// The role as written; implied for `planner`, `designer`, `evaluator`, `srt` and `prt`
    /// (then `None` here). [`Agent::role`] is the agent's role either way.
    #[serde(default)]
    pub role: Option<RoleKind>,
    /// The implementation's registered name, e.g. `rules`, `vlm`, `grid`.
    #[serde(rename = "impl")]
    pub implementation: Spanned<String>,
    /// The model server (a key of `[models]`), for model-backed implementations.
    #[serde(default)]
    pub model: Option<Spanned<String>>,
    /// A prompt template file, relative to the config file (overrides the built-in prompt).
    #[serde(default)]
    pub prompt: Option<Spanned<String>>,
    /// Deadline of one call, in seconds.
    #[serde(default = "default_deadline")]
    pub deadline_s: f64,
    /// Retries after a failed call before the fallback takes over.
    #[serde(default = "default_retries")]
    pub retries: u32,
    /// Implementation to swap in once retries are exhausted.
    #[serde(default)]
    pub fallback: Option<Spanned<String>>,
    /// Evaluator only: parallel or batched questions.
    #[serde(default)]
    pub mode: EvalModeConfig,
    /// Evaluator only: questions in flight at once.
    #[serde(default = "default_width")]
    pub width: usize,
    /// Evaluator only: structured or open questions.
    #[serde(default)]
    pub questions: QuestionStyle,
    /// Patch stages only: when to run.
    #[serde(default)]
    pub when: When,
    /// `impl = "process"` only: the program and its arguments, e.g.
    /// `["python3", "examples/agents/designer.py"]` (see docs/protocol/README.md).
    #[serde(default)]
    pub command: Option<Vec<String>>,
    /// `impl = "http"` only: the address the requests are POSTed to.
    #[serde(default)]
    pub url: Option<String>,
    /// `impl = "process"` and `"http"`: the longest reply read from the agent, in bytes (default
    /// 8 MiB, like a model answer; 1 KiB to 256 MiB). A longer reply is an unusable answer.
    #[serde(default = "default_max_reply_bytes")]
    pub max_reply_bytes: usize,
    /// Implementation-specific settings.
    #[serde(default)]
    pub options: toml::Table,
}

fn default_deadline() -> f64 {
    60.0
}
fn default_max_reply_bytes() -> usize {
    crate::external::capped::MAX_REPLY_BYTES
}
fn default_retries() -> u32 {
    2
}
fn default_width() -> usize {
    8
}

impl AgentConfig {
    /// The implementation's name.
    pub fn impl_name(&self) -> &str {
        self.implementation.get_ref()
    }
}

pub use disco_llm::ModelConfig;

mod agent_id;
mod overrides;
mod presets;
pub use agent_id::{Agent, AgentId, Stage};
pub use overrides::Override;
pub use presets::{PRESETS, Preset};

/// The bounds of the graph's numbers: every deadline, window and timeout must make a
/// `Duration` and every count must stay small enough to run, whatever a file or `--set` says.
pub mod bounds {
    /// The longest deadline, restart window or timeout, in seconds: one day.
    pub const MAX_SECONDS: f64 = 86_400.0;
    /// Restarts per role within the restart window at most.
    pub const MAX_RESTARTS: u64 = 1_000;
    /// Retries of one call at most.
    pub const MAX_RETRIES: u64 = 100;
    /// The longest first back-off delay, in milliseconds: one minute.
    pub const MAX_BACKOFF_MS: u64 = 60_000;
    /// Questions (or model requests) in flight at once at most.
    pub const MAX_WIDTH: u64 = 1_024;
    /// The slowest request rate, per second (one request every 1,000 s).
    pub const MIN_RATE_PER_S: f64 = 0.001;
    /// The fastest request rate, per second.
    pub const MAX_RATE_PER_S: f64 = 100_000.0;
    /// The largest `max_tokens` of a model answer.
    pub const MAX_TOKENS: u64 = 10_000_000;
}

/// The names of the method's own agents, whose role their name implies.
pub const ROLE_AGENTS: [&str; 5] = ["planner", "designer", "evaluator", "srt", "prt"];

/// A whole agent graph, checked: made only by [`GraphConfig::load`] and
/// [`GraphConfig::from_toml`], so its agents and round always agree (every stage names an agent
/// of the role it needs; the planner and designer exist; so do the evaluator when the round
/// evaluates and the PRT when `run.final_prt` is on).
#[derive(Debug, Clone, PartialEq)]
pub struct GraphConfig {
    /// Run settings.
    pub run: RunSettings,
    /// Agents by id, each with its role settled.
    pub(crate) agents: BTreeMap<AgentId, Agent>,
    /// The stages of each round: empty, or [`Stage::Evaluate`] first.
    pub(crate) round: Vec<Stage>,
    /// Model servers by name.
    pub models: BTreeMap<String, ModelConfig>,
    /// The model that scores layouts (`disco judge`, `disco bench --judge`); not part of the
    /// pipeline.
    pub judge: JudgeConfig,
    /// Where the graph came from (for messages and relative prompt paths).
    pub source: PathBuf,
    /// The text it was read from, after `--set` overrides (for line numbers).
    pub text: String,
    /// The `--set` overrides applied, so that their mistakes are reported at them.
    pub overrides: Vec<Override>,
}

/// A graph file as written, before it is checked into a [`GraphConfig`].
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct GraphFile {
    #[serde(default)]
    run: RunSettings,
    #[serde(default)]
    pipeline: PipelineConfig,
    #[serde(default)]
    agents: BTreeMap<String, AgentConfig>,
    #[serde(default)]
    models: BTreeMap<String, ModelConfig>,
    #[serde(default)]
    judge: JudgeConfig,
}

/// `[judge]`: which model scores layouts, and with which prompt. Without a model the designer's
/// model judges, else the graph's only model.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JudgeConfig {
    /// A `[models.NAME]` section.
    pub model: Option<Spanned<String>>,
    /// A prompt template replacing the built-in `judge` one (relative to the graph file).
    pub prompt: Option<Spanned<String>>,
}

/// The role a built-in agent name implies.
pub fn implied_role(name: &str) -> Option<RoleKind> {
    Some(match name {
        "planner" => RoleKind::Planner,
        "designer" => RoleKind::Designer,
        "evaluator" => RoleKind::Evaluator,
        "srt" => RoleKind::Srt,
        "prt" => RoleKind::Prt,
        _ => return None,
    })
}

impl GraphConfig {
    /// The chat client of model `name`. A model section that cannot work (its key variable unset,
    /// no base URL) is an input error naming this file and `models.NAME`; other failures are
    /// model errors.
    pub fn model_client(
        &self,
        name: &str,
        gateway: Option<std::sync::Arc<disco_llm::ModelGateway>>,
        cache: Option<std::sync::Arc<disco_llm::Cache>>,
    ) -> Result<disco_llm::ChatClient> {
        let Some(config) = self.models.get(name) else {
            return Err(Error::invalid(
                &self.source,
                format!("models.{name}"),
                "no such model section",
            ));
        };
        disco_llm::ChatClient::from_config(name, config, gateway, cache).map_err(|e| match e {
            disco_llm::LlmError::Config(reason) => {
                let field = format!("models.{name}");
                let reason = reason
                    .strip_prefix(&format!("{field}: "))
                    .unwrap_or(&reason);
                Error::invalid(&self.source, field, reason)
            }
            other => Error::Model {
                name: name.to_string(),
                reason: other.to_string(),
            },
        })
    }

    /// Reads a graph from `path` (or the built-in default), applying `--set key=value` overrides.
    /// A `path` that is no file but a preset's name (`local-llm`) reads that [`Preset`].
    /// Only the syntax and the shape are checked here; the registry (`Registry::check`)
    /// checks implementation names.
    pub fn load(path: Option<&Path>, sets: &[String]) -> Result<Self> {
        let preset = path
            .filter(|p| !p.exists() && p.components().count() == 1)
            .and_then(|p| Preset::named(p.to_str()?));
        if let Some(preset) = preset {
            let source = PathBuf::from(format!("{} (built in)", preset.name));
            return Self::from_toml(&source, preset.text, sets);
        }
        let (source, text) = match path {
            Some(p) => (p.to_path_buf(), disco_core::io::read_text(p)?),
            None => (
                PathBuf::from("config/default.toml (built in)"),
                DEFAULT_TOML.to_string(),
            ),
        };
        Self::from_toml(&source, &text, sets)
    }

    /// Parses a graph from `text` (labelled `source`), applying overrides.
    pub fn from_toml(source: &Path, text: &str, sets: &[String]) -> Result<Self> {
        let (text, overrides) = overrides::apply(source, text, sets)?;
        let file: GraphFile = toml::from_str(&text).map_err(|e| {
            // The parser's message may hold the offending value itself: cut it too.
            let reason = quoted(&with_suggestion(e.message().trim()), 2 * QUOTED_CHARS);
            let Some(at) = e.span().map(|s| locate(&text, s.start)) else {
                return Error::invalid(source, "(document)", reason);
            };
            match at
                .key
                .as_deref()
                .and_then(|k| overrides::origin(&overrides, k))
            {
                Some(o) => Error::invalid(&o.label(), &o.key, reason),
                None => Error::invalid(source, at.describe(), reason),
            }
        })?;
        let mut graph = GraphConfig {
            run: file.run,
            agents: BTreeMap::new(),
            round: Vec::new(),
            models: file.models,
            judge: file.judge,
            source: source.to_path_buf(),
            text,
            overrides,
        };
        graph.check_run()?;
        graph.check_models()?;
        for (name, config) in file.agents {
            let role = graph.check_agent(&name, &config)?;
            let id = AgentId::new(name);
            graph
                .agents
                .insert(id.clone(), Agent::new(id, role, config));
        }
        graph.check_required_agents()?;
        graph.check_model_and_prompt("judge", &graph.judge.model, &graph.judge.prompt)?;
        graph.round = graph.stages(&file.pipeline.round)?;
        Ok(graph)
    }

    /// The agents, by id.
    pub fn agents(&self) -> &BTreeMap<AgentId, Agent> {
        &self.agents
    }

    /// Agent `id`, if the graph has it.
    pub fn agent(&self, id: &AgentId) -> Option<&Agent> {
        self.agents.get(id)
    }

    /// The stages of each evaluate-and-refine round, in order: empty (no rounds), or
    /// [`Stage::Evaluate`] first and then refinement stages.
    pub fn round(&self) -> &[Stage] {
        &self.round
    }

    /// An error about `key` (dotted): at the `--set` argument that typed it, else at its line
    /// (`span`) when known.
    pub fn error_at(&self, span: Option<usize>, key: &str, reason: impl Into<String>) -> Error {
        if let Some(o) = overrides::origin(&self.overrides, key) {
            return Error::invalid(&o.label(), key, reason);
        }
        let field = match span {
            Some(s) => format!("line {}, {key}", locate(&self.text, s).line_no),
            None => key.to_string(),
        };
        Error::invalid(&self.source, field, reason)
    }

    /// Resolves a prompt path relative to the config file's folder.
    pub fn resolve_path(&self, p: &str) -> PathBuf {
        let p = Path::new(p);
        if p.is_absolute() {
            return p.to_path_buf();
        }
        let beside = self.source.parent().map(|d| d.join(p));
        match beside {
            Some(b) if b.exists() => b,
            _ => p.to_path_buf(),
        }
    }

    /// An error about `key`, located at its line when it is written out.
    fn bad(&self, key: &str, why: &str) -> Error {
        self.error_at(self.find(key), key, why.to_string())
    }

    /// `[run]`: bounds of the rounds, the grid step, the deadlines, restarts and back-off.
    fn check_run(&self) -> Result<()> {
        let r = &self.run;
        if r.max_rounds > 20 {
            return Err(self.bad("run.max_rounds", "must be at most 20"));
        }
        if !(r.grid_step_cm.is_finite() && r.grid_step_cm >= 0.5 && r.grid_step_cm <= 100.0) {
            return Err(self.bad("run.grid_step_cm", "must be between 0.5 and 100 cm"));
        }
        self.check_seconds("run.scene_deadline_s", r.scene_deadline_s, false)?;
        self.check_seconds("run.restart_window_s", r.restart_window_s, true)?;
        self.check_count(
            "run.max_restarts",
            r.max_restarts as f64,
            0,
            bounds::MAX_RESTARTS,
        )?;
        self.check_count(
            "run.backoff_ms",
            r.backoff_ms as f64,
            0,
            bounds::MAX_BACKOFF_MS,
        )
    }

    /// A number of seconds: finite, positive (or zero when `zero_ok`) and at most
    /// [`bounds::MAX_SECONDS`] (one day), so that it always makes a `Duration`.
    fn check_seconds(&self, key: &str, v: f64, zero_ok: bool) -> Result<()> {
        let low_ok = if zero_ok { v >= 0.0 } else { v > 0.0 };
        if v.is_finite() && low_ok && v <= bounds::MAX_SECONDS {
            return Ok(());
        }
        let low = if zero_ok { "0" } else { "more than 0" };
        Err(self.bad(
            key,
            &format!(
                "must be {low} and at most {} seconds (1 day), got {v}",
                bounds::MAX_SECONDS
            ),
        ))
    }

    /// A whole number between `min` and `max`.
    fn check_count(&self, key: &str, v: f64, min: u64, max: u64) -> Result<()> {
        if v.is_finite() && v >= min as f64 && v <= max as f64 {
            return Ok(());
        }
        Err(self.bad(key, &format!("must be between {min} and {max}, got {v}")))
    }

    /// `[models.NAME]`: requests in flight and per second, and the numbers of `options` that
    /// become durations and counts (timeouts, retries, back-off).
    fn check_models(&self) -> Result<()> {
        for (name, m) in &self.models {
            let key = |k: &str| format!("models.{name}.{k}");
            self.check_count(
                &key("max_in_flight"),
                m.max_in_flight as f64,
                1,
                bounds::MAX_WIDTH,
            )?;
            if let Some(rate) = m.rate_per_s
                && !(bounds::MIN_RATE_PER_S..=bounds::MAX_RATE_PER_S).contains(&rate)
            {
                return Err(self.bad(
                    &key("rate_per_s"),
                    &format!(
                        "must be between {} and {} requests per second, got {rate}",
                        bounds::MIN_RATE_PER_S,
                        bounds::MAX_RATE_PER_S
                    ),
                ));
            }
            for (option, value) in &m.options {
                let Some(v) = value
                    .as_float()
                    .or_else(|| value.as_integer().map(|i| i as f64))
                else {
                    continue; // not a number: the client's own check names it
                };
                let at = key(&format!("options.{option}"));
                match option.as_str() {
                    "timeout_s" | "max_retry_after_s" => self.check_seconds(&at, v, true)?,
                    "retries" => self.check_count(&at, v, 0, bounds::MAX_RETRIES)?,
                    "backoff_ms" => self.check_count(&at, v, 0, bounds::MAX_BACKOFF_MS)?,
                    "max_tokens" => self.check_count(&at, v, 1, bounds::MAX_TOKENS)?,
                    _ => {}
                }
            }
        }
        Ok(())
    }

    /// One `[agents.NAME]`: its role, deadline, width, model and prompt file. Returns its role.
    fn check_agent(&self, name: &str, a: &AgentConfig) -> Result<RoleKind> {
        let key = |k: &str| format!("agents.{name}.{k}");
        let role = a.role.or_else(|| implied_role(name)).ok_or_else(|| {
            let needs = "a custom agent needs `role = \"patch\"` (or planner, designer, evaluator, srt, prt)";
            let reason = match did_you_mean(name, &ROLE_AGENTS) {
                typo if typo.is_empty() => needs.to_string(),
                typo => format!("no agent of the method is named {name:?}{typo} ({needs})"),
            };
            self.error_at(Some(a.implementation.span().start), &key("role"), reason)
        })?;
        if let (Some(given), Some(implied)) = (a.role, implied_role(name))
            && given != implied
        {
            return Err(self.bad(
                &key("role"),
                &format!("the {name} agent must have role {implied}"),
            ));
        }
        self.check_seconds(&key("deadline_s"), a.deadline_s, false)?;
        self.check_count(&key("retries"), a.retries as f64, 0, bounds::MAX_RETRIES)?;
        self.check_count(&key("width"), a.width as f64, 1, bounds::MAX_WIDTH)?;
        {
            use crate::external::capped::{MAX_REPLY_CAP, MIN_REPLY_CAP, shown};
            if !(MIN_REPLY_CAP..=MAX_REPLY_CAP).contains(&a.max_reply_bytes) {
                let why = format!(
                    "must be between {MIN_REPLY_CAP} and {MAX_REPLY_CAP} bytes ({} to {})",
                    shown(MIN_REPLY_CAP),
                    shown(MAX_REPLY_CAP)
                );
                return Err(self.bad(&key("max_reply_bytes"), &why));
            }
        }
        self.check_model_and_prompt(&format!("agents.{name}"), &a.model, &a.prompt)?;
        Ok(role)
    }

    /// The `model` and `prompt` keys of the section `section`: the model has a `[models.NAME]`
    /// section and the prompt file exists.
    fn check_model_and_prompt(
        &self,
        section: &str,
        model: &Option<Spanned<String>>,
        prompt: &Option<Spanned<String>>,
    ) -> Result<()> {
        let key = |k: &str| format!("{section}.{k}");
        if let Some(m) = model
            && !self.models.contains_key(m.get_ref())
        {
            return Err(self.error_at(
                Some(m.span().start),
                &key("model"),
                format!(
                    "no [models.{}] section{}",
                    m.get_ref(),
                    did_you_mean(m.get_ref(), &self.models.keys().collect::<Vec<_>>())
                ),
            ));
        }
        if let Some(p) = prompt {
            let path = self.resolve_path(p.get_ref());
            if !path.is_file() {
                return Err(self.error_at(
                    Some(p.span().start),
                    &key("prompt"),
                    format!("prompt file {} not found", path.display()),
                ));
            }
        }
        Ok(())
    }

    /// Every graph needs a planner and a designer, and a PRT when the final pass is on.
    fn check_required_agents(&self) -> Result<()> {
        for need in ["planner", "designer"] {
            if !self.agents.contains_key(need) {
                return Err(Error::invalid(
                    &self.source,
                    format!("agents.{need}"),
                    "missing: every graph needs one",
                ));
            }
        }
        if self.run.final_prt && !self.agents.contains_key("prt") {
            return Err(Error::invalid(
                &self.source,
                "agents.prt",
                "missing, but run.final_prt = true needs it",
            ));
        }
        Ok(())
    }

    /// `[pipeline] round` as [`Stage`]s: `evaluate` first, then agents of role srt, prt or
    /// patch (each with its `when`).
    fn stages(&self, round: &[String]) -> Result<Vec<Stage>> {
        let mut stages = Vec::with_capacity(round.len());
        for (i, stage) in round.iter().enumerate() {
            let key = format!("pipeline.round[{i}]");
            if stage == "evaluate" {
                if i != 0 {
                    return Err(self.bad(&key, "`evaluate` must be the first stage of a round"));
                }
                if !self.agents.contains_key("evaluator") {
                    return Err(self.bad(&key, "`evaluate` needs an [agents.evaluator]"));
                }
                stages.push(Stage::Evaluate);
                continue;
            }
            let typed = match self.agents.get(stage.as_str()) {
                Some(agent) => match agent.role() {
                    RoleKind::Srt => Stage::Srt(agent.id().clone()),
                    RoleKind::Prt => Stage::Prt(agent.id().clone()),
                    RoleKind::Patch => Stage::Patch {
                        agent: agent.id().clone(),
                        when: agent.config().when,
                    },
                    other => {
                        return Err(self.bad(
                            &key,
                            &format!(
                                "{stage:?} is a {other}; a round holds srt, prt and patch agents"
                            ),
                        ));
                    }
                },
                None => {
                    let names: Vec<&str> = self.agents.keys().map(AgentId::as_str).collect();
                    let typo = match ROLE_AGENTS.contains(&stage.as_str()) {
                        true => String::new(), // missing, not misspelt
                        false => did_you_mean(stage, &names),
                    };
                    return Err(
                        self.bad(&key, &format!("no agent named {stage:?} in [agents]{typo}"))
                    );
                }
            };
            if round.first().map(String::as_str) != Some("evaluate") {
                return Err(self.bad(&key, "refinement stages need `evaluate` first in the round"));
            }
            stages.push(typed);
        }
        Ok(stages)
    }

    /// The byte offset of a dotted key's line (`key = ...` under `[table]`), if it is written out.
    pub(crate) fn find(&self, dotted: &str) -> Option<usize> {
        let (table, key) = dotted.rsplit_once('.')?;
        let key = key.split('[').next()?;
        let header = format!("[{table}]");
        let mut in_table = false;
        let mut offset = 0;
        for line in self.text.split_inclusive('\n') {
            let t = line.trim();
            if t.starts_with('[') {
                in_table = t == header;
            } else if in_table && t.split('=').next().map(str::trim) == Some(key) {
                return Some(offset);
            }
            offset += line.len();
        }
        None
    }
}

/// Where a byte offset of the graph's text falls.
struct Location {
    /// The line, from 1.
    line_no: usize,
    /// That line's text, trimmed.
    line: String,
    /// The dotted key of a `key = ...` line (`table.key`), if it is one.
    key: Option<String>,
}

impl Location {
    /// `line N, table.key (`text`)`, or `line N (`text`)` for a header or a stray line.
    fn describe(&self) -> String {
        match &self.key {
            Some(key) => format!("line {}, {key} (`{}`)", self.line_no, self.line),
            None => format!("line {} (`{}`)", self.line_no, self.line),
        }
    }
}

/// The line of byte `offset` of `text`, and its dotted key.
fn locate(text: &str, offset: usize) -> Location {
    let offset = offset.min(text.len());
    let line_no = text[..offset].matches('\n').count() + 1;
    let full = text.lines().nth(line_no - 1).unwrap_or("").trim();
    let line = quoted(full, QUOTED_CHARS);
    let key = full.split('=').next().unwrap_or("").trim();
    let key = key.chars().take(QUOTED_CHARS).collect::<String>();
    let key = key.as_str();
    let key = (!key.is_empty() && !line.starts_with('[')).then(|| dotted_key(text, line_no, key));
    Location { line_no, line, key }
}

/// The most characters of a line an error quotes: a 10 MB line is cut, not repeated.
const QUOTED_CHARS: usize = 200;

/// `line` as an error quotes it: at most `max` characters, then how many more.
fn quoted(line: &str, max: usize) -> String {
    let total = line.chars().count();
    if total <= max {
        return line.to_string();
    }
    let head: String = line.chars().take(max).collect();
    format!("{head}... ({} more characters)", total - max)
}

/// Serde's "unknown field `x`, expected one of `a`, `b`" (or variant), with the nearest expected
/// name when `x` looks like a typo of it.
fn with_suggestion(message: &str) -> String {
    let rest = message
        .strip_prefix("unknown field `")
        .or_else(|| message.strip_prefix("unknown variant `"));
    let Some((word, expected)) = rest.and_then(|r| r.split_once('`')) else {
        return message.to_string();
    };
    let expected: Vec<&str> = expected.split('`').skip(1).step_by(2).collect();
    format!("{message}{}", did_you_mean(word, &expected))
}

/// `table.key` for a `key = ...` line, from the nearest `[table]` header above it.
fn dotted_key(text: &str, line_no: usize, key: &str) -> String {
    let header = text
        .lines()
        .take(line_no - 1)
        .filter_map(|l| {
            let t = l.trim();
            (t.starts_with('[') && t.ends_with(']'))
                .then(|| t.trim_matches(|c| c == '[' || c == ']').to_string())
        })
        .last();
    match header {
        Some(h) => format!("{h}.{key}"),
        None => key.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(text: &str) -> Result<GraphConfig> {
        GraphConfig::from_toml(Path::new("graph.toml"), text, &[])
    }

    #[test]
    fn the_default_graph_loads() {
        let g = GraphConfig::load(None, &[]).unwrap();
        assert_eq!(g.agents["designer"].config().impl_name(), "rules");
        assert_eq!(
            g.round(),
            [
                Stage::Evaluate,
                Stage::Srt(AgentId::SRT),
                Stage::Prt(AgentId::PRT)
            ]
        );
    }

    #[test]
    fn the_graph_is_read_once_into_typed_agents_and_stages() {
        let text = "[run]\nfinal_prt = false\n[pipeline]\nround = [\"evaluate\", \"tidy\", \"fix\", \"prt\"]\n[agents.planner]\nimpl = \"rules\"\n[agents.designer]\nimpl = \"rules\"\n[agents.evaluator]\nimpl = \"rules\"\n[agents.prt]\nimpl = \"grid\"\n[agents.tidy]\nrole = \"patch\"\nimpl = \"clearance\"\nwhen = \"physical_failed\"\n[agents.fix]\nrole = \"srt\"\nimpl = \"rules\"\n";
        let g = load(text).unwrap();
        let tidy = AgentId::new("tidy");
        assert_eq!(
            g.round(),
            [
                Stage::Evaluate,
                Stage::Patch {
                    agent: tidy.clone(),
                    when: When::PhysicalFailed
                },
                Stage::Srt(AgentId::new("fix")),
                Stage::Prt(AgentId::PRT),
            ]
        );
        let roles: Vec<(&str, RoleKind)> = g
            .agents()
            .iter()
            .map(|(id, a)| (id.as_str(), a.role()))
            .collect();
        use RoleKind::*;
        assert_eq!(
            roles,
            [
                ("designer", Designer),
                ("evaluator", Evaluator),
                ("fix", Srt),
                ("planner", Planner),
                ("prt", Prt),
                ("tidy", Patch),
            ]
        );
        let agent = g.agent(&tidy).unwrap();
        assert_eq!(
            (agent.id(), agent.config().impl_name()),
            (&tidy, "clearance")
        );
        assert_eq!(g.round()[1].agent(), Some(&tidy));
        assert!(g.agent(&AgentId::SRT).is_none());
        // Every reference is checked where the graph is read, at its line.
        let bad = |round: &str| {
            load(&text.replace(
                "round = [\"evaluate\", \"tidy\", \"fix\", \"prt\"]",
                &format!("round = {round}"),
            ))
            .unwrap_err()
            .to_string()
        };
        let e = bad("[\"evaluate\", \"designer\"]");
        assert!(
            e.contains("line 4, pipeline.round[1]: \"designer\" is a designer; a round holds srt, prt and patch agents"),
            "{e}"
        );
        let e = bad("[\"evaluate\", \"tidi\"]");
        assert!(
            e.ends_with(
                "pipeline.round[1]: no agent named \"tidi\" in [agents]; did you mean tidy?"
            ),
            "{e}"
        );
        let e = bad("[\"tidy\", \"evaluate\"]");
        assert!(
            e.ends_with("pipeline.round[0]: refinement stages need `evaluate` first in the round"),
            "{e}"
        );
        let e = bad("[\"evaluate\", \"evaluate\"]");
        assert!(
            e.ends_with("pipeline.round[1]: `evaluate` must be the first stage of a round"),
            "{e}"
        );
        let e = bad("[\"evaluate\", \"srt\"]");
        assert!(
            e.ends_with("pipeline.round[1]: no agent named \"srt\" in [agents]"),
            "{e}"
        );
        assert_eq!(
            load(&text.replace(
                "round = [\"evaluate\", \"tidy\", \"fix\", \"prt\"]",
                "round = []"
            ))
            .unwrap()
            .round(),
            []
        );
    }

    #[test]
    fn set_overrides_any_value() {
        let g = GraphConfig::load(
            None,
            &[
                "agents.designer.deadline_s=5".into(),
                "run.max_rounds=1".into(),
            ],
        )
        .unwrap();
        assert_eq!(g.agents["designer"].config().deadline_s, 5.0);
        assert_eq!(g.run.max_rounds, 1);
        let g = GraphConfig::load(None, &["agents.designer.impl=noisy".into()]).unwrap();
        assert_eq!(g.agents["designer"].config().impl_name(), "noisy");
    }

    #[test]
    fn a_typo_names_the_line_and_key() {
        let text = "[run]\nmax_rounds = 2\n\n[agents.planner]\nimpl = \"rules\"\ndeadlne_s = 3\n";
        let e = load(text).unwrap_err().to_string();
        assert!(
            e.starts_with("graph.toml: line 6, agents.planner.deadlne_s"),
            "{e}"
        );
        assert!(e.contains("unknown field `deadlne_s`"), "{e}");
    }

    #[test]
    fn a_bad_value_names_the_line_and_key() {
        let text = "[agents.planner]\nimpl = \"rules\"\n[agents.designer]\nimpl = \"rules\"\nwidth = \"wide\"\n";
        let e = load(text).unwrap_err().to_string();
        assert!(e.contains("line 5, agents.designer.width"), "{e}");
        let text = "[run]\nmax_rounds = 50\n[agents.planner]\nimpl = \"rules\"\n[agents.designer]\nimpl = \"rules\"\n";
        let e = load(text).unwrap_err().to_string();
        assert!(
            e.contains("line 2, run.max_rounds: must be at most 20"),
            "{e}"
        );
    }

    #[test]
    fn the_reply_cap_of_an_agent_is_bounded_where_it_is_read() {
        let load = |set: &str| GraphConfig::load(None, &[set.to_string()]);
        let g = load("agents.designer.max_reply_bytes=1048576").unwrap();
        assert_eq!(g.agents["designer"].config().max_reply_bytes, 1 << 20);
        let g = load("run.max_rounds=1").unwrap();
        assert_eq!(
            g.agents["designer"].config().max_reply_bytes,
            8 << 20,
            "the default"
        );
        for bad in ["0", "10", "1000000000000", "-1"] {
            let e = load(&format!("agents.designer.max_reply_bytes={bad}"))
                .unwrap_err()
                .to_string();
            assert!(e.contains("agents.designer.max_reply_bytes"), "{bad}: {e}");
        }
        let e = load("agents.designer.max_reply_bytes=10")
            .unwrap_err()
            .to_string();
        assert!(
            e.ends_with("must be between 1024 and 268435456 bytes (1 KiB to 256 MiB)"),
            "{e}"
        );
    }

    #[test]
    fn a_mistake_in_a_set_names_the_set_argument() {
        let e = |set: &str| {
            GraphConfig::load(None, &[set.to_string()])
                .unwrap_err()
                .to_string()
        };
        let typo = e("run.max_roundz=2");
        assert!(
            typo.starts_with("--set run.max_roundz=2: run.max_roundz: unknown field `max_roundz`"),
            "{typo}"
        );
        assert!(typo.ends_with("; did you mean max_rounds?"), "{typo}");
        assert!(!typo.contains("default.toml"), "{typo}");
        let bound = e("run.max_rounds=50");
        assert_eq!(
            bound,
            "--set run.max_rounds=50: run.max_rounds: must be at most 20"
        );
        let agent = e("agents.desinger.impl=noisy");
        assert!(
            agent.starts_with("--set agents.desinger.impl=noisy: agents.desinger.role: no agent of the method is named \"desinger\"; did you mean designer?"),
            "{agent}"
        );
        let variant = e("agents.evaluator.mode=paralel");
        assert!(
            variant.starts_with("--set agents.evaluator.mode=paralel: "),
            "{variant}"
        );
        assert!(variant.contains("did you mean parallel?"), "{variant}");
    }

    #[test]
    fn absurd_numbers_are_refused_with_the_allowed_range() {
        let e = |set: &str| {
            GraphConfig::load(None, &[set.to_string()])
                .unwrap_err()
                .to_string()
        };
        let deadline = e("agents.designer.deadline_s=1e300");
        assert!(
            deadline.starts_with("--set agents.designer.deadline_s=1e300: agents.designer.deadline_s: must be more than 0 and at most 86400 seconds (1 day)"),
            "{deadline}"
        );
        assert!(e("run.scene_deadline_s=1e300").contains("at most 86400 seconds"));
        assert!(e("run.scene_deadline_s=-1").contains("run.scene_deadline_s: must be"));
        assert!(e("run.restart_window_s=-5").contains("run.restart_window_s: must be 0"));
        assert!(e("run.restart_window_s=inf").contains("run.restart_window_s"));
        assert!(e("run.backoff_ms=99999999999").contains("between 0 and 60000"));
        assert!(e("run.max_restarts=4000000000").contains("between 0 and 1000"));
        assert!(e("agents.designer.retries=4000000000").contains("agents.designer.retries"));
        assert!(e("agents.evaluator.width=100000").contains("between 1 and 1024"));
        let model = |opt: &str| {
            let text = format!(
                "[run]\nfinal_prt = false\n[pipeline]\nround = []\n[agents.planner]\nimpl = \"rules\"\n[agents.designer]\nimpl = \"rules\"\n[models.m]\nbase_url = \"http://127.0.0.1:9/v1\"\nmodel = \"m\"\n{opt}\n"
            );
            load(&text).map(|_| ()).map_err(|e| e.to_string())
        };
        assert!(model("options = { timeout_s = 120 }").is_ok());
        let e = model("options = { timeout_s = 1e300 }").unwrap_err();
        assert!(
            e.contains("models.m.options.timeout_s: must be 0 and at most"),
            "{e}"
        );
        assert!(
            model("rate_per_s = 1e-300")
                .unwrap_err()
                .contains("rate_per_s")
        );
        assert!(
            model("max_in_flight = 0")
                .unwrap_err()
                .contains("max_in_flight")
        );
        // The shipped graphs stay within the bounds.
        for preset in PRESETS {
            GraphConfig::from_toml(Path::new(preset.name), preset.text, &[]).unwrap();
        }
    }

    #[test]
    fn a_long_offending_line_is_quoted_short() {
        let long = "x".repeat(100_000);
        let text = format!("[agents.planner]\nimpl = \"rules\"\nwidth = \"{long}\"\n");
        let e = load(&text).unwrap_err().to_string();
        assert!(e.len() < 1_000, "{} characters", e.len());
        assert!(e.contains("more characters)"), "{e}");
        assert!(e.contains("line 3, agents.planner.width"), "{e}");
    }

    #[test]
    fn a_mistake_in_the_file_still_names_the_file_beside_sets() {
        let text = "[run]\nmax_rounds = 2\n[agents.planner]\nimpl = \"rules\"\nwidht = 3\n";
        let e = GraphConfig::from_toml(
            Path::new("graph.toml"),
            text,
            &["run.final_prt=false".into()],
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.starts_with("graph.toml: line 6, agents.planner.widht"),
            "{e}"
        );
        assert!(e.contains("did you mean width?"), "{e}");
    }

    #[test]
    fn the_judge_section_names_a_model_of_the_graph() {
        let base = "[run]\nfinal_prt = false\n[pipeline]\nround = []\n[agents.planner]\nimpl = \"rules\"\n[agents.designer]\nimpl = \"rules\"\n[models.main]\nbase_url = \"http://127.0.0.1:9/v1\"\nmodel = \"m\"\n";
        let ok = load(&format!("{base}[judge]\nmodel = \"main\"\n")).unwrap();
        assert_eq!(
            ok.judge.model.as_ref().map(|m| m.get_ref().as_str()),
            Some("main")
        );
        let e = load(&format!("{base}[judge]\nmodel = \"mian\"\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("judge.model: no [models.mian] section"), "{e}");
        assert!(e.contains("did you mean main?"), "{e}");
    }

    #[test]
    fn missing_prompt_files_and_stages_are_refused() {
        let base = "[run]\nfinal_prt = false\n[pipeline]\nround = []\n[agents.planner]\nimpl = \"rules\"\n[agents.designer]\nimpl = \"rules\"\n";
        let e = load(&format!("{base}prompt = \"nowhere.j2\"\n"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("agents.designer.prompt: prompt file nowhere.j2 not found"),
            "{e}"
        );
        let e = load(&base.replace("round = []", "round = [\"evaluate\", \"tidy\"]"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("pipeline.round[0]") || e.contains("pipeline.round"),
            "{e}"
        );
        let e = load(&format!("{base}[agents.tidy]\nimpl = \"clearance\"\n"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("agents.tidy.role: a custom agent needs"), "{e}");
    }
}
