//! `contacts`: query, benchmark and demo scenes of curved solids.
//!
//! Exit status 0 on success, 2 on bad input (with one message on stderr).

use clap::{Parser, Subcommand};
use contacts::run::prepare_scene;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "contacts", about = "Exact contacts between curved solids")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print every pair's contacts as JSON.
    Query {
        /// Scene file.
        scene: PathBuf,
    },
    /// Time every pair's query; print median and minimum µs per query as JSON.
    Bench {
        /// Scene file.
        scene: PathBuf,
        /// Timed queries per pair (after as many warm-up queries).
        #[arg(long, default_value_t = 1000)]
        iterations: usize,
    },
    /// Run the paper's four two-contact scenes and print a table beside the paper's Table 3.
    Demo {
        /// Timed queries per scene.
        #[arg(long, default_value_t = 2000)]
        iterations: usize,
    },
    /// Draw the scene with every contact's points and normal marked, as a PNG picture.
    #[cfg(feature = "render")]
    Render {
        /// Scene file.
        scene: PathBuf,
        /// PNG file to write.
        #[arg(short, long)]
        output: PathBuf,
        /// Picture width (pixels).
        #[arg(long, default_value_t = 1024)]
        width: u32,
        /// Picture height (pixels).
        #[arg(long, default_value_t = 768)]
        height: u32,
        /// Fit the contacts with some surroundings instead of the whole scene.
        #[arg(long)]
        zoom_contacts: bool,
    },
}

/// `contacts render`: writes the picture and returns a one-line JSON summary.
#[cfg(feature = "render")]
fn render(
    scene: &std::path::Path,
    output: &std::path::Path,
    options: &contacts::render::RenderOptions,
) -> Result<String, String> {
    let scene = prepare_scene(scene).map_err(|e| e.to_string())?;
    let rendered = contacts::render::render_scene(&scene, options).map_err(|e| e.to_string())?;
    rendered.write_png(output).map_err(|e| e.to_string())?;
    let contacts: usize = rendered.pairs.iter().map(|p| p.report.contacts.len()).sum();
    Ok(serde_json::json!({
        "png": output.display().to_string(),
        "width": options.width,
        "height": options.height,
        "contacts": contacts,
    })
    .to_string())
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Command::Query { scene } => prepare_scene(&scene)
            .map_err(|e| e.to_string())
            .and_then(|s| s.query_json().map_err(|e| e.to_string()))
            .map(|v| v.to_string()),
        Command::Bench { scene, iterations } => prepare_scene(&scene)
            .map_err(|e| e.to_string())
            .and_then(|s| s.bench_json(iterations.max(1)).map_err(|e| e.to_string()))
            .map(|v| v.to_string()),
        Command::Demo { iterations } => contacts::demo::run(iterations.max(1)),
        #[cfg(feature = "render")]
        Command::Render {
            scene,
            output,
            width,
            height,
            zoom_contacts,
        } => render(
            &scene,
            &output,
            &contacts::render::RenderOptions {
                width,
                height,
                zoom_contacts,
            },
        ),
    };
    match result {
        Ok(text) => {
            // A closed pipe (e.g. `| head`) is not an error of ours.
            let _ = writeln!(std::io::stdout().lock(), "{text}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("contacts: {e}");
            ExitCode::from(2)
        }
    }
}
