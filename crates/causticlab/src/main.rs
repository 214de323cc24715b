//! `causticlab`: list Vulkan devices, render scenes, compare with references, run benchmarks,
//! and view a scene interactively.
//! Errors are printed as `error: <chain>` and
//! mapped to exit codes (see `exit.rs`); with `--validate`, any validation message turns a
//! successful run into exit code 3.

#![forbid(unsafe_code)]

mod cli;
mod cmd_bench;
mod cmd_compare;
mod cmd_devices;
mod cmd_diff;
mod cmd_pool_reference;
mod cmd_reference;
mod cmd_reference_final;
mod cmd_render;
mod cmd_soak;
mod cmd_variants;
mod exit;
mod view;

use anyhow::Result;
use clap::Parser;
use cli::{Cli, Command, GlobalOpts};
use std::process::ExitCode;
use std::sync::Arc;
use vkcore::{ContextOptions, Feature, ValidationLog};

fn main() -> ExitCode {
    // `log` warnings (gpu-allocator's leak report among them) go to stderr; RUST_LOG sets the
    // level (e.g. RUST_LOG=info, RUST_LOG=gpu_allocator=trace).
    env_logger::Builder::from_env(env_logger::Env::default().default_filter_or("warn")).format_timestamp(None).init();
    exit_quietly_when_stdout_closes();
    let cli = Cli::parse();
    let mut validation: Option<Arc<ValidationLog>> = None;
    let ok = |r: Result<()>| r.map(|()| exit::OK);
    let result = match &cli.command {
        Command::Devices => ok(cmd_devices::run(&cli.global, &mut validation)),
        Command::Render(args) => ok(cmd_render::run(&cli.global, args, &mut validation)),
        Command::Reference(args) => ok(cmd_reference::run(&cli.global, args, &mut validation)),
        Command::Compare(args) => ok(cmd_compare::run(args)),
        Command::Diff(args) => cmd_diff::run(args),
        Command::Bench(args) => ok(cmd_bench::run(&cli.global, args, &mut validation)),
        Command::Soak(args) => ok(cmd_soak::run(&cli.global, args, &mut validation)),
        Command::View(args) => ok(view::run(&cli.global, args, &mut validation)),
        Command::Variants(args) => ok(cmd_variants::run(args)),
        Command::Dumps => {
            print!("{}", caustics::render::dumps::markdown_table());
            Ok(exit::OK)
        }
    };
    let mut code = match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            // `diff`, as diff(1): 1 means the two sides differ, so any trouble is 2.
            if matches!(cli.command, Command::Diff(_)) {
                exit::INPUT
            } else {
                exit::code_for(&e)
            }
        }
    };
    // Every Vulkan object is gone by now, so messages from their destruction are counted too.
    if let (true, Some(log)) = (cli.global.validate, validation) {
        let n = log.count();
        if n == 0 {
            eprintln!("validation: no warnings or errors reported");
        } else {
            eprintln!(
                "validation: {n} message(s) reported ({} error(s), {} warning(s))",
                log.errors(),
                n - log.errors()
            );
            if code == exit::OK {
                code = exit::VALIDATION;
            }
        }
    }
    ExitCode::from(code)
}

/// A reader that stops early (`causticlab variants | head -1`) closes our stdout, and `println!`
/// then panics ("failed printing to stdout: Broken pipe"). Exit instead as a program killed by
/// SIGPIPE does (`exit::CLOSED_STDOUT`, 128 + 13), quietly: the reader already has what it wanted.
/// (Rust ignores SIGPIPE, and restoring it takes `unsafe`, which this crate forbids.)
fn exit_quietly_when_stdout_closes() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info.payload_as_str().unwrap_or_default();
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(exit::CLOSED_STDOUT.into());
        }
        default(info)
    }));
}

/// The device options shared by every subcommand; unknown `--without-feature` names are input
/// errors listing the valid ones.
pub(crate) fn context_options(g: &GlobalOpts) -> Result<ContextOptions> {
    let mut without = vec![];
    for name in &g.without_feature {
        let f = Feature::parse(name.trim()).ok_or_else(|| {
            let valid: Vec<&str> = Feature::ALL.iter().map(|f| f.name()).collect();
            caustics::input_error!("--without-feature: unknown feature `{name}`; valid names: {}", valid.join(", "))
        })?;
        if !without.contains(&f) {
            without.push(f);
        }
    }
    Ok(ContextOptions { device: g.device.clone(), validation: g.validate, echo_validation: g.validate, without })
}
