//! `causticlab bench CONFIG`, `causticlab bench merge PARTS...` and `causticlab bench explain
//! CONFIG TABLE`: the config is read and
//! checked before the device is opened; the tables are written only after every cell ran.

use crate::cli::{BenchArgs, BenchCommand, GlobalOpts};
use anyhow::{Context as _, Result};
use bench::{BenchOptions, LoadedConfig};
use std::io::Write as _;
use std::sync::Arc;
use vkcore::{Context, ShaderCompiler, ValidationLog};

pub fn run(g: &GlobalOpts, args: &BenchArgs, validation: &mut Option<Arc<ValidationLog>>) -> Result<()> {
    if let Some(BenchCommand::Merge(m)) = &args.merge {
        caustics::image_io::check_output_dir(&m.results).context("--results")?;
        let out = bench::merge(&m.parts, &m.results, m.partial)?;
        report(&out);
        return Ok(());
    }
    if let Some(BenchCommand::Explain(e)) = &args.merge {
        caustics::image_io::check_output_dir(&e.results).context("--results")?;
        let config = LoadedConfig::load(&e.config)?;
        let commit = committed("bench explain", &e.results, e.allow_dirty)?;
        let out = bench::explain::explain(&config, &e.table, &e.results, &commit)?;
        report(&out);
        return Ok(());
    }
    if let Some(BenchCommand::Claims(c)) = &args.merge {
        return claims(c);
    }
    if let Some(BenchCommand::Same(s)) = &args.merge {
        return same(s);
    }
    if let Some(BenchCommand::Index(i)) = &args.merge {
        return index(i);
    }
    let Some(path) = &args.config else {
        return Err(caustics::input_error!("bench: give a config file (bench_configs/*.toml) or `merge`").into());
    };
    let mut config = LoadedConfig::load(path)?;
    if let Some(cap) = args.max_time_budget {
        let run = &mut config.config.run;
        run.time_budget_s = run.time_budget_s.min(cap);
    }
    // The tables are written after every cell ran: a --results that cannot be a folder fails now.
    caustics::image_io::check_output_dir(&args.results).context("--results")?;
    committed("bench", &args.results, args.quick || args.allow_dirty)?;
    let opts = crate::context_options(g)?;
    // Timing runs never have validation on, and never pretend a feature is missing: those
    // are for --quick smoke tests, whose tables go to their own folder.
    if !args.quick && (opts.validation || !opts.without.is_empty()) {
        return Err(caustics::input_error!(
            "bench: --validate and --without-feature are for --quick runs only: a timing run measures the device as it is"
        )
        .into());
    }
    let ctx = Context::new(&opts).context("opening the Vulkan device")?;
    *validation = Some(ctx.validation_log());
    let shaders = ShaderCompiler::new(&caustics::render::shader_root()).context("creating the shader compiler")?;
    let bench_opts = BenchOptions {
        quick: args.quick,
        filter: args.filter.clone(),
        shard: args.shard.clone(),
        results_root: args.results.clone(),
        busy_cores: args.busy_cores,
        busy_retries: args.busy_retries,
        spread_retries: args.spread_retries,
        refuse_busy: !args.quick && !args.allow_busy && bench::meta::in_work_tree(&args.results),
        refuse_other_cpu: !args.quick && !args.allow_other_cpu && bench::meta::in_work_tree(&args.results),
    };
    let out = bench::run(&ctx, &shaders, &config, &bench_opts)?;
    report(&out);
    Ok(())
}

/// `bench same A B`: every difference outside the timings, or a line saying there is none.
fn same(s: &crate::cli::SameArgs) -> Result<()> {
    let a = bench::results::read(&s.first, "result")?;
    let b = bench::results::read(&s.second, "result")?;
    let d = bench::same::differences(&a, &b, s.tolerance);
    let (na, nb) = (s.first.display(), s.second.display());
    let absent = bench::same::absent_settings(&a, &b);
    if !absent.is_empty() {
        let keys: Vec<&str> = absent.iter().map(|k| k.as_str()).collect();
        println!(
            "bench same: not compared, in one result only (written before the setting existed): {}",
            keys.join(", ")
        );
    }
    if d.is_empty() {
        println!(
            "bench same: {na} and {nb} agree in all {} cells outside the timings (tolerance {})",
            a.cells.len(),
            s.tolerance
        );
        return Ok(());
    }
    for line in &d {
        println!("{line}");
    }
    // Not an input error: exit 1 (`exit::DIFFERENT`), as `diff` when the two sides differ.
    anyhow::bail!("bench same: {} difference(s) between {na} and {nb}", d.len())
}

