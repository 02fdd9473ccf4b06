//! The scenes whose contacts the report measures errors on, each with its true contacts: the
//! closed form where there is one, otherwise the independent oracle (`contact-oracle`: dense
//! sampling of both exact surfaces, each minimum polished by plain Newton, cross-checked).

use contact_oracle::{ClosedFormScene, OracleContact, OracleOptions, closed_form, find_contacts};
use contacts::scene::Scene;
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectDescription, ObjectFile, Solid};
use std::path::Path;

/// A contact taken as the truth (world frame, mm).
#[derive(Clone, Copy, Debug)]
pub struct TrueContact {
    /// On A.
    pub point_a: DVec3,
    /// On B.
    pub point_b: DVec3,
    /// Signed distance.
    pub distance: f64,
}

impl From<&OracleContact> for TrueContact {
    fn from(c: &OracleContact) -> Self {
        Self {
            point_a: c.point_a,
            point_b: c.point_b,
            distance: c.distance,
        }
    }
}

/// A pair of objects, their poses and their true contacts.
pub struct AccuracyScene {
    /// Name used in tables.
    pub name: String,
    /// File-name form of the name: lowercase letters, digits and '-'.
    pub slug: String,
    /// Object A.
    pub a: ObjectDescription,
    /// Placement of A.
    pub pose_a: DPose3,
    /// Object B.
    pub b: ObjectDescription,
    /// Placement of B.
    pub pose_b: DPose3,
    /// Every true contact inside the default band.
    pub truth: Vec<TrueContact>,
    /// Where the truth comes from, in words (closed form, or the oracle with its cross-check).
    pub truth_source: String,
    /// For closed-form scenes: the oracle's worst disagreement with the closed form
    /// (distance, points; mm), so that the report shows the oracle is tested, not trusted.
    pub oracle_check: Option<(f64, f64)>,
}

/// The four paper scenes (fixtures/scenes/*-two-contacts.json) under `root`.
pub const PAPER_SCENES: [&str; 4] = [
    "pencil-paperweight",
    "paperweight-goblet",
    "pencil-bowl",
    "vase-vase",
];

/// The band the truth is cut to (the pipeline's default contact band).
const DELTA1: f64 = -0.001;
const DELTA2: f64 = 0.1;

/// The exact solid of a description (the mesh tolerance does not change the exact solid).
fn solid(description: &ObjectDescription) -> Result<Solid, String> {
    let scale = geom_param::Profile::new(&description.profile)
        .map_err(|e| format!("{}: {e}", description.name))?
        .scale();
    description
        .build(&MeshOptions {
            chordal_tolerance: (0.02 * scale).max(0.01),
        })
        .map(|model| model.solid)
        .map_err(|e| format!("{}: {e}", description.name))
}

/// A paper scene with the oracle's contacts as truth.
///
/// # Errors
/// A message if the scene does not load or the oracle refuses it.
pub fn paper_scene(root: &Path, name: &str) -> Result<AccuracyScene, String> {
    let path = root.join(format!("fixtures/scenes/{name}-two-contacts.json"));
    let scene = Scene::from_file(&path).map_err(|e| format!("{name}: {e}"))?;
    let [oa, ob] = scene.objects.as_slice() else {
        return Err(format!("{name}: expected two objects"));
    };
    let revolved = |file: &ObjectFile| match file {
        ObjectFile::Revolved(d) => Ok(d.clone()),
        ObjectFile::General(d) => Err(format!(
            "{name}: {} is not a solid of revolution (the mesh baseline needs a profile)",
            d.name
        )),
    };
    let (da, db) = (revolved(&oa.description)?, revolved(&ob.description)?);
    let (sa, sb) = (solid(&da)?, solid(&db)?);
    let options = OracleOptions::for_solids(&sa, &sb, DELTA2);
    let oracle = find_contacts(&sa, &oa.pose, &sb, &ob.pose, &options)
        .map_err(|e| format!("{name}: oracle: {e}"))?;
    let truth: Vec<TrueContact> = oracle
        .in_band(DELTA1, DELTA2)
        .map(TrueContact::from)
        .collect();
    let check = &oracle.cross_check;
    Ok(AccuracyScene {
        name: name.to_string(),
        slug: slug(name),
        a: da,
        pose_a: oa.pose,
        b: db,
        pose_b: ob.pose,
        truth,
        truth_source: format!(
            "oracle ({} samples; two samplings agree to {:.1e} mm in distance, {:.1e} mm in points, {} unmatched)",
            oracle.samples,
            check.max_distance_difference,
            check.max_point_difference,
            check.unmatched
        ),
        oracle_check: None,
    })
}

