//! Shared helpers of the mesh-phase tests: closed-form solids, paper objects, a seeded RNG.
#![allow(dead_code)]

use geom_param::{
    ComponentId, ComponentKind, DPose3, DQuat, DVec3, MeshOptions, ObjectFile, ObjectModel,
    Profile, SegmentSpec,
};
use mesh_narrowphase::{
    ComponentRef, ConcavePath, ContactBand, MeshNarrowphase, MeshNarrowphaseOptions, MeshOutput,
    MeshPhase, MeshScratch, MeshVerdict, PreparedObject,
};

/// Both triangle paths, for suites that hold for either.
pub const PATHS: [ConcavePath; 2] = [ConcavePath::NormalCones, ConcavePath::ProxyRegions];

/// The mesh phase answering concave pairs with `path`.
pub fn phase(path: ConcavePath) -> MeshNarrowphase {
    MeshNarrowphase {
        options: MeshNarrowphaseOptions {
            concave_path: path,
            ..MeshNarrowphaseOptions::default()
        },
    }
}

/// Deterministic xorshift generator.
pub struct Rng(pub u64);

impl Rng {
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// A unit vector (from the cube, normalised; +z in the unlikely zero case).
    pub fn axis(&mut self) -> DVec3 {
        DVec3::new(
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
            self.range(-1.0, 1.0),
        )
        .try_normalize()
        .unwrap_or(DVec3::Z)
    }
    pub fn rotation(&mut self) -> DQuat {
        let axis = self.axis();
        DQuat::from_axis_angle(axis, self.range(0.0, std::f64::consts::TAU))
    }
}

pub fn model(name: &str, specs: &[SegmentSpec], tolerance: f64) -> ObjectModel {
    let profile = Profile::new(specs).expect("valid profile");
    ObjectModel::from_profile(
        name,
        profile,
        &MeshOptions {
            chordal_tolerance: tolerance,
        },
    )
    .expect("valid tolerance")
}

/// Ball of radius `r` centred at the origin.
pub fn sphere(r: f64, tolerance: f64) -> ObjectModel {
    model(
        "sphere",
        &[SegmentSpec::Arc {
            center: [0.0, 0.0],
            from: [0.0, -r],
            to: [0.0, r],
            ccw: true,
        }],
        tolerance,
    )
}

/// Cylinder of radius `r` from z = 0 to z = `h`.
pub fn cylinder(r: f64, h: f64, tolerance: f64) -> ObjectModel {
    model(
        "cylinder",
        &[
            SegmentSpec::Line {
                from: [0.0, 0.0],
                to: [r, 0.0],
            },
            SegmentSpec::Line {
                from: [r, 0.0],
                to: [r, h],
            },
            SegmentSpec::Line {
                from: [r, h],
                to: [0.0, h],
            },
        ],
        tolerance,
    )
}

/// Torus about the z axis with centre-circle radius `rc` and tube radius `a`, split into its
/// upper and lower halves (each a saddle-and-dome face, so the whole ring is one concave
/// component).
pub fn torus(rc: f64, a: f64, tolerance: f64) -> ObjectModel {
    model(
        "torus",
        &[
            SegmentSpec::Arc {
                center: [rc, 0.0],
                from: [rc + a, 0.0],
                to: [rc - a, 0.0],
                ccw: true,
            },
            SegmentSpec::Arc {
                center: [rc, 0.0],
                from: [rc - a, 0.0],
                to: [rc + a, 0.0],
                ccw: true,
            },
        ],
        tolerance,
    )
}

/// A spherical bowl (socket): outer sphere of radius `outer` and inner (concave) sphere of radius
/// `inner`, both centred at (0, 0, `zc`), cut flat at z = `zc` (the rim annulus).
pub fn socket(inner: f64, outer: f64, zc: f64, tolerance: f64) -> ObjectModel {
    model(
        "socket",
        &[
            SegmentSpec::Arc {
                center: [0.0, zc],
                from: [0.0, zc - outer],
                to: [outer, zc],
                ccw: true,
            },
            SegmentSpec::Line {
                from: [outer, zc],
                to: [inner, zc],
            },
            SegmentSpec::Arc {
                center: [0.0, zc],
                from: [inner, zc],
                to: [0.0, zc - inner],
                ccw: false,
            },
        ],
        tolerance,
    )
}

pub fn paper_object(name: &str, tolerance: f64) -> ObjectModel {
    fixture_object(name, tolerance)
}

/// A fixture object of `fixtures/objects/` (a solid of revolution or a general solid), meshed at
/// the chordal `tolerance` (mm).
pub fn fixture_object(name: &str, tolerance: f64) -> ObjectModel {
    let path = format!(
        "{}/../../fixtures/objects/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("fixture exists");
    ObjectFile::from_json(&text)
        .expect("valid fixture")
        .build(&MeshOptions {
            chordal_tolerance: tolerance,
        })
        .expect("valid tolerance")
}

pub fn components_of(object: &ObjectModel, kind: ComponentKind) -> Vec<ComponentId> {
    object
        .components
        .iter()
        .filter(|c| c.kind == kind)
        .map(|c| c.id)
        .collect()
}

/// One prepared object.
pub struct Prepared {
    pub object: ObjectModel,
    pub prepared: PreparedObject,
}

impl Prepared {
    pub fn new(object: ObjectModel) -> Self {
        let prepared = MeshNarrowphase::default().prepare(&object);
        Self { object, prepared }
    }
    pub fn component(&self, id: ComponentId) -> ComponentRef<'_, PreparedObject> {
        ComponentRef {
            object: &self.object,
            prepared: &self.prepared,
            component: id,
        }
    }
}

pub fn query(
    a: &Prepared,
    ca: ComponentId,
    b: &Prepared,
    cb: ComponentId,
    pose_ab: &DPose3,
    band: &ContactBand,
    scratch: &mut MeshScratch,
) -> (MeshVerdict, MeshOutput) {
    query_path(
        ConcavePath::default(),
        (a, ca),
        (b, cb),
        pose_ab,
        band,
        scratch,
    )
}

/// As [`query`], with the triangle path `path`.
pub fn query_path(
    path: ConcavePath,
    (a, ca): (&Prepared, ComponentId),
    (b, cb): (&Prepared, ComponentId),
    pose_ab: &DPose3,
    band: &ContactBand,
    scratch: &mut MeshScratch,
) -> (MeshVerdict, MeshOutput) {
    let mut out = MeshOutput::default();
    let verdict = phase(path).query(
        a.component(ca),
        b.component(cb),
        pose_ab,
        band,
        scratch,
        &mut out,
    );
    (verdict, out)
}

pub fn pose(rotation: DQuat, translation: DVec3) -> DPose3 {
    DPose3 {
        rotation,
        translation,
    }
}
