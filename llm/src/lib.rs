//! # disco-llm
//!
//! Talking to models over any OpenAI-compatible server: the chat client ([`ChatClient`]), the
//! settings of a server ([`ModelConfig`]), one bounded [`gateway`] per server shared by every
//! scene, record and replay ([`Cache`]), the prompt templates ([`Prompts`]) and reading JSON out of
//! what models answer ([`extract`]).
//!
//! It knows nothing of agents or of the runtime; it depends only on `disco-core`.
#![deny(missing_docs)]

mod cache;
mod client;
pub mod extract;
pub mod gateway;
mod model;
mod prompts;

pub use cache::Cache;
pub use client::{
    CallRecord, ChatClient, ChatReply, ClientSettings, LlmError, MAX_BODY_BYTES, Message, Schema,
    expand_env, install_tls_provider, read_completion,
};
pub use gateway::{Gateways, ModelGateway};
pub use model::ModelConfig;
pub use prompts::{BUILTIN as BUILTIN_PROMPTS, Prompts};
