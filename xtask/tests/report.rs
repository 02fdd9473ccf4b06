//! The report generator runs end to end on a reduced setting (no timing is asserted), so that
//! `cargo xtask report` cannot rot between the runs that regenerate docs/REPORT.md.

use std::path::Path;
use xtask::report::{ReportSettings, write_report};

#[test]
fn quick_report_writes_every_section_and_figure() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("quick-report");
    let _ = std::fs::remove_dir_all(&out);
    write_report(&root, &out, &ReportSettings::quick()).expect("report runs");

    let text = std::fs::read_to_string(out.join("REPORT.md")).expect("REPORT.md written");
    for heading in [
        "## 1. Error against run time",
        "### Truth",
        "### Ratios",
        "## 2. The paper's tables beside ours",
        "### Table 1",
        "### Fig. 2",
        "### Table 2",
        "### Table 3",
        "## 3. Where the time goes",
        "### Growth with mesh resolution",
        "### Growth with the number of components",
        "### Stage 2: proxy regions against normal cones",
        "## 4. Pictures",
        "## 5. Many-object worlds",
        "## 6. Frame-to-frame coherence",
    ] {
        assert!(text.contains(heading), "missing section {heading:?}");
    }
    assert!(!text.contains("NaN"), "a NaN reached the report");

    // Every linked figure exists and is the format its name says.
    let links: Vec<&str> = text
        .split("](report/")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .collect();
    assert!(links.iter().any(|l| l.ends_with(".svg")), "no SVG figure");
    assert!(links.iter().any(|l| l.ends_with(".png")), "no picture");
    for link in links {
        let bytes = std::fs::read(out.join("report").join(link)).expect("linked figure exists");
        if link.ends_with(".svg") {
            assert!(String::from_utf8_lossy(&bytes).contains("<svg"), "{link}");
        } else {
            assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "{link}");
        }
    }

    // The closed-form scenes are scored against their closed forms: the exact pipeline finds
    // every true contact there (a reduced run still measures real answers).
    let sphere = text
        .split("### sphere_on_sphere")
        .nth(1)
        .expect("a sphere scene section");
    let exact_row = sphere
        .lines()
        .find(|l| l.starts_with("| exact (ours"))
        .expect("an exact row");
    let missed: usize = exact_row.split('|').nth(7).unwrap().trim().parse().unwrap();
    assert_eq!(missed, 0, "{exact_row}");
}
