//! Implementations by name: the config says `impl = "rules"`, the registry builds it.
//!
//! Built in: `rules` and `vlm` (any OpenAI-compatible model) for planner, designer, evaluator
//! and srt; `noisy` designer (seeded poses
//! perturbation over the rules designer); `grid-search` designer (the Holodeck-shaped baseline);
//! `grid` for prt; `clearance` for a patch stage; `process` and `http` for every role (an agent
//! outside the binary, see [`crate::external`]). Library
//! users add their own with [`Registry::register`] before building the runtime.
//!
//! Each built-in declares the keys of `options` it reads, so [`Registry::check`] refuses any other
//! key (a typo would otherwise be silently ignored).

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Duration;

use crate::config::{AgentConfig, AgentId, GraphConfig, ModelConfig};
use agents::options::{did_you_mean, unknown_option};
use agents::vlm::VlmBase;
use disco_agents as agents;
use disco_core::error::{Error, Result};
use disco_core::roles::{RoleImpl, RoleKind};
use disco_llm::ModelGateway;
use disco_llm::{Cache, ChatClient, Prompts};
use disco_tools as tools;
use std::path::PathBuf;

/// What a factory gets to build an implementation from.
pub struct BuildContext<'a> {
    /// The agent's name in the graph.
    pub agent_name: &'a str,
    /// The agent's role.
    pub role: RoleKind,
    /// The agent's settings.
    pub agent: &'a AgentConfig,
    /// The whole graph (run settings, prompt paths).
    pub graph: &'a GraphConfig,
    /// The agent's model server, if it names one.
    pub model: Option<&'a ModelConfig>,
    /// That server's shared gateway.
    pub gateway: Option<Arc<ModelGateway>>,
}

/// Builds one implementation; an `Err` says why it cannot (missing key, bad option, ...).
pub type Factory =
    Arc<dyn Fn(&BuildContext<'_>) -> std::result::Result<RoleImpl, String> + Send + Sync>;

/// Implementations by role and name.
#[derive(Clone, Default)]
pub struct Registry {
    factories: BTreeMap<(RoleKind, String), Factory>,
    /// The `options` keys an implementation reads, for those that declared them.
    options: BTreeMap<(RoleKind, String), &'static [&'static str]>,
}

/// No `options` at all.
const NO_OPTIONS: &[&str] = &[];

impl Registry {
    /// A registry with nothing in it.
    pub fn empty() -> Self {
        Registry::default()
    }