/// A closed-form scene with its closed-form contacts as truth, and the oracle run on it too.
///
/// # Errors
/// A message if a builder's object does not build or the oracle refuses it.
pub fn closed_form_scene(scene: ClosedFormScene) -> Result<AccuracyScene, String> {
    let (sa, sb) = (solid(&scene.a)?, solid(&scene.b)?);
    let options = OracleOptions::for_solids(&sa, &sb, DELTA2);
    let oracle = find_contacts(&sa, &scene.pose_a, &sb, &scene.pose_b, &options)
        .map_err(|e| format!("{}: oracle: {e}", scene.name))?;
    let truth: Vec<TrueContact> = scene
        .expected
        .iter()
        .map(|c| TrueContact {
            point_a: c.point_a,
            point_b: c.point_b,
            distance: c.distance,
        })
        .collect();
    let found: Vec<TrueContact> = oracle
        .in_band(DELTA1, DELTA2)
        .map(TrueContact::from)
        .collect();
    let oracle_check = (found.len() == truth.len()).then(|| {
        truth.iter().fold((0.0_f64, 0.0_f64), |(dd, dp), t| {
            let nearest = found
                .iter()
                .min_by(|x, y| {
                    x.point_a
                        .distance(t.point_a)
                        .total_cmp(&y.point_a.distance(t.point_a))
                })
                .copied()
                .unwrap_or(*t);
            (
                dd.max((nearest.distance - t.distance).abs()),
                dp.max(
                    nearest
                        .point_a
                        .distance(t.point_a)
                        .max(nearest.point_b.distance(t.point_b)),
                ),
            )
        })
    });
    Ok(AccuracyScene {
        slug: slug(&scene.name),
        name: scene.name,
        a: scene.a,
        pose_a: scene.pose_a,
        b: scene.b,
        pose_b: scene.pose_b,
        truth,
        truth_source: "closed form".to_string(),
        oracle_check: oracle_check.or(Some((f64::INFINITY, f64::INFINITY))),
    })
}

/// `name` with every run of characters other than ASCII letters and digits replaced by one
/// '-', lowercased, without leading or trailing '-': "sphere_on_sphere(r1 10)" becomes
/// "sphere-on-sphere-r1-10".
fn slug(name: &str) -> String {
    name.to_ascii_lowercase()
        .split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|part| !part.is_empty())
        .collect::<Vec<_>>()
        .join("-")
}

/// The closed-form scenes of the report: four at a gap of `gap` mm, then spheres overlapping by
/// 0.0005 mm.
#[must_use]
pub fn closed_form_scenes(gap: f64) -> Vec<ClosedFormScene> {
    let tilted = DVec3::new(0.3, -0.5, 0.81).normalize();
    vec![
        closed_form::sphere_on_sphere(
            10.0,
            15.0,
            gap,
            tilted,
            [DQuat::from_rotation_x(0.4), DQuat::from_rotation_y(-0.7)],
        ),
        closed_form::sphere_in_bowl(8.0, 20.0, gap, 0.3, 1.1, DQuat::from_rotation_z(0.5)),
        closed_form::crossed_cylinders(5.0, 8.0, gap, 60.0),
        closed_form::torus_on_plane(20.0, 4.0, 0.3, gap),
        // Overlapping by 0.5 µm: still a contact in the band [-0.001, 0.1] mm, with a negative
        // distance, and below the meshes' chordal errors.
        closed_form::sphere_on_sphere(
            10.0,
            15.0,
            -0.0005,
            tilted,
            [DQuat::from_rotation_x(0.4), DQuat::from_rotation_y(-0.7)],
        ),
    ]
}
