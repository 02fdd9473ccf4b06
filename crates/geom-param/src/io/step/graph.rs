//! The entity graph of a parsed file: typed access to an instance's parameters with errors
//! that name the instance, reference resolution, and the cycle check below the solids.

use crate::io::step::error::StepError;
use crate::io::step::part21::{Param, Part21, Record};
use std::collections::HashMap;

/// One instance seen as a given type: its id, record and the parameters of that type's part.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Entity<'a> {
    /// The `#id`.
    pub id: u64,
    /// The whole instance.
    pub record: &'a Record,
    /// The parameters of the part being read.
    pub params: &'a [Param],
}

impl<'a> Entity<'a> {
    /// The instance's type name.
    pub(crate) fn type_name(&self) -> String {
        self.record.type_name()
    }

    /// A [`StepError::Malformed`] about this instance.
    pub(crate) fn malformed(&self, reason: impl Into<String>) -> StepError {
        StepError::Malformed {
            id: self.id,
            entity: self.type_name(),
            reason: reason.into(),
        }
    }

    /// A [`StepError::Unsupported`] about this instance.
    pub(crate) fn unsupported(&self, role: &'static str) -> StepError {
        StepError::Unsupported {
            id: self.id,
            entity: self.type_name(),
            role,
        }
    }

    /// A [`StepError::Geometry`] about this instance.
    pub(crate) fn geometry(&self, source: crate::GeometryError) -> StepError {
        StepError::Geometry {
            id: self.id,
            entity: self.type_name(),
            source,
        }
    }

    /// Parameter `i`.
    pub(crate) fn param(&self, i: usize) -> Result<&'a Param, StepError> {
        self.params.get(i).ok_or_else(|| {
            self.malformed(format!(
                "it has {} parameters, needs at least {}",
                self.params.len(),
                i + 1
            ))
        })
    }

    /// Parameter `i` as a real (an integer is accepted).
    pub(crate) fn real(&self, i: usize) -> Result<f64, StepError> {
        real_of(self.param(i)?)
            .ok_or_else(|| self.malformed(format!("parameter {} is not a number", i + 1)))
    }

    /// Parameter `i` as an integer.
    pub(crate) fn int(&self, i: usize) -> Result<i64, StepError> {
        match self.param(i)? {
            Param::Int(v) => Ok(*v),
            _ => Err(self.malformed(format!("parameter {} is not an integer", i + 1))),
        }
    }

    /// Parameter `i` as a reference.
    pub(crate) fn reference(&self, i: usize) -> Result<u64, StepError> {
        match self.param(i)? {
            Param::Ref(id) => Ok(*id),
            _ => Err(self.malformed(format!("parameter {} is not a reference", i + 1))),
        }
    }

    /// Parameter `i` as a reference, or `None` for `$`.
    pub(crate) fn optional_reference(&self, i: usize) -> Result<Option<u64>, StepError> {
        match self.params.get(i) {
            None | Some(Param::Null) => Ok(None),
            Some(Param::Ref(id)) => Ok(Some(*id)),
            Some(_) => Err(self.malformed(format!("parameter {} is not a reference", i + 1))),
        }
    }

    /// Parameter `i` as a list.
    pub(crate) fn list(&self, i: usize) -> Result<&'a [Param], StepError> {
        match self.param(i)? {
            Param::List(items) => Ok(items),
            _ => Err(self.malformed(format!("parameter {} is not a list", i + 1))),
        }
    }

    /// Parameter `i` as a list of references.
    pub(crate) fn ref_list(&self, i: usize) -> Result<Vec<u64>, StepError> {
        self.list(i)?
            .iter()
            .map(|p| match p {
                Param::Ref(id) => Ok(*id),
                _ => Err(self.malformed(format!("parameter {} holds a non-reference", i + 1))),
            })
            .collect()
    }

    /// Parameter `i` as a list of reals.
    pub(crate) fn real_list(&self, i: usize) -> Result<Vec<f64>, StepError> {
        self.list(i)?
            .iter()
            .map(|p| {
                real_of(p).ok_or_else(|| {
                    self.malformed(format!("parameter {} holds a non-number", i + 1))
                })
            })
            .collect()
    }

    /// Parameter `i` as a boolean `.T.` / `.F.`.
    pub(crate) fn boolean(&self, i: usize) -> Result<bool, StepError> {
        match self.param(i)? {
            Param::Enum(e) if e == "T" => Ok(true),
            Param::Enum(e) if e == "F" => Ok(false),
            _ => Err(self.malformed(format!("parameter {} is not .T. or .F.", i + 1))),
        }
    }

    /// Parameter `i` as a string, or "" for `$`.
    pub(crate) fn string(&self, i: usize) -> String {
        match self.params.get(i) {
            Some(Param::Str(s)) => s.clone(),
            _ => String::new(),
        }
    }
}

