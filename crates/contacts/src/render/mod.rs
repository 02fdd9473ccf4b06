//! Pictures of contact scenes (cargo feature `render`): both objects flat-shaded, every
//! contact's closest points and normal marked, rendered in software with tiny-skia to PNG.
//!
//! The view is orthographic, looking perpendicular to the first contact normal from a little
//! above (see [`Camera`]), chosen deterministically so that the contacts are visible; the
//! whole scene, or with [`RenderOptions::zoom_contacts`] the contacts' neighbourhood, is
//! fitted inside a margin. Objects are painted far to near (painter's algorithm) with back
//! faces culled; markers are drawn on top of everything.

mod camera;
mod markers;
mod shading;
mod view;
mod world_mesh;

pub use camera::{Camera, WORLD_UP};
pub use markers::{MarkerStyle, NORMAL_COLOUR, PENETRATION_COLOUR, POINT_A_COLOUR, POINT_B_COLOUR};
pub use shading::{BACKGROUND, OBJECT_COLOURS};

use crate::run::PreparedScene;
use contact_pipeline::{PairReport, QueryError, QueryScratch};
use glam::{DVec2, DVec3};
use std::path::{Path, PathBuf};
use tiny_skia::{Color, Pixmap};

/// Largest picture side (pixels) accepted: 16384 × 16384 RGBA is 1 GiB.
pub const MAX_SIDE: u32 = 16384;

/// Border round the fitted scene, as a fraction of the picture's smaller side.
const MARGIN_FRACTION: f64 = 0.08;

/// With [`RenderOptions::zoom_contacts`]: room shown round the contacts, as a fraction of the
/// scene's diameter.
const ZOOM_PADDING_FRACTION: f64 = 0.08;

/// What to render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderOptions {
    /// Picture width (pixels), in 1..=[`MAX_SIDE`].
    pub width: u32,
    /// Picture height (pixels), in 1..=[`MAX_SIDE`].
    pub height: u32,
    /// Fit the contacts (and penetration witnesses) with some surroundings instead of the whole
    /// scene; ignored when there are none.
    pub zoom_contacts: bool,
}

impl Default for RenderOptions {
    /// 1024 × 768, whole scene.
    fn default() -> Self {
        Self {
            width: 1024,
            height: 768,
            zoom_contacts: false,
        }
    }
}

/// Why a scene could not be rendered or written.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A picture side is zero or larger than [`MAX_SIDE`].
    #[error(
        "picture size {width} x {height} is not usable (each side must be 1 to {MAX_SIDE} pixels)"
    )]
    BadSize {
        /// Requested width (pixels).
        width: u32,
        /// Requested height (pixels).
        height: u32,
    },
    /// The contact query of a pair failed.
    #[error("query: {0}")]
    Query(#[from] QueryError),
    /// PNG encoding failed.
    #[error("PNG encoding: {0}")]
    Png(String),
    /// The PNG file could not be written.
    #[error("cannot write {path}: {message}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The system's message.
        message: String,
    },
}

/// One pair's query result, as drawn.
#[derive(Clone, Debug)]
pub struct DrawnPair {
    /// Scene indices (i, j), i < j, of objects A and B.
    pub pair: (usize, usize),
    /// The pipeline's report for the pair.
    pub report: PairReport,
}

/// A rendered scene: the picture, how it was taken, and what was marked.
#[derive(Clone, Debug)]
pub struct RenderedScene {
    /// The picture (opaque, premultiplied RGBA).
    pub pixmap: Pixmap,
    /// The camera: [`Camera::project`] tells where a world point landed.
    pub camera: Camera,
    /// The marker sizes used.
    pub markers: MarkerStyle,
    /// Every pair's report, in [`PreparedScene::pairs`] order.
    pub pairs: Vec<DrawnPair>,
}

impl RenderedScene {
    /// The picture as PNG bytes.
    ///
    /// # Errors
    /// [`RenderError::Png`] if encoding fails.
    pub fn png_bytes(&self) -> Result<Vec<u8>, RenderError> {
        self.pixmap
            .encode_png()
            .map_err(|e| RenderError::Png(e.to_string()))
    }

    /// Writes the picture as a PNG file.
    ///
    /// # Errors
    /// [`RenderError::Png`] if encoding fails, [`RenderError::Io`] if writing does.
    pub fn write_png(&self, path: &Path) -> Result<(), RenderError> {
        std::fs::write(path, self.png_bytes()?).map_err(|e| RenderError::Io {
            path: path.to_path_buf(),
            message: e.to_string(),
        })
    }
}

/// Queries every pair of `scene` and renders it with the contacts marked.
///
/// # Errors
/// [`RenderError::BadSize`] for an unusable picture size (checked before any work),
/// [`RenderError::Query`] if a pair's query fails.
pub fn render_scene(
    scene: &PreparedScene,
    options: &RenderOptions,
) -> Result<RenderedScene, RenderError> {
    let (width, height) = (options.width, options.height);
    let bad_size = RenderError::BadSize { width, height };
    if !(1..=MAX_SIDE).contains(&width) || !(1..=MAX_SIDE).contains(&height) {
        return Err(bad_size);
    }
    let mut pixmap = Pixmap::new(width, height).ok_or(bad_size)?;
    let mut scratch = QueryScratch::default();
    let pairs = scene
        .pairs()
        .into_iter()
        .map(|pair| {
            Ok(DrawnPair {
                pair,
                report: scene.query(pair, &mut scratch)?,
            })
        })
        .collect::<Result<Vec<_>, QueryError>>()?;

    let triangles = world_mesh::world_triangles(scene);
    let size = world_mesh::bounds(&triangles).map_or(1.0, |(lo, hi)| (hi - lo).length());
    let reports = || pairs.iter().map(|p| &p.report);
    let marked: Vec<DVec3> = reports()
        .flat_map(|r| {
            r.contacts
                .iter()
                .flat_map(|c| [c.point_a, c.point_b])
                .chain(r.penetration_witnesses.iter().copied())
        })
        .collect();
    let first_normal = reports().flat_map(|r| &r.contacts).map(|c| c.normal).next();
    let forward = view::choose_forward(first_normal, &marked, &triangles, size);

    let zoom = options.zoom_contacts && !marked.is_empty();
    let frame = |camera: &Camera| {
        let screen = |p: DVec3| camera.screen_mm(p);
        let (mut lo, mut hi) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        let mut include = |p: DVec2| {
            lo = lo.min(p);
            hi = hi.max(p);
        };
        marked.iter().for_each(|&p| include(screen(p)));
        if zoom {
            let pad = DVec2::splat(ZOOM_PADDING_FRACTION * size);
            return (lo - pad, hi + pad);
        }
        triangles
            .iter()
            .flat_map(|t| t.corners)
            .for_each(|p| include(screen(p)));
        if lo.x > hi.x {
            (DVec2::ZERO, DVec2::ZERO)
        } else {
            (lo, hi)
        }
    };
    let margin = MARGIN_FRACTION * f64::from(width.min(height));
    let camera = Camera::fitting(forward, frame, width, height, margin);

    pixmap.fill(Color::from_rgba8(
        BACKGROUND[0],
        BACKGROUND[1],
        BACKGROUND[2],
        255,
    ));
    shading::paint_objects(&mut pixmap, &camera, &triangles);
    let markers = MarkerStyle::for_picture(width, height);
    markers::draw_markers(&mut pixmap, &camera, &markers, reports());
    Ok(RenderedScene {
        pixmap,
        camera,
        markers,
        pairs,
    })
}
