//! A surface with its outward side flipped (a hole's inner wall, a STEP face with
//! same_sense = false).

use crate::curves::curve::ParamRange;
use crate::surfaces::surface::{PrincipalCurvatures, Surface, SurfacePoint};
use glam::DVec3;

/// The points of `inner` with the opposite outward normal.
///
/// Parameter map: S'(u, v) = S(u, −v), so the domain of v' is [−v_max, −v_min] (periodicity
/// kept) and a point of S at (u, v) is the point of S' at (u, −v). Derivatives: S'_u = S_u,
/// S'_v = −S_v, S'_uu = S_uu, S'_uv = −S_uv, S'_vv = S_vv; hence S'_u × S'_v = −(S_u × S_v),
/// and the principal curvatures change sign (min' = −max, max' = −min).
///
/// Generic over the inner surface (a `Box<dyn Surface>` by default, or a concrete surface for
/// static dispatch and `Clone`/`PartialEq`).
#[derive(Clone, Debug, PartialEq)]
pub struct ReversedSurface<S: Surface = Box<dyn Surface>> {
    /// The surface whose outward side is flipped.
    pub inner: S,
}

impl<S: Surface> Surface for ReversedSurface<S> {
    fn eval(&self, u: f64, v: f64) -> SurfacePoint {
        let p = self.inner.eval(u, -v);
        SurfacePoint {
            point: p.point,
            du: p.du,
            dv: -p.dv,
            duu: p.duu,
            duv: -p.duv,
            dvv: p.dvv,
        }
    }

    fn domain(&self) -> [ParamRange; 2] {
        let [u, v] = self.inner.domain();
        [
            u,
            ParamRange {
                min: -v.max,
                max: -v.min,
                periodic: v.periodic,
            },
        ]
    }

    /// −(the inner normal at (u, −v)), so the inner surface's pole and apex handling carries
    /// over.
    fn normal(&self, u: f64, v: f64) -> Option<DVec3> {
        self.inner.normal(u, -v).map(|n| -n)
    }

    fn principal_curvatures(&self, u: f64, v: f64) -> Option<PrincipalCurvatures> {
        self.inner
            .principal_curvatures(u, -v)
            .map(|k| PrincipalCurvatures {
                min: -k.max,
                max: -k.min,
            })
    }
}
