//! Integration tests: one binary made of modules (see Cargo.toml,
//! `autotests = false`).
#![allow(
    unreachable_pub,
    reason = "items of a test binary are reachable only inside it"
)]

mod catalogue;
mod certify;
mod certify_cli;
mod cli;
mod curves;
mod drawings;
mod immersion;
mod keys;
mod morph;
mod outputs;
mod pairs;
mod properties;
mod sequence;
mod stress;
mod util;
mod web;
