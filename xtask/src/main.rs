//! Project automation: `cargo xtask fixtures` writes `fixtures/`; `cargo xtask report` measures
//! and writes `docs/REPORT.md` with its figures.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use xtask::report::{ReportSettings, write_report};

const USAGE: &str = "usage: cargo xtask fixtures | cargo xtask report [--quick] [--out DIR]";

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

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

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("fixtures") => xtask::write_fixtures(&workspace_root()),
        Some("report") => report(&args[1..]),
        _ => Err(USAGE.to_string()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("xtask: {message}");
            ExitCode::from(2)
        }
    }
}
