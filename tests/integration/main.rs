//! End-to-end tests of the `disco` command: every bad input gets a message that names the file,
//! the field and the reason; good input gets a valid layout, metrics and a picture.
//!
//! One test binary (`cargo test --test integration`), one module per command or area; the shared
//! runner, fixtures and the outside tools (headless Chromium, the glTF checker, a local model
//! server) are in `harness`.

mod harness;

mod agents;
mod batch;
mod bench;
mod config;
mod contain;
mod crash;
mod export;
mod generate;
mod inputs_kept;
mod kitchens;
mod metrics;
mod open_rooms;
mod patterns;
mod refine;
mod render;
mod replay;
mod requests;
mod rooms;
mod shard;
mod validate;
mod vlm;
mod whole_rooms;
