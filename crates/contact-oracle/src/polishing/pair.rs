//! A pair of points, one on each solid, as the polishers move it: each point's face, (u, v)
//! and feature (free on the face, held on an edge or at a vertex).

use crate::polishing::linalg::N;
use crate::solids::held::Held;
use geom_param::FaceId;

/// A pair of points: A's face and (u, v), B's face and (u, v), and for each whether it is free
/// on that face or held on an edge or vertex of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Pair {
    pub fa: FaceId,
    pub a: [f64; 2],
    pub fb: FaceId,
    pub b: [f64; 2],
    pub held_a: Held,
    pub held_b: Held,
}

impl Pair {
    /// Two points free on their faces.
    pub fn faces(fa: FaceId, a: [f64; 2], fb: FaceId, b: [f64; 2]) -> Self {
        Self {
            fa,
            a,
            fb,
            b,
            held_a: Held::Face,
            held_b: Held::Face,
        }
    }

    /// A's point (`on_a`) or B's: face, (u, v), feature.
    pub fn side(&self, on_a: bool) -> (FaceId, [f64; 2], Held) {
        if on_a {
            (self.fa, self.a, self.held_a)
        } else {
            (self.fb, self.b, self.held_b)
        }
    }

    /// Replaces A's point (`on_a`) or B's.
    pub fn set_side(&mut self, on_a: bool, face: FaceId, uv: [f64; 2], held: Held) {
        if on_a {
            (self.fa, self.a, self.held_a) = (face, uv, held);
        } else {
            (self.fb, self.b, self.held_b) = (face, uv, held);
        }
    }

    /// The parameters that exist (see [`Held::dims`]): A's two, then B's two.
    pub fn dims(&self) -> [bool; N] {
        let (a, b) = (self.held_a.dims(), self.held_b.dims());
        [a[0], a[1], b[0], b[1]]
    }

    /// Both points free on their faces.
    pub fn on_faces(&self) -> bool {
        self.held_a == Held::Face && self.held_b == Held::Face
    }

    /// B's point first.
    pub fn swapped(&self) -> Self {
        Self {
            fa: self.fb,
            a: self.b,
            fb: self.fa,
            b: self.a,
            held_a: self.held_b,
            held_b: self.held_a,
        }
    }
}