    /// The built-in implementations.
    pub fn builtin() -> Self {
        let mut r = Registry::empty();
        r.register(RoleKind::Planner, "rules", |_| {
            Ok(RoleImpl::Planner(Arc::new(
                agents::rules::RulePlanner::new(),
            )))
        });
        r.register(RoleKind::Designer, "rules", |_| {
            Ok(RoleImpl::Designer(Arc::new(
                agents::rules::RuleDesigner::new(),
            )))
        });
        r.register(RoleKind::Designer, "noisy", |ctx| {
            let noisy = agents::noisy::NoisyDesigner::from_options(&ctx.agent.options)?;
            Ok(RoleImpl::Designer(Arc::new(noisy)))
        });
        r.register(RoleKind::Designer, "grid-search", |ctx| {
            let search = agents::grid_search::GridSearchDesigner::from_options(&ctx.agent.options)?;
            Ok(RoleImpl::Designer(Arc::new(search)))
        });
        r.register(RoleKind::Evaluator, "rules", |_| {
            Ok(RoleImpl::Evaluator(Arc::new(agents::rules::RuleEvaluator)))
        });
        r.register(RoleKind::Srt, "rules", |_| {
            Ok(RoleImpl::Srt(Arc::new(tools::srt::RuleSrt)))
        });
        r.register(RoleKind::Prt, "grid", |ctx| {
            let config = disco_tools::prt::PrtConfig {
                grid_step_cm: ctx.graph.run.grid_step_cm,
                ..Default::default()
            };
            Ok(RoleImpl::Prt(Arc::new(tools::prt::GridPrt::new(config))))
        });
        r.register(RoleKind::Planner, "vlm", |ctx| {
            let base = vlm_base(ctx, "planner")?;
            Ok(RoleImpl::Planner(Arc::new(agents::vlm::VlmPlanner::new(
                base,
            ))))
        });
        r.register(RoleKind::Designer, "vlm", |ctx| {
            let base = vlm_base(ctx, "designer")?;
            Ok(RoleImpl::Designer(Arc::new(agents::vlm::VlmDesigner::new(
                base,
            ))))
        });
        r.register(RoleKind::Evaluator, "vlm", |ctx| {
            let template = match ctx.agent.questions {
                crate::config::QuestionStyle::Structured => "evaluator",
                crate::config::QuestionStyle::Open => "open",
            };
            let base = vlm_base(ctx, template)?;
            Ok(RoleImpl::Evaluator(Arc::new(
                agents::vlm::VlmEvaluator::new(base, &ctx.agent.options)?,
            )))
        });
        r.register(RoleKind::Srt, "vlm", |ctx| {
            let base = vlm_base(ctx, "srt")?;
            Ok(RoleImpl::Srt(Arc::new(agents::vlm::VlmSrt::new(base))))
        });
        r.register(RoleKind::Patch, "vlm", |ctx| {
            if ctx.agent.prompt.is_none() {
                return Err("impl \"vlm\" for a patch stage needs `prompt = \"prompts/....j2\"`: the prompt is the stage".into());
            }
            let base = vlm_base(ctx, agents::vlm::patch::TEMPLATE)?;
            Ok(RoleImpl::Patch(Arc::new(agents::vlm::VlmPatch::new(
                base,
                ctx.agent_name,
            ))))
        });
        r.register(RoleKind::Patch, "clearance", |ctx| {
            Ok(RoleImpl::Patch(Arc::new(
                agents::clearance::ClearanceKeeper::from_options(&ctx.agent.options)?,
            )))
        });
        r.declare_builtin_options();
        register_external(&mut r);
        r
    }

    /// The `options` keys of each built-in implementation.
    fn declare_builtin_options(&mut self) {
        use RoleKind::*;
        for role in [Planner, Designer, Evaluator, Srt] {
            self.declare_options(role, "rules", NO_OPTIONS);
            self.declare_options(role, "vlm", NO_OPTIONS);
        }
        self.declare_options(Evaluator, "vlm", &["physical", "ask"]);
        self.declare_options(Designer, "noisy", agents::noisy::NoisyDesigner::OPTIONS);
        self.declare_options(
            Designer,
            "grid-search",
            agents::grid_search::GridSearchDesigner::OPTIONS,
        );
        self.declare_options(Prt, "grid", NO_OPTIONS);
        self.declare_options(Patch, "vlm", NO_OPTIONS);
        self.declare_options(
            Patch,
            "clearance",
            agents::clearance::ClearanceKeeper::OPTIONS,
        );
    }

