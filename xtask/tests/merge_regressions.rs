//! Two minima merged into one because one was near a conformal touch, found by the swap and
//! rigid-motion properties of `soak 10000 --seed 8105` (goblet-bowl 5784345834712098383): the
//! goblet's wall touching the bowl's inside at 3.7e-10 mm (condition 8e11, point error
//! estimate 0.13 mm), and a separate minimum 12.6 mm away at 0.0225 mm. The touch's merge
//! tolerance (100 x its point error estimate, 13 mm) took the other minimum in as the same
//! contact, and kept whichever had the smaller gradient, so one of the two was lost, depending
//! on the seeds' order.
//!
//! Truth: the swap property (A and B exchanged: the same contacts with points exchanged), and
//! the two contacts' own invariants: distances that differ by far more than both error
//! estimates, and connecting vectors along both surface normals.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3};
use xtask::soak::run::prepare_objects;

#[test]
fn a_conformal_touch_does_not_swallow_a_minimum_12_mm_away() {
    let options = ContactOptions::default();
    let pipeline = ContactPipeline::new(options).expect("default options");
    let objects = prepare_objects(&pipeline).expect("fixture objects build");
    let (goblet, bowl) = (&objects["goblet"], &objects["bowl"]);
    let pose_b = DPose3 {
        rotation: DQuat::from_xyzw(
            -0.8907255613938031,
            0.41604826547698964,
            -0.008447037801193064,
            -0.18286733613652253,
        ),
        translation: DVec3::new(-47.3094409399043, 6.126421174034504, 71.37104933276184),
    };
    let mut scratch = QueryScratch::default();
    let base = pipeline
        .query(goblet, &DPose3::IDENTITY, bowl, &pose_b, &mut scratch)
        .expect("unit quaternion");
    let swapped = pipeline
        .query(bowl, &pose_b, goblet, &DPose3::IDENTITY, &mut scratch)
        .expect("unit quaternion");
    for (report, order) in [(&base, "goblet-bowl"), (&swapped, "bowl-goblet")] {
        assert_eq!(report.state, PairState::Contact, "{order}: {report:?}");
        let mut distances: Vec<f64> = report.contacts.iter().map(|c| c.distance).collect();
        distances.sort_by(f64::total_cmp);
        assert_eq!(distances.len(), 2, "{order}: {report:?}");
        assert!(distances[0].abs() <= 1e-7, "{order}: {distances:?}");
        assert!(
            (distances[1] - 0.022537536984).abs() <= 1e-9,
            "{order}: {distances:?}"
        );
        let far = report
            .contacts
            .iter()
            .find(|c| c.distance > 0.01)
            .expect("the 0.0225 mm minimum");
        let near = report
            .contacts
            .iter()
            .find(|c| c.distance < 0.01)
            .expect("the touch");
        assert!(far.point_a.distance(near.point_a) > 10.0, "{order}");
        assert!(far.diagnostics.error_estimate < 1e-9, "{far:?}");
        // The connecting vector is along the normal (A to B) at the isolated minimum.
        let along = (far.point_b - far.point_a).normalize();
        assert!(along.angle_between(far.normal) <= 1e-6, "{far:?}");
    }
}
