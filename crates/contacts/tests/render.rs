//! Pictures of contact scenes: decoded and checked pixel by pixel against where the camera
//! puts the pipeline's contact points (no PNG snapshots).
#![cfg(feature = "render")]

use contacts::render::{
    BACKGROUND, MAX_SIDE, NORMAL_COLOUR, PENETRATION_COLOUR, POINT_A_COLOUR, POINT_B_COLOUR,
    RenderError, RenderOptions, RenderedScene, render_scene,
};
use contacts::run::{PreparedScene, prepare_scene};
use glam::{DVec2, DVec3};
use std::path::{Path, PathBuf};
use std::process::Command;
use tiny_skia::Pixmap;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/scenes")
        .join(format!("{name}.json"))
}

fn scene(name: &str) -> PreparedScene {
    prepare_scene(&fixture(name)).expect("fixture scene loads")
}

fn small() -> RenderOptions {
    RenderOptions {
        width: 200,
        height: 150,
        zoom_contacts: false,
    }
}

/// The picture as a decoder reads it back from the PNG bytes.
fn decoded(rendered: &RenderedScene) -> Pixmap {
    Pixmap::decode_png(&rendered.png_bytes().expect("encodes")).expect("decodes")
}

fn rgb(pixmap: &Pixmap, p: DVec2) -> [u8; 3] {
    assert!(p.x >= 0.0 && p.y >= 0.0, "{p} inside the picture");
    let c = pixmap
        .pixel(p.x as u32, p.y as u32)
        .unwrap_or_else(|| panic!("{p} inside the picture"));
    assert_eq!(c.alpha(), 255, "opaque picture");
    [c.red(), c.green(), c.blue()]
}

fn all_rgb(pixmap: &Pixmap) -> impl Iterator<Item = [u8; 3]> + '_ {
    pixmap
        .pixels()
        .iter()
        .map(|c| [c.red(), c.green(), c.blue()])
}

const MARKER_COLOURS: [[u8; 3]; 4] = [
    POINT_A_COLOUR,
    POINT_B_COLOUR,
    PENETRATION_COLOUR,
    NORMAL_COLOUR,
];

#[test]
fn two_contacts_are_marked_where_the_camera_projects_them() {
    let scene = scene("pencil-paperweight-two-contacts");
    let rendered = render_scene(&scene, &small()).expect("renders");
    let picture = decoded(&rendered);
    assert_eq!((picture.width(), picture.height()), (200, 150));
    let contacts: Vec<_> = rendered
        .pairs
        .iter()
        .flat_map(|p| &p.report.contacts)
        .collect();
    assert_eq!(contacts.len(), 2, "the fixture has two contacts");
    let camera = &rendered.camera;
    let style = &rendered.markers;
    for c in contacts {
        // B's dot is drawn last, centred on B's point.
        assert_eq!(rgb(&picture, camera.project(c.point_b)), POINT_B_COLOUR);
        // A's dot shows round it; look on the side away from the normal arrow, between the
        // two dots' rims (a pixel there lies wholly inside A's dot and outside B's).
        let away = -camera.project_direction(c.normal).normalize();
        let offset = 0.75 * f64::from(style.dot_a_radius);
        assert!(offset - 0.75 > f64::from(style.dot_b_radius));
        assert!(offset + 0.75 < f64::from(style.dot_a_radius));
        let beside = camera.project(c.point_a) + offset * away;
        assert_eq!(rgb(&picture, beside), POINT_A_COLOUR);
        // The arrow's shaft, a third of the way along the normal's screen direction.
        let along = camera.project(c.point_a) - (f64::from(style.arrow_length) / 3.0) * away;
        assert_eq!(rgb(&picture, along), NORMAL_COLOUR);
    }
}

/// Distance (pixels) from `p` to the segment [a, b].
fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
    p.distance(a + t * (b - a))
}

#[test]
fn objects_are_drawn_in_their_colours_on_a_background() {
    let scene = scene("pencil-paperweight-two-contacts");
    let rendered = render_scene(&scene, &small()).expect("renders");
    let picture = decoded(&rendered);
    // The mean of the highest quarter of each object's mesh vertices is inside the object
    // (both are convex there) and far from the contacts, so it lands on that object: the
    // paperweight (object 0) blue-grey, the pencil (object 1) sandy.
    let camera = &rendered.camera;
    let style = &rendered.markers;
    // Each contact's marker, as a screen segment (the normal arrow from A's point) and how far
    // round it ink or halo may reach (dot, arrowhead half-width, halo, anti-aliasing).
    let markers: Vec<(DVec2, DVec2)> = rendered
        .pairs
        .iter()
        .flat_map(|p| &p.report.contacts)
        .map(|c| {
            let from = camera.project(c.point_a);
            let direction = camera.project_direction(c.normal).normalize();
            (from, from + f64::from(style.arrow_length) * direction)
        })
        .collect();
    let head = (3.5 * style.line_width).max(0.3 * style.arrow_length);
    let reach = f64::from(style.dot_a_radius.max(0.45 * head) + style.halo) + 1.5;
    for (i, (prepared, placed)) in scene.objects.iter().zip(&scene.scene.objects).enumerate() {
        let mut vertices: Vec<DVec3> = prepared
            .model
            .meshes
            .iter()
            .flat_map(|m| &m.positions)
            .map(|&p| placed.pose * p)
            .collect();
        vertices.sort_by(|a, b| b.z.total_cmp(&a.z));
        let top = &vertices[..vertices.len() / 4];
        let inside = camera.project(top.iter().sum::<DVec3>() / top.len() as f64);
        assert!(
            markers
                .iter()
                .all(|&(a, b)| segment_distance(inside, a, b) > reach),
            "object {i}'s test pixel {inside} is clear of the markers"
        );
        let [r, _, b] = rgb(&picture, inside);
        match i {
            0 => assert!(b > r, "paperweight pixel is blue-grey: {r} {b}"),
            _ => assert!(r > b, "pencil pixel is sandy: {r} {b}"),
        }
    }
    let (w, h) = (picture.width(), picture.height());
    for (x, y) in [(0, 0), (w - 1, 0), (0, h - 1), (w - 1, h - 1)] {
        let c = picture.pixel(x, y).expect("corner");
        assert_eq!(
            [c.red(), c.green(), c.blue()],
            BACKGROUND,
            "corner ({x}, {y})"
        );
    }
    // The scene is fitted: it spans at least 70% of the room inside the 8% margins in one
    // direction, and a tenth of the picture is not background.
    let drawn = all_rgb(&picture).filter(|c| *c != BACKGROUND).count();
    assert!(drawn * 10 > (w * h) as usize, "{drawn} drawn pixels");
    let (mut lo, mut hi) = ([u32::MAX; 2], [0; 2]);
    for y in 0..h {
        for x in 0..w {
            let c = picture.pixel(x, y).expect("pixel");
            if [c.red(), c.green(), c.blue()] != BACKGROUND {
                lo = [lo[0].min(x), lo[1].min(y)];
                hi = [hi[0].max(x), hi[1].max(y)];
            }
        }
    }
    let room = [w as f64 * 0.84, h as f64 * 0.84];
    assert!(
        f64::from(hi[0] - lo[0]) > 0.7 * room[0] || f64::from(hi[1] - lo[1]) > 0.7 * room[1],
        "drawn box {lo:?}..{hi:?}"
    );
}

