//! Units and uncertainty of a solid: the length unit of its representation context converted
//! to millimetres (SI_UNIT with a prefix, CONVERSION_BASED_UNIT such as INCH), the plane angle
//! unit to radians, and the GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT's length uncertainty.

use crate::io::step::error::StepError;
use crate::io::step::graph::{Entity, Graph, real_of};
use crate::io::step::part21::Param;

/// Depth of CONVERSION_BASED_UNIT chains followed (each one refers to another unit).
const MAX_UNIT_CHAIN: usize = 8;

/// The units a solid's numbers are in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Units {
    /// Millimetres per length unit of the file.
    pub length_mm: f64,
    /// Radians per plane angle unit of the file.
    pub angle_rad: f64,
    /// The length uncertainty (mm), when the context gives one.
    pub uncertainty_mm: Option<f64>,
}

/// Representation types whose items can hold a solid, with the index of their context.
const REPRESENTATIONS: [&str; 4] = [
    "ADVANCED_BREP_SHAPE_REPRESENTATION",
    "SHAPE_REPRESENTATION",
    "MANIFOLD_SURFACE_SHAPE_REPRESENTATION",
    "FACETED_BREP_SHAPE_REPRESENTATION",
];

/// The context of the representation whose items hold `solid`, or else of the first
/// representation context with a unit, in id order.
pub(crate) fn context_of(graph: &Graph<'_>, solid: u64) -> Option<u64> {
    let mut ids: Vec<&u64> = graph.file.records.keys().collect();
    ids.sort_unstable();
    let mut fallback = None;
    for &id in ids {
        let record = &graph.file.records[&id];
        for name in REPRESENTATIONS {
            if let Some(params) = record.part(name) {
                let context = match params.get(2) {
                    Some(Param::Ref(c)) => *c,
                    _ => continue,
                };
                if let Some(Param::List(items)) = params.get(1) {
                    if items.contains(&Param::Ref(solid)) {
                        return Some(context);
                    }
                }
            }
        }
        if fallback.is_none() && record.has("GLOBAL_UNIT_ASSIGNED_CONTEXT") {
            fallback = Some(id);
        }
    }
    fallback
}

/// The units of context `context`.
///
/// # Errors
/// [`StepError::Units`] for a context without a length unit or with a unit it cannot read;
/// [`StepError::MissingReference`].
pub(crate) fn units_of(graph: &Graph<'_>, context: u64) -> Result<Units, StepError> {
    let ctx = graph.root(context).ok_or(StepError::Units {
        id: context,
        reason: "the context does not exist".into(),
    })?;
    let units = ctx
        .record
        .part("GLOBAL_UNIT_ASSIGNED_CONTEXT")
        .ok_or_else(|| StepError::Units {
            id: context,
            reason: "the representation context has no GLOBAL_UNIT_ASSIGNED_CONTEXT".into(),
        })?;
    let units_entity = Entity {
        params: units,
        ..ctx
    };
    let mut length = None;
    let mut angle = 1.0;
    for unit in units_entity.ref_list(0)? {
        let u = graph.get(&units_entity, unit)?;
        if u.record.has("LENGTH_UNIT") {
            length = Some(unit_factor(graph, &u, 0)? * 1000.0);
        } else if u.record.has("PLANE_ANGLE_UNIT") {
            angle = unit_factor(graph, &u, 0)?;
        }
    }
    let length_mm = length.ok_or_else(|| StepError::Units {
        id: context,
        reason: "the context has no LENGTH_UNIT".into(),
    })?;
    let mut uncertainty_mm = None;
    if let Some(params) = ctx.record.part("GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT") {
        let e = Entity { params, ..ctx };
        for id in e.ref_list(0)? {
            let m = graph.get(&e, id)?;
            if !m.record.has("UNCERTAINTY_MEASURE_WITH_UNIT") {
                continue;
            }
            // The simple form holds (value, unit, name, description); the complex one
            // (LENGTH_MEASURE_WITH_UNIT() MEASURE_WITH_UNIT(value, unit)
            // UNCERTAINTY_MEASURE_WITH_UNIT(name, description)), as CATIA, Pro/E and
            // other exporters write it, holds the value and unit in MEASURE_WITH_UNIT.
            let params = m
                .record
                .part("MEASURE_WITH_UNIT")
                .or_else(|| m.record.part("UNCERTAINTY_MEASURE_WITH_UNIT"))
                .unwrap_or(m.params);
            let m = Entity { params, ..m };
            let value = m.real(0)?;
            let unit = graph.get(&m, m.reference(1)?)?;
            if !unit.record.has("LENGTH_UNIT") {
                continue;
            }
            let mm = value * unit_factor(graph, &unit, 0)? * 1000.0;
            if !(mm.is_finite() && mm > 0.0) {
                return Err(StepError::Units {
                    id: m.id,
                    reason: format!("the uncertainty {mm} mm is not a positive number"),
                });
            }
            uncertainty_mm = Some(uncertainty_mm.map_or(mm, |u: f64| u.min(mm)));
        }
    }
    if !(length_mm.is_finite() && length_mm > 0.0 && angle.is_finite() && angle > 0.0) {
        return Err(StepError::Units {
            id: context,
            reason: format!("unit factors {length_mm} mm, {angle} rad are not positive numbers"),
        });
    }
    Ok(Units {
        length_mm,
        angle_rad: angle,
        uncertainty_mm,
    })
}

/// The size of `unit` in SI units (metres or radians).
fn unit_factor(graph: &Graph<'_>, unit: &Entity<'_>, depth: usize) -> Result<f64, StepError> {
    if depth > MAX_UNIT_CHAIN {
        return Err(StepError::Units {
            id: unit.id,
            reason: "conversion-based units nest too deeply".into(),
        });
    }
    if let Some(params) = unit.record.part("SI_UNIT") {
        let prefix = match params.first() {
            Some(Param::Enum(p)) => prefix_factor(p).ok_or_else(|| StepError::Units {
                id: unit.id,
                reason: format!("unknown SI prefix .{p}."),
            })?,
            _ => 1.0,
        };
        return Ok(prefix);
    }
    if let Some(params) = unit.record.part("CONVERSION_BASED_UNIT") {
        let e = Entity { params, ..*unit };
        let measure = graph.get(&e, e.reference(1)?)?;
        let value = measure
            .params
            .first()
            .and_then(real_of)
            .ok_or_else(|| measure.malformed("the measure's value is not a number"))?;
        let base = graph.get(&measure, measure.reference(1)?)?;
        return Ok(value * unit_factor(graph, &base, depth + 1)?);
    }
    Err(StepError::Units {
        id: unit.id,
        reason: format!(
            "{} is neither an SI_UNIT nor a CONVERSION_BASED_UNIT",
            unit.type_name()
        ),
    })
}

fn prefix_factor(prefix: &str) -> Option<f64> {
    Some(match prefix {
        "EXA" => 1e18,
        "PETA" => 1e15,
        "TERA" => 1e12,
        "GIGA" => 1e9,
        "MEGA" => 1e6,
        "KILO" => 1e3,
        "HECTO" => 1e2,
        "DECA" => 1e1,
        "DECI" => 1e-1,
        "CENTI" => 1e-2,
        "MILLI" => 1e-3,
        "MICRO" => 1e-6,
        "NANO" => 1e-9,
        "PICO" => 1e-12,
        "FEMTO" => 1e-15,
        "ATTO" => 1e-18,
        _ => return None,
    })
}