    /// Declares the keys of `options` that implementation `name` of `role` reads: the graph's
    /// check then refuses any other key. Without a declaration the factory alone judges them.
    pub fn declare_options(&mut self, role: RoleKind, name: &str, known: &'static [&'static str]) {
        self.options.insert((role, name.to_string()), known);
    }

    /// Registers (or replaces) implementation `name` of `role`.
    pub fn register(
        &mut self,
        role: RoleKind,
        name: &str,
        factory: impl Fn(&BuildContext<'_>) -> std::result::Result<RoleImpl, String>
        + Send
        + Sync
        + 'static,
    ) {
        self.factories
            .insert((role, name.to_string()), Arc::new(factory));
        self.options.remove(&(role, name.to_string()));
    }

    /// The registered names for `role`.
    pub fn names(&self, role: RoleKind) -> Vec<String> {
        self.factories
            .keys()
            .filter(|(r, _)| *r == role)
            .map(|(_, n)| n.clone())
            .collect()
    }

    /// Checks that every `impl` and `fallback` of `graph` is registered for its role, and that
    /// its `options` are ones they read.
    pub fn check(&self, graph: &GraphConfig) -> Result<()> {
        self.check_names(graph)?;
        self.check_options(graph)
    }

    /// Every `impl` and `fallback` is registered for its agent's role.
    fn check_names(&self, graph: &GraphConfig) -> Result<()> {
        for (name, agent) in graph.agents() {
            let role = agent.role();
            let agent = agent.config();
            let mut names = vec![("impl", &agent.implementation)];
            if let Some(f) = &agent.fallback {
                names.push(("fallback", f));
            }
            for (key, value) in names {
                if !self
                    .factories
                    .contains_key(&(role, value.get_ref().clone()))
                {
                    return Err(graph.error_at(
                        Some(value.span().start),
                        &format!("agents.{name}.{key}"),
                        format!(
                            "unknown {role} implementation {:?}; known: {}{}",
                            value.get_ref(),
                            self.names(role).join(", "),
                            did_you_mean(value.get_ref(), &self.names(role))
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Every key of an agent's `options` is read by its `impl` or its `fallback` (they share the
    /// table), when both declared what they read.
    fn check_options(&self, graph: &GraphConfig) -> Result<()> {
        for (name, agent) in graph.agents() {
            let role = agent.role();
            let agent = agent.config();
            let impls = std::iter::once(&agent.implementation).chain(&agent.fallback);
            let Some(known) = impls
                .map(|i| self.options.get(&(role, i.get_ref().clone())).copied())
                .collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            let known: Vec<&str> = known.concat();
            if let Some(key) = agent.options.keys().find(|k| !known.contains(&k.as_str())) {
                let dotted = format!("agents.{name}.options.{key}");
                let at = graph
                    .find(&dotted)
                    .or_else(|| graph.find(&format!("agents.{name}.options")));
                return Err(graph.error_at(at, &dotted, unknown_option(key, &known)));
            }
        }
        Ok(())
    }

    /// Builds implementation `impl_name` for agent `agent` of `graph`.
    pub fn build(
        &self,
        graph: &GraphConfig,
        gateways: &disco_llm::Gateways,
        agent: &AgentId,
        impl_name: &str,
    ) -> std::result::Result<RoleImpl, BuildError> {
        let agent_id = || agent.clone();
        let found = graph
            .agent(agent)
            .ok_or_else(|| BuildError::NoAgent { agent: agent_id() })?;
        let role = found.role();
        let factory = self
            .factories
            .get(&(role, impl_name.to_string()))
            .ok_or_else(|| BuildError::Unknown {
                agent: agent_id(),
                role,
                implementation: impl_name.to_string(),
            })?;
        let config = found.config();
        let model_name = config.model.as_ref().map(|m| m.get_ref().as_str());
        let ctx = BuildContext {
            agent_name: agent.as_str(),
            role,
            agent: config,
            graph,
            model: model_name.and_then(|m| graph.models.get(m)),
            gateway: model_name.and_then(|m| gateways.get(m)),
        };
        let built = factory(&ctx).map_err(|reason| BuildError::Factory {
            agent: agent_id(),
            implementation: impl_name.to_string(),
            reason,
        })?;
        if built.kind() != role {
            return Err(BuildError::WrongKind {
                agent: agent_id(),
                implementation: impl_name.to_string(),
                built: built.kind(),
                role,
            });
        }
        Ok(built)
    }
}

/// Why an agent's implementation could not be built. Its text names the agent's section
/// (`agents.NAME: ...`); [`BuildError::in_graph`] makes it an input error of the graph's file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BuildError {
    /// The graph has no such agent.
    NoAgent {
        /// The agent asked for.
        agent: AgentId,
    },
    /// No implementation of that name is registered for the agent's role.
    Unknown {
        /// The agent.
        agent: AgentId,
        /// Its role.
        role: RoleKind,
        /// The implementation asked for.
        implementation: String,
    },
    /// The implementation's factory refused (a missing key, a bad option, ...).
    Factory {
        /// The agent.
        agent: AgentId,
        /// The implementation.
        implementation: String,
        /// What the factory said.
        reason: String,
    },
    /// The factory built an implementation of another role than the agent's.
    WrongKind {
        /// The agent.
        agent: AgentId,
        /// The implementation.
        implementation: String,
        /// The role of what it built.
        built: RoleKind,
        /// The agent's role.
        role: RoleKind,
    },
}

impl BuildError {
    /// The agent the error is about.
    pub fn agent(&self) -> &AgentId {
        match self {
            BuildError::NoAgent { agent }
            | BuildError::Unknown { agent, .. }
            | BuildError::Factory { agent, .. }
            | BuildError::WrongKind { agent, .. } => agent,
        }
    }

    /// What is wrong, without the agent's section.
    pub fn reason(&self) -> String {
        match self {
            BuildError::NoAgent { .. } => "no such agent".into(),
            BuildError::Unknown {
                role,
                implementation,
                ..
            } => format!("unknown {role} implementation {implementation:?}"),
            BuildError::Factory {
                implementation,
                reason,
                ..
            } => format!("cannot build {implementation:?}: {reason}"),
            BuildError::WrongKind {
                implementation,
                built,
                role,
                ..
            } => format!("{implementation:?} built a {built} for a {role} role"),
        }
    }

    /// The error as an input error of `graph`'s file, at `agents.NAME`.
    pub fn in_graph(&self, graph: &GraphConfig) -> Error {
        Error::invalid(
            &graph.source,
            format!("agents.{}", self.agent()),
            self.reason(),
        )
    }
}

impl std::fmt::Display for BuildError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "agents.{}: {}", self.agent(), self.reason())
    }
}

impl std::error::Error for BuildError {}

/// Builds the client and prompts of one agent from the graph: its `model`, its `prompt`
/// file (replacing the built-in template `template`), and the run's record/replay folder.
fn vlm_base(ctx: &BuildContext<'_>, template: &str) -> std::result::Result<VlmBase, String> {
    let name = ctx
        .agent
        .model
        .as_ref()
        .map(|m| m.get_ref().clone())
        .ok_or("impl \"vlm\" needs `model = \"...\"`, naming a [models.NAME] section")?;
    let model = ctx
        .model
        .ok_or_else(|| format!("no [models.{name}] section for model {name:?}"))?;
    let cache = match &ctx.graph.run.cache {
        Some(dir) => Some(Arc::new(
            Cache::open(&PathBuf::from(dir)).map_err(|e| e.to_string())?,
        )),
        None => None,
    };
    let client = ChatClient::from_config(&name, model, ctx.gateway.clone(), cache)
        .map_err(|e| e.to_string())?;
    let mut prompts = Prompts::default();
    if let Some(p) = &ctx.agent.prompt {
        prompts = prompts
            .with_file(template, &ctx.graph.resolve_path(p.get_ref()))
            .map_err(|e| e.to_string())?;
    }
    Ok(VlmBase { client, prompts })
}

/// Whether `options.render = true`.
fn wants_render(ctx: &BuildContext<'_>) -> Result<bool, String> {
    match ctx.agent.options.get("render") {
        None => Ok(false),
        Some(v) => v
            .as_bool()
            .ok_or_else(|| format!("options.render must be true or false, got {v}")),
    }
}

/// Registers `process` and `http` (agents outside the binary, [`crate::external`]) for every
/// role.
fn register_external(r: &mut Registry) {
    use RoleKind::*;
    for role in [Planner, Designer, Evaluator, Srt, Prt, Patch] {
        r.register(role, "process", |ctx| {
            let command = ctx.agent.command.clone().unwrap_or_default();
            let command = command
                .iter()
                .map(|a| ctx.graph.resolve_path(a).to_string_lossy().into_owned())
                .collect();
            let deadline = Duration::from_secs_f64(ctx.agent.deadline_s);
            let transport =
                crate::external::process::ProcessTransport::new(ctx.agent_name, command, deadline)?
                    .with_max_reply(ctx.agent.max_reply_bytes);
            let agent = crate::external::ExternalAgent::new(
                ctx.agent_name,
                ctx.role,
                Box::new(transport),
                wants_render(ctx)?,
            );
            Ok(agent.into_role_impl())
        });
        r.register(role, "http", |ctx| {
            let url = ctx.agent.url.as_deref().unwrap_or_default();
            let deadline = Duration::from_secs_f64(ctx.agent.deadline_s);
            let transport = crate::external::http::HttpTransport::new(url, deadline)?
                .with_max_reply(ctx.agent.max_reply_bytes);
            let agent = crate::external::ExternalAgent::new(
                ctx.agent_name,
                ctx.role,
                Box::new(transport),
                wants_render(ctx)?,
            );
            Ok(agent.into_role_impl())
        });
        r.declare_options(role, "process", crate::external::OPTIONS);
        r.declare_options(role, "http", crate::external::OPTIONS);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(sets: &[&str]) -> String {
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let graph = GraphConfig::load(None, &sets).unwrap();
        match Registry::builtin().check(&graph) {
            Ok(()) => "ok".into(),
            Err(e) => e.to_string(),
        }
    }

    #[test]
    fn options_no_implementation_reads_are_refused_at_the_set() {
        assert_eq!(
            check(&["agents.designer.options.bogus=1"]),
            "--set agents.designer.options.bogus=1: agents.designer.options.bogus: unknown option \"bogus\"; this implementation takes no options"
        );
        let e = check(&[
            "agents.designer.impl=noisy",
            "agents.designer.options.sede=1",
        ]);
        assert!(
            e.ends_with("known: seed, shift_cm, turn_deg; did you mean seed?"),
            "{e}"
        );
        assert_eq!(
            check(&[
                "agents.designer.impl=noisy",
                "agents.designer.options.seed=1"
            ]),
            "ok"
        );
        assert!(check(&["agents.prt.options.step=1"]).contains("unknown option \"step\""));
    }

    #[test]
    fn options_of_the_impl_are_allowed_beside_its_fallback() {
        let text = "[pipeline]\nround = [\"evaluate\"]\n[agents.planner]\nimpl = \"rules\"\n[agents.designer]\nimpl = \"rules\"\n[agents.prt]\nimpl = \"grid\"\n[agents.evaluator]\nimpl = \"vlm\"\nfallback = \"rules\"\nmodel = \"m\"\noptions = { physical = \"either\" }\n[models.m]\nbase_url = \"http://localhost:1\"\nmodel = \"x\"\n";
        let graph = GraphConfig::from_toml(std::path::Path::new("g.toml"), text, &[]).unwrap();
        Registry::builtin().check(&graph).unwrap();
        let bad = text.replace("physical", "phisical");
        let graph = GraphConfig::from_toml(std::path::Path::new("g.toml"), &bad, &[]).unwrap();
        let e = Registry::builtin().check(&graph).unwrap_err().to_string();
        assert!(
            e.starts_with("g.toml: line 13, agents.evaluator.options.phisical: unknown option"),
            "{e}"
        );
        assert!(e.contains("did you mean physical?"), "{e}");
    }

    #[test]
    fn an_unknown_implementation_gets_the_nearest_name() {
        let e = check(&["agents.designer.impl=nosy"]);
        assert!(e.starts_with("--set agents.designer.impl=nosy: agents.designer.impl: unknown designer implementation"), "{e}");
        assert!(e.ends_with("did you mean noisy?"), "{e}");
    }
}
