//! Project automation. `cargo xtask fixtures` writes `fixtures/`; `cargo xtask report` measures
//! and writes `docs/REPORT.md` with its figures (see `xtask::report`); `cargo xtask stage2`
//! prints the report's table of Stage 2's two paths alone; `cargo xtask world` prints the table
//! of many-object worlds (see `xtask::world_scene`); `cargo xtask coherence` prints the table of
//! coherent against cold frames (see `xtask::report::coherence_table`); `cargo xtask soak N`
//! runs the random near-contact soak (see `xtask::soak`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;
use xtask::report::{ReportSettings, write_report};
use xtask::soak::run::{SoakConfig, replay, run_soak};
use xtask::soak::table::{render, totals};

const USAGE: &str = "usage: cargo xtask fixtures\n       \
cargo xtask report [--quick] [--out DIR]\n       \
cargo xtask stage2 [REPETITIONS]\n       \
cargo xtask world [STEPS]\n       \
cargo xtask coherence [PASSES]\n       \
cargo xtask soak N [--seed S] [--pairs a-b,c-d,...] [--general]\n       \
cargo xtask soak --replay a-b:SEED";

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

/// Splits "a-b" into two fixture object names; names may hold a dash themselves
/// ("rounded-box-vase"), so the split is at the dash where both sides are known objects (the
/// first dash when none is).
fn parse_pair(text: &str) -> Result<(String, String), String> {
    let names: Vec<String> = xtask::fixture_objects()
        .iter()
        .map(|o| o.name().to_string())
        .collect();
    let known = |n: &str| names.iter().any(|m| m == n);
    let splits = text
        .match_indices('-')
        .map(|(i, _)| (&text[..i], &text[i + 1..]));
    splits
        .clone()
        .find(|(a, b)| known(a) && known(b))
        .or_else(|| splits.clone().next())
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .ok_or(format!("bad pair `{text}`: expected a-b"))
}

/// Measures and writes the report (docs/REPORT.md unless `--out DIR`).
fn report(args: &[String]) -> Result<(), String> {
    let root = workspace_root();
    let mut settings = ReportSettings::full();
    let mut out = root.join("docs");
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        match arg.as_str() {
            "--quick" => settings = ReportSettings::quick(),
            "--out" => out = PathBuf::from(rest.next().ok_or(USAGE)?),
            _ => return Err(USAGE.to_string()),
        }
    }
    write_report(&root, &out, &settings)?;
    eprintln!("report: wrote {}", out.join("REPORT.md").display());
    Ok(())
}

/// Measures Stage 2's two paths on every fixture scene and the report's concave scenes in one
/// run and prints the report's table (markdown).
fn stage2(args: &[String]) -> Result<(), String> {
    let repetitions = match args.first() {
        Some(n) => n
            .parse()
            .map_err(|e| format!("bad repetitions `{n}`: {e}"))?,
        None => 201,
    };
    let rows = xtask::report::stage2_comparison::measure(&workspace_root(), repetitions)?;
    let mut text = String::new();
    xtask::report::writer::stage2_section(&mut text, &rows);
    print!("{text}");
    Ok(())
}

/// Runs the soak; Ok(true) when nothing failed.
fn soak(args: &[String]) -> Result<bool, String> {
    if let [flag, what] = args
        && flag == "--replay"
    {
        let (pair, seed) = what
            .split_once(':')
            .ok_or(format!("bad replay `{what}`: expected a-b:SEED"))?;
        let (a, b) = parse_pair(pair)?;
        let seed = seed.parse().map_err(|e| format!("bad seed: {e}"))?;
        let (pose, stats) = replay(&a, &b, seed)?;
        println!("{pose:#?}\n{stats:#?}");
        return Ok(stats.failure_count() == 0);
    }
    let mut config = SoakConfig {
        poses: 0,
        seed: 1,
        pairs: Vec::new(),
        general: false,
    };
    let mut rest = args.iter();
    while let Some(arg) = rest.next() {
        let mut value = || rest.next().ok_or(format!("{arg} needs a value"));
        match arg.as_str() {
            "--general" => config.general = true,
            "--seed" => config.seed = value()?.parse().map_err(|e| format!("bad seed: {e}"))?,
            "--pairs" => {
                config.pairs = value()?
                    .split(',')
                    .map(parse_pair)
                    .collect::<Result<_, _>>()?;
            }
            n => config.poses = n.parse().map_err(|_| USAGE.to_string())?,
        }
    }
    if config.poses == 0 {
        return Err(USAGE.into());
    }
    let start = Instant::now();
    let summary = run_soak(&config, |(a, b), s| {
        eprintln!(
            "{a}-{b}: {} poses, {} failures ({:.0} s)",
            s.poses,
            s.failure_count(),
            start.elapsed().as_secs_f64()
        );
    })?;
    print!("{}", render(&summary));
    let total = totals(&summary);
    println!(
        "{} poses in {:.1} s, seed {}",
        total.poses,
        start.elapsed().as_secs_f64(),
        config.seed
    );
    Ok(total.failure_count() == 0)
}

/// Prints the table of worlds of 10, 100 and 1000 objects (markdown; see
/// `xtask::world_scene::world_table`).
fn world(args: &[String]) -> Result<(), String> {
    let steps = match args.first() {
        Some(n) => n.parse().map_err(|e| format!("bad steps `{n}`: {e}"))?,
        None => 20,
    };
    let table =
        xtask::world_scene::world_table(&xtask::fixture_objects(), &[10, 100, 1000], steps)?;
    print!("{table}");
    Ok(())
}

/// Prints the table of coherent against cold frames on the paper scenes (markdown; see
/// `xtask::report::coherence_table`).
fn coherence(args: &[String]) -> Result<(), String> {
    let passes = match args.first() {
        Some(n) => n.parse().map_err(|e| format!("bad passes `{n}`: {e}"))?,
        None => 15,
    };
    let table = xtask::report::coherence_table::coherence_table(&workspace_root(), passes)?;
    print!("{table}");
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("fixtures") => xtask::write_fixtures(&workspace_root()).map(|()| true),
        Some("report") => report(&args[1..]).map(|()| true),
        Some("soak") => soak(&args[1..]),
        Some("stage2") => stage2(&args[1..]).map(|()| true),
        Some("world") => world(&args[1..]).map(|()| true),
        Some("coherence") => coherence(&args[1..]).map(|()| true),
        _ => Err(USAGE.to_string()),
    };
    match result {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(message) => {
            eprintln!("xtask: {message}");
            ExitCode::from(2)
        }
    }
}
