//! Query options: the margin, the contact band and the mesh tolerance.

/// What a query computes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum QueryDepth {
    /// Every contact with its exact points (all three stages where needed).
    #[default]
    Contacts,
    /// Only the state (separated, contact or penetration): stops before Stage 3 whenever the
    /// mesh phase already decides it (separated or penetrating meshes), and refines only as far
    /// as needed to tell contact from separation otherwise.
    StateOnly,
}

/// Options of a contact query. All lengths in millimetres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactOptions {
    /// Inflation of the bounding volumes and offset of proxy meshes (mm). Must exceed the motion
    /// of one time step and be at least `delta2`. Default 1.0.
    pub margin: f64,
    /// Lower end of the contact band (mm): below it the pair penetrates. Default -0.001.
    pub delta1: f64,
    /// Upper end of the contact band (mm): above it the pair is separated. Default 0.1.
    pub delta2: f64,
    /// Largest distance between the component meshes and the exact surfaces (mm), used when
    /// objects are prepared. Default 0.05.
    pub chordal_tolerance: f64,
    /// How far to go.
    pub depth: QueryDepth,
}

impl Default for ContactOptions {
    fn default() -> Self {
        Self {
            margin: 1.0,
            delta1: -0.001,
            delta2: 0.1,
            chordal_tolerance: 0.05,
            depth: QueryDepth::Contacts,
        }
    }
}

/// Options that cannot work together.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum OptionsError {
    /// A length is NaN or infinite.
    #[error("option `{name}` = {value} is not a finite number")]
    NotFinite {
        /// Which option.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// `margin` or `chordal_tolerance` is not positive.
    #[error("option `{name}` = {value} must be > 0")]
    NotPositive {
        /// Which option.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The band is empty or not covered by the margin: need delta1 <= delta2 <= margin.
    #[error(
        "need delta1 <= delta2 <= margin, got delta1 = {delta1}, delta2 = {delta2}, margin = {margin}"
    )]
    BadBand {
        /// delta1 (mm).
        delta1: f64,
        /// delta2 (mm).
        delta2: f64,
        /// margin (mm).
        margin: f64,
    },
}

impl ContactOptions {
    /// Checks that the options can be used.
    ///
    /// # Errors
    /// An [`OptionsError`] naming the offending option.
    pub fn validate(&self) -> Result<(), OptionsError> {
        for (name, value) in [
            ("margin", self.margin),
            ("delta1", self.delta1),
            ("delta2", self.delta2),
            ("chordal_tolerance", self.chordal_tolerance),
        ] {
            if !value.is_finite() {
                return Err(OptionsError::NotFinite { name, value });
            }
        }
        for (name, value) in [
            ("margin", self.margin),
            ("chordal_tolerance", self.chordal_tolerance),
        ] {
            if value <= 0.0 {
                return Err(OptionsError::NotPositive { name, value });
            }
        }
        if !(self.delta1 <= self.delta2 && self.delta2 <= self.margin) {
            return Err(OptionsError::BadBand {
                delta1: self.delta1,
                delta2: self.delta2,
                margin: self.margin,
            });
        }
        Ok(())
    }
}
