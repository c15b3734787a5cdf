//! Talking to models: the chat client ([`ChatClient`]), record and replay ([`Cache`]), the
//! prompt templates ([`Prompts`]) and reading JSON out of what models answer ([`extract`]).

mod cache;
mod client;
pub mod extract;
mod prompts;

pub use cache::Cache;
pub use client::{
    CallRecord, ChatClient, ChatReply, ClientSettings, LlmError, Message, Schema, expand_env,
    read_completion,
};
pub use prompts::{BUILTIN as BUILTIN_PROMPTS, Prompts};

#[cfg(test)]
mod fault_tests;