/// A number: a real, an integer, or a typed measure such as `LENGTH_MEASURE(1.0)`.
pub(crate) fn real_of(p: &Param) -> Option<f64> {
    match p {
        Param::Real(v) => Some(*v),
        #[allow(clippy::cast_precision_loss)]
        Param::Int(v) => Some(*v as f64),
        Param::Typed(_, inner) if inner.len() == 1 => real_of(&inner[0]),
        _ => None,
    }
}

/// The parsed file as a graph of instances.
#[derive(Debug)]
pub(crate) struct Graph<'a> {
    /// The parsed exchange structure.
    pub file: &'a Part21,
}

impl<'a> Graph<'a> {
    /// Instance `target` referenced from `from`, as type `name` (a simple instance of that
    /// type, or a complex one with that part).
    ///
    /// # Errors
    /// [`StepError::MissingReference`]; [`StepError::Unsupported`] with `role` when the
    /// instance has no part `name`.
    pub(crate) fn get_as(
        &self,
        from: &Entity<'_>,
        target: u64,
        name: &str,
        role: &'static str,
    ) -> Result<Entity<'a>, StepError> {
        let e = self.get(from, target)?;
        e.record
            .part(name)
            .map(|params| Entity { params, ..e })
            .ok_or_else(|| e.unsupported(role))
    }

    /// Instance `target` referenced from `from`, seen as its first part.
    ///
    /// # Errors
    /// [`StepError::MissingReference`].
    pub(crate) fn get(&self, from: &Entity<'_>, target: u64) -> Result<Entity<'a>, StepError> {
        let record = self
            .file
            .records
            .get(&target)
            .ok_or_else(|| StepError::MissingReference {
                id: from.id,
                entity: from.type_name(),
                target,
            })?;
        Ok(Entity {
            id: target,
            record,
            params: record.parts.first().map_or(&[], |(_, p)| p.as_slice()),
        })
    }

    /// Instance `id` as its first part, if it exists.
    pub(crate) fn root(&self, id: u64) -> Option<Entity<'a>> {
        self.file.records.get(&id).map(|record| Entity {
            id,
            record,
            params: record.parts.first().map_or(&[], |(_, p)| p.as_slice()),
        })
    }

    /// Checks that no instance reachable from `roots` references a missing id or lies on a
    /// reference cycle (iterative depth-first search, linear in the reachable instances).
    ///
    /// # Errors
    /// [`StepError::MissingReference`], [`StepError::ReferenceCycle`].
    pub(crate) fn check_acyclic(&self, roots: &[u64]) -> Result<(), StepError> {
        // 1 = on the stack, 2 = done.
        let mut state: HashMap<u64, u8> = HashMap::new();
        let mut refs = Vec::new();
        for &root in roots {
            if state.contains_key(&root) {
                continue;
            }
            // (id, its references, next index)
            let mut stack: Vec<(u64, Vec<u64>, usize)> = Vec::new();
            let children = |id: u64, refs: &mut Vec<u64>| -> Vec<u64> {
                refs.clear();
                if let Some(r) = self.file.records.get(&id) {
                    for (_, params) in &r.parts {
                        for p in params {
                            p.refs(refs);
                        }
                    }
                }
                refs.clone()
            };
            state.insert(root, 1);
            stack.push((root, children(root, &mut refs), 0));
            while let Some((id, kids, next)) = stack.last_mut() {
                let Some(&kid) = kids.get(*next) else {
                    state.insert(*id, 2);
                    stack.pop();
                    continue;
                };
                *next += 1;
                let parent = *id;
                match state.get(&kid) {
                    Some(2) => {}
                    Some(_) => {
                        let record = &self.file.records[&kid];
                        return Err(StepError::ReferenceCycle {
                            id: kid,
                            entity: record.type_name(),
                        });
                    }
                    None => {
                        if !self.file.records.contains_key(&kid) {
                            let record = &self.file.records[&parent];
                            return Err(StepError::MissingReference {
                                id: parent,
                                entity: record.type_name(),
                                target: kid,
                            });
                        }
                        state.insert(kid, 1);
                        let grand = children(kid, &mut refs);
                        stack.push((kid, grand, 0));
                    }
                }
            }
        }
        Ok(())
    }
}
