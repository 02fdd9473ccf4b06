//! The iso-parametric curve along a side of a surface's parameter rectangle: the exact edge
//! curve of two rectangle faces sewn along a side.

use crate::curves::curve::{Curve, CurvePoint, ParamRange};
use crate::surfaces::surface::Surface;
use crate::topology::solid::ParamSide;

/// C(t) = S(side point at running parameter t): S(u_min, t), S(u_max, t), S(t, v_min) or
/// S(t, v_max), over the running parameter's range (periodic when the surface is).
#[derive(Clone, Debug, PartialEq)]
pub struct IsoCurve<S: Surface> {
    /// The surface (a copy of the face's).
    pub surface: S,
    /// The side the curve runs along.
    pub side: ParamSide,
}

impl<S: Surface> Curve for IsoCurve<S> {
    fn eval(&self, t: f64) -> CurvePoint {
        let [ru, rv] = self.surface.domain();
        match self.side {
            ParamSide::UMin | ParamSide::UMax => {
                let u = if self.side == ParamSide::UMin {
                    ru.min
                } else {
                    ru.max
                };
                let s = self.surface.eval(u, t);
                CurvePoint {
                    point: s.point,
                    d1: s.dv,
                    d2: s.dvv,
                }
            }
            ParamSide::VMin | ParamSide::VMax => {
                let v = if self.side == ParamSide::VMin {
                    rv.min
                } else {
                    rv.max
                };
                let s = self.surface.eval(t, v);
                CurvePoint {
                    point: s.point,
                    d1: s.du,
                    d2: s.duu,
                }
            }
        }
    }

    fn domain(&self) -> ParamRange {
        let [ru, rv] = self.surface.domain();
        match self.side {
            ParamSide::UMin | ParamSide::UMax => rv,
            ParamSide::VMin | ParamSide::VMax => ru,
        }
    }
}