/// The commit the tables will name. Committed tables come from committed code: from a work tree
/// with uncommitted changes (other than results and Markdown) nothing is written into the
/// repository's results folder unless `allow_dirty`.
fn committed(who: &str, results: &std::path::Path, allow_dirty: bool) -> Result<String> {
    let commit = bench::meta::commit();
    if commit.ends_with("-dirty") && !allow_dirty && bench::meta::in_work_tree(results) {
        return Err(caustics::input_error!(
            "{who}: the work tree has uncommitted changes ({commit}), so the tables in {} would not match any commit; \
             commit first, write elsewhere with --results, or pass --allow-dirty (the tables then say `{commit}`)",
            results.display()
        )
        .into());
    }
    Ok(commit)
}

fn report(out: &bench::Outcome) {
    println!("{}", out.summary);
    for f in &out.written {
        println!("wrote {}", f.display());
    }
    for f in &out.removed {
        println!("removed {} (the table's uncompressed copy: its .json.gz replaces it)", f.display());
    }
}

/// `bench index`: the results folder's index rebuilt, or with --check compared.
fn index(i: &crate::cli::IndexArgs) -> Result<()> {
    if !i.results.is_dir() {
        return Err(caustics::input_error!("--results {}: not a folder", i.results.display()).into());
    }
    if !i.check {
        println!("wrote {}", bench::index::write_index(&i.results)?.display());
        return Ok(());
    }
    let stale = bench::index::stale_lines(&i.results)?;
    for line in &stale {
        println!("{line}");
    }
    if !stale.is_empty() {
        anyhow::bail!(
            "bench index --check: {} line(s) of {} are out of date: `causticlab bench index` rewrites it",
            stale.len(),
            i.results.join("README.md").display()
        );
    }
    println!("{}: current", i.results.join("README.md").display());
    Ok(())
}

/// `bench claims`: every page's claims against the committed tables.
fn claims(c: &crate::cli::ClaimsArgs) -> Result<()> {
    if let Some(table) = &c.list {
        // A closed pipe (`| head`) ends the listing, not the program.
        let _ = std::io::stdout().lock().write_all(bench::claims::list(table)?.as_bytes());
        return Ok(());
    }
    // A root or page that is not there is the user's to fix (exit 2), and a check that read no
    // page has checked nothing: neither passes.
    if !c.root.is_dir() {
        return Err(caustics::input_error!("bench claims: --root {}: no such folder", c.root.display()).into());
    }
    let pages = if c.pages.is_empty() { bench::claims::pages(&c.root)? } else { c.pages.clone() };
    if pages.is_empty() {
        return Err(caustics::input_error!(
            "bench claims: no page under {} (README.md, docs/, results/): nothing to check",
            c.root.display()
        )
        .into());
    }
    if let Some(p) = pages.iter().find(|p| !p.is_file()) {
        return Err(caustics::input_error!("bench claims: {}: no such page", p.display()).into());
    }
    let checked = bench::claims::check(&c.root, &pages)?;
    let (mut claims, mut problems, mut unread) = (0, 0, 0);
    let mut out = std::io::stdout().lock();
    for p in &checked {
        let page = p.page.strip_prefix(&c.root).unwrap_or(&p.page).display().to_string();
        // Every page is held to its numbers: one that names no source yet fails on each
        // measured-looking number, as an enrolled page fails on one without a claim.
        if !p.report.enrolled && !p.report.problems.is_empty() {
            let _ = writeln!(
                out,
                "{page}: names no tables (`<!--claims DIR -->` or `<!--claims NAME = FILE.csv -->` near the top) and has {} measured-looking number(s):",
                p.report.problems.len()
            );
        }
        for f in &p.report.problems {
            let _ = writeln!(out, "{page}:{}: `{}`: {}", f.line, f.written, f.what);
        }
        claims += p.report.claims;
        problems += p.report.problems.len();
        unread += p.report.papers_missing;
    }
    if unread > 0 {
        let _ = writeln!(
            out,
            "{unread} paper value(s) not checked: the papers' text is not in {} (CI has it)",
            c.root.join("../shared/papers").display()
        );
    }
    let _ = writeln!(out, "{} page(s), {claims} claim(s) checked, {problems} problem(s)", checked.len());
    if problems > 0 {
        anyhow::bail!("bench claims: {problems} number(s) disagree with the tables or have no source");
    }
    Ok(())
}