#[test]
fn separated_scene_has_no_markers() {
    let rendered = render_scene(&scene("pencil-paperweight-separated"), &small()).expect("renders");
    assert!(rendered.pairs.iter().all(|p| p.report.contacts.is_empty()));
    let picture = decoded(&rendered);
    assert!(all_rgb(&picture).any(|c| c != BACKGROUND), "objects drawn");
    assert!(
        all_rgb(&picture).all(|c| !MARKER_COLOURS.contains(&c)),
        "no marker colour"
    );
}

#[test]
fn penetration_witnesses_are_red_crosses() {
    let rendered = render_scene(&scene("pencil-bowl-penetrating"), &small()).expect("renders");
    let witnesses: Vec<DVec3> = rendered
        .pairs
        .iter()
        .flat_map(|p| p.report.penetration_witnesses.iter().copied())
        .collect();
    assert!(!witnesses.is_empty(), "the fixture penetrates");
    let picture = decoded(&rendered);
    for w in witnesses {
        assert_eq!(
            rgb(&picture, rendered.camera.project(w)),
            PENETRATION_COLOUR
        );
    }
}

#[test]
fn zooming_on_contacts_magnifies_and_keeps_them_in_the_picture() {
    let scene = scene("vase-vase-two-contacts");
    let whole = render_scene(&scene, &small()).expect("renders");
    let zoomed = render_scene(
        &scene,
        &RenderOptions {
            zoom_contacts: true,
            ..small()
        },
    )
    .expect("renders");
    assert!(zoomed.camera.scale > 1.5 * whole.camera.scale);
    let picture = decoded(&zoomed);
    for c in zoomed.pairs.iter().flat_map(|p| &p.report.contacts) {
        assert_eq!(
            rgb(&picture, zoomed.camera.project(c.point_b)),
            POINT_B_COLOUR
        );
    }
}

#[test]
fn unusable_sizes_are_refused() {
    let scene = scene("pencil-paperweight-two-contacts");
    for (width, height) in [(0, 100), (100, 0), (MAX_SIDE + 1, 10), (10, u32::MAX)] {
        let options = RenderOptions {
            width,
            height,
            zoom_contacts: false,
        };
        assert!(
            matches!(
                render_scene(&scene, &options),
                Err(RenderError::BadSize { width: w, height: h }) if (w, h) == (width, height)
            ),
            "{width} x {height}"
        );
    }
}

fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_contacts"))
        .args(args)
        .output()
        .expect("binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn cli_writes_a_png_and_refuses_bad_input_with_status_2() {
    let dir = std::env::temp_dir().join(format!("contacts-render-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let out = dir.join("scene.png");
    let scene_path = fixture("pencil-bowl-two-contacts");
    let scene_arg = scene_path.to_str().expect("utf-8 path");
    let out_arg = out.to_str().expect("utf-8 path");
    let (code, stdout, stderr) = run(&[
        "render", scene_arg, "-o", out_arg, "--width", "160", "--height", "120",
    ]);
    assert_eq!(code, 0, "stderr: {stderr}");
    assert!(stdout.contains("\"contacts\":2"), "{stdout}");
    let picture = Pixmap::decode_png(&std::fs::read(&out).expect("written")).expect("PNG");
    assert_eq!((picture.width(), picture.height()), (160, 120));

    for (args, needle) in [
        (
            vec!["render", "/nonexistent/scene.json", "-o", out_arg],
            "cannot read",
        ),
        (
            vec!["render", scene_arg, "-o", out_arg, "--width", "0"],
            "picture size 0 x 768",
        ),
        (
            vec!["render", scene_arg, "-o", "/nonexistent/dir/x.png"],
            "cannot write",
        ),
    ] {
        let (code, stdout, stderr) = run(&args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{args:?}: {stdout}");
        assert!(stderr.contains(needle), "{args:?}: {stderr}");
        assert_eq!(
            stderr.trim_end().lines().count(),
            1,
            "one message: {stderr}"
        );
    }
    std::fs::remove_dir_all(&dir).expect("clean up");
}
