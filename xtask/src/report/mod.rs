//! `cargo xtask report`: measures error against run time and the paper's tables in one run on
//! the machine at hand, and writes `REPORT.md` with its figures (SVG plots, PNG pictures).
//!
//! Everything in the report is measured by [`write_report`] in the same run; nothing is
//! copied from earlier runs except the paper's own figures, which are labelled as such.

pub mod accuracy_scene;
pub mod coherence_table;
pub mod error_vs_time;
pub mod machine;
pub mod mesh_seed_refiner;
pub mod methods;
pub mod paper_tables;
pub mod pictures;
pub mod plot;
pub mod stage2_comparison;
pub mod stage_growth;
pub mod stage_times;
pub mod timing;
pub mod writer;

use accuracy_scene::{
    AccuracyScene, PAPER_SCENES, closed_form_scene, closed_form_scenes, paper_scene,
};
use error_vs_time::MethodSettings;
use paper_tables::TableSettings;
use std::path::Path;

/// How much the report measures.
pub struct ReportSettings {
    /// Paper scenes (names in [`PAPER_SCENES`]) to measure errors on.
    pub paper_scenes: Vec<&'static str>,
    /// How many of the closed-form scenes to include (in their fixed order).
    pub closed_form_scenes: usize,
    /// Gap (mm) of the closed-form scenes.
    pub closed_form_gap: f64,
    /// Methods and their settings.
    pub methods: MethodSettings,
    /// Paper tables' work.
    pub tables: TableSettings,
    /// Chordal tolerances (mm) of the growth-with-resolution table.
    pub growth_tolerances: Vec<f64>,
    /// Component counts of the growth-with-components table.
    pub growth_components: Vec<usize>,
    /// Picture size (pixels).
    pub picture_size: (u32, u32),
    /// Object counts of the many-object worlds table.
    pub world_counts: Vec<usize>,
    /// Steps timed per world (medians).
    pub world_steps: usize,
    /// Passes of the coherence table's trajectory timed per way (medians).
    pub coherence_passes: usize,
}

impl ReportSettings {
    /// The full report, as committed in docs/REPORT.md.
    #[must_use]
    pub fn full() -> Self {
        Self {
            paper_scenes: PAPER_SCENES.to_vec(),
            closed_form_scenes: 5,
            closed_form_gap: 0.02,
            methods: MethodSettings {
                chordal: vec![0.2, 0.05, 0.01],
                newton: vec![1e-4, 1e-8, 1e-13],
                parry_triangles: vec![1_000, 5_000, 20_000, 80_000],
                repetitions: 301,
                parry_repetitions: 31,
            },
            tables: TableSettings {
                poses_per_group: 32,
                random_queries: 400,
                repetitions: 21,
            },
            growth_tolerances: vec![0.2, 0.1, 0.05, 0.02, 0.01],
            growth_components: vec![4, 16, 64, 256],
            picture_size: (960, 720),
            world_counts: vec![10, 100, 1000],
            world_steps: 20,
            coherence_passes: 15,
        }
    }

    /// A reduced run (seconds) that exercises every part, for the test that keeps the
    /// generator from rotting. Its numbers mean nothing.
    #[must_use]
    pub fn quick() -> Self {
        Self {
            paper_scenes: vec!["pencil-paperweight"],
            closed_form_scenes: 2,
            closed_form_gap: 0.02,
            methods: MethodSettings {
                chordal: vec![0.2],
                newton: vec![1e-13],
                parry_triangles: vec![1_000],
                repetitions: 3,
                parry_repetitions: 2,
            },
            tables: TableSettings {
                poses_per_group: 2,
                random_queries: 8,
                repetitions: 2,
            },
            growth_tolerances: vec![0.2],
            growth_components: vec![4],
            picture_size: (160, 120),
            world_counts: vec![10],
            world_steps: 2,
            coherence_passes: 1,
        }
    }
}

/// Measures everything and writes `out_dir/REPORT.md`, `out_dir/report/*.svg` and
/// `out_dir/report/*.png`. `root` is the workspace root (fixtures are read from it).
///
/// # Errors
/// A message naming what failed (a scene that does not load, a method that refuses it, an
/// unwritable file).
pub fn write_report(root: &Path, out_dir: &Path, settings: &ReportSettings) -> Result<(), String> {
    let figures = out_dir.join("report");
    std::fs::create_dir_all(&figures).map_err(|e| format!("{}: {e}", figures.display()))?;

    let mut scenes: Vec<AccuracyScene> = Vec::new();
    for scene in closed_form_scenes(settings.closed_form_gap)
        .into_iter()
        .take(settings.closed_form_scenes)
    {
        scenes.push(closed_form_scene(scene)?);
    }
    for name in &settings.paper_scenes {
        scenes.push(paper_scene(root, name)?);
    }
    let mut accuracy = Vec::with_capacity(scenes.len());
    for scene in &scenes {
        eprintln!("report: error against time on {}", scene.name);
        let measurements = error_vs_time::measure_scene(scene, &settings.methods)?;
        let svg = error_vs_time::figure(scene, &measurements)?;
        let file = format!("error-vs-time-{}.svg", scene.slug);
        write(&figures.join(&file), svg.as_bytes())?;
        accuracy.push((scene, measurements, file));
    }

    eprintln!("report: paper tables");
    let table1 = paper_tables::table1(&settings.tables)?;
    let random = paper_tables::random_query_tables(&settings.tables)?;
    let table3 = paper_tables::table3(root, settings.tables.repetitions * 10)?;

    eprintln!("report: growth");
    let growth_resolution = PAPER_SCENES
        .iter()
        .filter(|name| settings.paper_scenes.contains(name))
        .map(|name| {
            stage_growth::with_resolution(
                root,
                name,
                &settings.growth_tolerances,
                settings.tables.repetitions,
            )
            .map(|rows| (*name, rows))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let growth_components =
        stage_growth::with_components(&settings.growth_components, settings.tables.repetitions)?;

    eprintln!("report: stage 2 paths");
    let stage2 = stage2_comparison::measure(root, settings.tables.repetitions * 10)?;

    eprintln!("report: worlds");
    let worlds = crate::world_scene::world_table(
        &crate::fixture_objects(),
        &settings.world_counts,
        settings.world_steps,
    )?;

    eprintln!("report: coherence");
    let coherence = coherence_table::coherence_table(root, settings.coherence_passes)?;

    eprintln!("report: pictures");
    let pictures = settings
        .paper_scenes
        .iter()
        .map(|name| {
            let file = format!("{name}.png");
            pictures::render_paper_scene(root, name, settings.picture_size, &figures.join(&file))
                .map(|()| (*name, file))
        })
        .collect::<Result<Vec<_>, _>>()?;

    let text = writer::markdown(&writer::ReportData {
        machine: machine::MachineInfo::read(),
        settings,
        accuracy: &accuracy,
        table1: &table1,
        random: &random,
        table3: &table3,
        growth_resolution: &growth_resolution,
        growth_components: &growth_components,
        stage2: &stage2,
        pictures: &pictures,
        worlds: &worlds,
        coherence: &coherence,
    });
    write(&out_dir.join("REPORT.md"), text.as_bytes())
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), String> {
    std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}
