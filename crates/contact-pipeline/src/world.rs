//! Many objects at once: a [`World`] of posed instances of shared prepared objects, a broad
//! phase across objects (parry's [`Bvh`] over world-frame boxes inflated by the margin), pair
//! filtering, and one call ([`World::step`]) that answers every pair in range with the
//! coherent query ([`crate::coherence`]), each pair keeping its own cache and scratch. With the
//! `parallel` feature, [`World::step_parallel`] spreads the pairs over rayon's threads; the
//! answers and their order are the same for any number of threads.
//!
//! # Broad phase
//! Each object's box is its meshes' vertex box in its own frame grown by its largest chordal
//! error (so it holds the exact surface), carried to the world frame (the box of its 8 moved
//! corners) and grown by margin/2 on every side. Two objects whose exact surfaces come within
//! the margin have overlapping boxes, so every pair Stage 1 of the pipeline could report is
//! visited. Boxes are updated in place when an object moves (parry's [`Bvh::insert`] widens
//! the ancestors as needed) and the tree is refitted before the next step's traversal.

use crate::coherence::{CoherenceOptions, ContactId, FrameKind, PairCache};
use crate::pipeline::{ContactPipeline, PreparedObject, QueryError, QueryScratch};
use crate::report::{PairReport, PairState};
use bvh_hybrid::BroadPhase;
use exact_refine::Refiner;
use geom_param::DPose3;
use glam::DVec3;
use mesh_narrowphase::MeshPhase;
use parry3d_f64::bounding_volume::Aabb;
use parry3d_f64::partitioning::{Bvh, BvhWorkspace};
use std::collections::BTreeMap;
use std::sync::Arc;

/// An object's handle in its [`World`]: a slot index and the slot's generation, so that a key
/// of a removed object never names a later one. Keys order by slot index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ObjectKey {
    /// Slot index.
    pub index: u32,
    /// Generation of the slot when the object was inserted.
    pub generation: u32,
}

/// Collision groups (as parry's interaction groups): two objects are paired when each one's
/// `memberships` meets the other's `filter` (bitwise AND non-zero). Default: all bits, so every
/// pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Groups {
    /// The groups the object belongs to.
    pub memberships: u32,
    /// The groups it may touch.
    pub filter: u32,
}

impl Default for Groups {
    fn default() -> Self {
        Self {
            memberships: u32::MAX,
            filter: u32::MAX,
        }
    }
}

impl Groups {
    /// Whether objects in `self` and `other` are paired.
    #[must_use]
    pub fn interact(&self, other: &Self) -> bool {
        self.memberships & other.filter != 0 && other.memberships & self.filter != 0
    }
}

/// Why a world operation failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum WorldError {
    /// The key names no object of this world (removed, or never inserted).
    #[error("no object {0:?} in the world")]
    UnknownObject(ObjectKey),
    /// A pose that is not a rigid motion (see [`QueryError::BadPose`]).
    #[error("object {key:?}: {source}")]
    BadPose {
        /// The object.
        key: ObjectKey,
        /// What is wrong.
        source: QueryError,
    },
    /// A pair's query failed; the first such pair in key order.
    #[error("pair {a:?}-{b:?}: {source}")]
    Query {
        /// First object of the pair.
        a: ObjectKey,
        /// Second object.
        b: ObjectKey,
        /// Why.
        source: QueryError,
    },
    /// More than `u32::MAX` objects.
    #[error("the world is full")]
    Full,
}

/// What one step did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WorldStats {
    /// Objects in the world.
    pub objects: usize,
    /// Pairs whose inflated boxes overlap (before filtering).
    pub pairs_in_range: usize,
    /// Pairs queried (in range and passing the filters).
    pub pairs_queried: usize,
    /// Of those, answered by a warm frame.
    pub warm: usize,
    /// Pairs in contact or penetrating.
    pub pairs_touching: usize,
    /// Contacts over all pairs.
    pub contacts: usize,
    /// Wall time of the broad phase across objects (µs).
    pub broad_us: f64,
    /// Wall time of the pair queries (µs).
    pub pairs_us: f64,
}

/// One queried pair's answer, as [`World::pairs`] lists it.
#[derive(Clone, Copy, Debug)]
pub struct WorldPair<'w> {
    /// The object with the smaller slot index (object A of the query).
    pub a: ObjectKey,
    /// The other (object B).
    pub b: ObjectKey,
    /// The pair's report (world frame).
    pub report: &'w PairReport,
    /// The contacts' ids, in the report's order.
    pub ids: &'w [ContactId],
    /// How the query was answered.
    pub frame: FrameKind,
}

/// A caller's pair predicate: `true` keeps the pair (called with the smaller key first).
pub type PairFilter = dyn Fn(ObjectKey, ObjectKey) -> bool + Send + Sync;

struct Slot<B: BroadPhase, M: MeshPhase> {
    object: Option<Arc<PreparedObject<B, M>>>,
    pose: DPose3,
    groups: Groups,
    generation: u32,
    /// Box of the exact surface in the object's frame.
    local_box: (DVec3, DVec3),
}

struct PairEntry<B: BroadPhase, M: MeshPhase, R: Refiner> {
    generations: (u32, u32),
    cache: PairCache,
    scratch: QueryScratch<B, M, R>,
    report: PairReport,
    frame: FrameKind,
    error: Option<QueryError>,
}

/// Posed instances of prepared objects, and every pair's contacts (see the module
/// documentation). Instances of one model share its preparation through an [`Arc`].
pub struct World<
    B: BroadPhase = bvh_hybrid::HybridBvh,
    M: MeshPhase = mesh_narrowphase::MeshNarrowphase,
    R: Refiner = exact_refine::NewtonRefiner,
> {
    pipeline: ContactPipeline<B, M, R>,
    coherence: Option<CoherenceOptions>,
    slots: Vec<Slot<B, M>>,
    free: Vec<u32>,
    bvh: Bvh,
    workspace: BvhWorkspace,
    moved: bool,
    filter: Option<Box<PairFilter>>,
    pairs: BTreeMap<(u32, u32), PairEntry<B, M, R>>,
    candidates: Vec<(u32, u32)>,
    stats: WorldStats,
}

impl<B: BroadPhase, M: MeshPhase, R: Refiner> World<B, M, R> {
    /// An empty world answering with `pipeline`; with `coherence`, each pair by
    /// [`ContactPipeline::query_coherent`] (warm frames, contact ids), without (`None`, for
    /// one-off queries: the coherent full query widens the band) by
    /// [`ContactPipeline::query_into`], and [`WorldPair::ids`] is empty.
    #[must_use]
    pub fn new(pipeline: ContactPipeline<B, M, R>, coherence: Option<CoherenceOptions>) -> Self {
        Self {
            pipeline,
            coherence,
            slots: Vec::new(),
            free: Vec::new(),
            bvh: Bvh::new(),
            workspace: BvhWorkspace::default(),
            moved: false,
            filter: None,
            pairs: BTreeMap::new(),
            candidates: Vec::new(),
            stats: WorldStats::default(),
        }
    }

    /// The pipeline (to prepare objects for [`Self::insert`]).
    #[must_use]
    pub fn pipeline(&self) -> &ContactPipeline<B, M, R> {
        &self.pipeline
    }

    /// Sets the caller's pair predicate (`None`: every pair the groups allow).
    pub fn set_filter(&mut self, filter: Option<Box<PairFilter>>) {
        self.filter = filter;
    }

    /// Adds an instance of `object` at `pose` (world frame) in `groups`.
    ///
    /// # Errors
    /// [`WorldError::BadPose`] for a pose that is not a rigid motion; [`WorldError::Full`].
    pub fn insert(
        &mut self,
        object: Arc<PreparedObject<B, M>>,
        pose: DPose3,
        groups: Groups,
    ) -> Result<ObjectKey, WorldError> {
        let local_box = local_box(&object);
        let index = match self.free.pop() {
            Some(i) => i,
            None => {
                let i = u32::try_from(self.slots.len()).map_err(|_| WorldError::Full)?;
                self.slots.push(Slot {
                    object: None,
                    pose: DPose3::IDENTITY,
                    groups,
                    generation: 0,
                    local_box,
                });
                i
            }
        };
        let slot = &mut self.slots[index as usize];
        slot.generation = slot.generation.wrapping_add(1);
        let key = ObjectKey {
            index,
            generation: slot.generation,
        };
        let pose = crate::pipeline::check_pose(&pose, "a")
            .map_err(|source| WorldError::BadPose { key, source });
        let pose = match pose {
            Ok(p) => p,
            Err(e) => {
                self.free.push(index);
                return Err(e);
            }
        };
        slot.object = Some(object);
        slot.pose = pose;
        slot.groups = groups;
        slot.local_box = local_box;
        let aabb = world_box(slot, self.pipeline.options().margin);
        self.bvh.insert(aabb, index);
        self.moved = true;
        Ok(key)
    }

    /// Removes an object (its pairs' caches go at the next step).
    ///
    /// # Errors
    /// [`WorldError::UnknownObject`].
    pub fn remove(&mut self, key: ObjectKey) -> Result<Arc<PreparedObject<B, M>>, WorldError> {
        let slot = self.slot_mut(key)?;
        let object = slot.object.take().ok_or(WorldError::UnknownObject(key))?;
        self.bvh.remove(key.index);
        self.free.push(key.index);
        self.moved = true;
        Ok(object)
    }

    /// Moves an object to `pose` (world frame).
    ///
    /// # Errors
    /// [`WorldError::UnknownObject`]; [`WorldError::BadPose`].
    pub fn set_pose(&mut self, key: ObjectKey, pose: DPose3) -> Result<(), WorldError> {
        let margin = self.pipeline.options().margin;
        let pose = crate::pipeline::check_pose(&pose, "a")
            .map_err(|source| WorldError::BadPose { key, source })?;
        let slot = self.slot_mut(key)?;
        slot.pose = pose;
        let aabb = world_box(slot, margin);
        self.bvh.insert(aabb, key.index);
        self.moved = true;
        Ok(())
    }

    /// An object's prepared data (shared with its other instances).
    ///
    /// # Errors
    /// [`WorldError::UnknownObject`].
    pub fn object(&self, key: ObjectKey) -> Result<Arc<PreparedObject<B, M>>, WorldError> {
        self.slot(key)
            .and_then(|s| s.object.clone().ok_or(WorldError::UnknownObject(key)))
    }

    /// An object's pose.
    ///
    /// # Errors
    /// [`WorldError::UnknownObject`].
    pub fn pose(&self, key: ObjectKey) -> Result<DPose3, WorldError> {
        self.slot(key).map(|s| s.pose)
    }

    /// Number of objects.
    #[must_use]
    pub fn len(&self) -> usize {
        self.slots.len() - self.free.len()
    }

    /// Whether the world holds no object.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The last step's statistics.
    #[must_use]
    pub fn stats(&self) -> WorldStats {
        self.stats
    }

    fn slot(&self, key: ObjectKey) -> Result<&Slot<B, M>, WorldError> {
        self.slots
            .get(key.index as usize)
            .filter(|s| s.generation == key.generation && s.object.is_some())
            .ok_or(WorldError::UnknownObject(key))
    }

    fn slot_mut(&mut self, key: ObjectKey) -> Result<&mut Slot<B, M>, WorldError> {
        self.slots
            .get_mut(key.index as usize)
            .filter(|s| s.generation == key.generation && s.object.is_some())
            .ok_or(WorldError::UnknownObject(key))
    }

    fn key(&self, index: u32) -> ObjectKey {
        ObjectKey {
            index,
            generation: self.slots[index as usize].generation,
        }
    }

    /// The broad phase: fills `self.candidates` (sorted, filtered) and the pair entries (new
    /// pairs get fresh caches, pairs out of range lose theirs).
    fn broad_phase(&mut self) {
        let start = std::time::Instant::now();
        if self.moved {
            self.bvh.refit(&mut self.workspace);
            self.moved = false;
        }
        self.candidates.clear();
        let candidates = &mut self.candidates;
        self.bvh
            .traverse_bvtt_single_tree::<false>(&mut self.workspace, &mut |i, j| {
                if i != j {
                    candidates.push((i.min(j), i.max(j)));
                }
            });
        self.candidates.sort_unstable();
        self.candidates.dedup();
        let in_range = self.candidates.len();
        let slots = &self.slots;
        let filter = self.filter.as_deref();
        let keys = |i: u32| ObjectKey {
            index: i,
            generation: slots[i as usize].generation,
        };
        self.candidates.retain(|&(i, j)| {
            let (a, b) = (&slots[i as usize], &slots[j as usize]);
            a.object.is_some()
                && b.object.is_some()
                && a.groups.interact(&b.groups)
                && filter.is_none_or(|f| f(keys(i), keys(j)))
        });
        // Keep the caches of pairs still in range with the same objects.
        let generations =
            |(i, j): (u32, u32)| (slots[i as usize].generation, slots[j as usize].generation);
        let candidates = &self.candidates;
        self.pairs.retain(|&k, entry| {
            candidates.binary_search(&k).is_ok() && entry.generations == generations(k)
        });
        for &k in &self.candidates {
            self.pairs.entry(k).or_insert_with(|| PairEntry {
                generations: generations(k),
                cache: PairCache::new(),
                scratch: QueryScratch::default(),
                report: PairReport::default(),
                frame: FrameKind::Full,
                error: None,
            });
        }
        self.stats = WorldStats {
            objects: self.len(),
            pairs_in_range: in_range,
            pairs_queried: self.candidates.len(),
            broad_us: start.elapsed().as_secs_f64() * 1e6,
            ..WorldStats::default()
        };
    }

    /// Answers every pair in range on this thread (see the module documentation).
    ///
    /// # Errors
    /// [`WorldError::Query`] for the first pair (in key order) whose query failed; the other
    /// pairs are answered.
    pub fn step(&mut self) -> Result<WorldStats, WorldError> {
        self.broad_phase();
        let start = std::time::Instant::now();
        let (pipeline, coherence, slots) = (&self.pipeline, self.coherence.as_ref(), &self.slots);
        for (&k, entry) in &mut self.pairs {
            answer(pipeline, coherence, slots, k, entry);
        }
        self.finish(start)
    }

    /// Totals the step's statistics and returns the first error.
    fn finish(&mut self, start: std::time::Instant) -> Result<WorldStats, WorldError> {
        self.stats.pairs_us = start.elapsed().as_secs_f64() * 1e6;
        let mut first_error = None;
        for (&(i, j), entry) in &self.pairs {
            if let Some(e) = &entry.error {
                first_error.get_or_insert_with(|| WorldError::Query {
                    a: self.key(i),
                    b: self.key(j),
                    source: e.clone(),
                });
            }
            if entry.frame == FrameKind::Warm {
                self.stats.warm += 1;
            }
            if entry.report.state != PairState::Separated {
                self.stats.pairs_touching += 1;
            }
            self.stats.contacts += entry.report.contacts.len();
        }
        first_error.map_or(Ok(self.stats), Err)
    }

    /// The last step's answers for the pairs that touch (contact or penetration), in key order
    /// (by the pairs' slot indices).
    pub fn pairs(&self) -> impl Iterator<Item = WorldPair<'_>> + '_ {
        self.all_pairs()
            .filter(|p| p.report.state != PairState::Separated)
    }

    /// The last step's answers for every queried pair, separated ones included, in key order.
    pub fn all_pairs(&self) -> impl Iterator<Item = WorldPair<'_>> + '_ {
        self.pairs.iter().map(|(&(i, j), e)| WorldPair {
            a: ObjectKey {
                index: i,
                generation: e.generations.0,
            },
            b: ObjectKey {
                index: j,
                generation: e.generations.1,
            },
            report: &e.report,
            ids: if self.coherence.is_some() {
                e.cache.contact_ids()
            } else {
                &[]
            },
            frame: e.frame,
        })
    }
}

#[cfg(feature = "parallel")]
impl<B, M, R> World<B, M, R>
where
    B: BroadPhase + Sync,
    M: MeshPhase + Sync,
    R: Refiner + Sync,
    B::Scratch: Send,
    M::Scratch: Send,
    R::Scratch: Send,
{
    /// As [`Self::step`], with the pairs spread over the current rayon thread pool. Every
    /// pair keeps its own cache and scratch, so the answers, and their order, do not depend
    /// on the number of threads.
    ///
    /// # Errors
    /// As [`Self::step`].
    pub fn step_parallel(&mut self) -> Result<WorldStats, WorldError> {
        use rayon::prelude::*;
        self.broad_phase();
        let start = std::time::Instant::now();
        let (pipeline, coherence, slots) = (&self.pipeline, self.coherence.as_ref(), &self.slots);
        let mut entries: Vec<_> = self.pairs.iter_mut().map(|(&k, e)| (k, e)).collect();
        entries
            .par_iter_mut()
            .with_min_len(4)
            .for_each(|(k, entry)| answer(pipeline, coherence, slots, *k, entry));
        self.finish(start)
    }
}

/// Queries one pair into its entry.
fn answer<B: BroadPhase, M: MeshPhase, R: Refiner>(
    pipeline: &ContactPipeline<B, M, R>,
    coherence: Option<&CoherenceOptions>,
    slots: &[Slot<B, M>],
    (i, j): (u32, u32),
    entry: &mut PairEntry<B, M, R>,
) {
    let (sa, sb) = (&slots[i as usize], &slots[j as usize]);
    let (Some(a), Some(b)) = (&sa.object, &sb.object) else {
        return;
    };
    let result = match coherence {
        Some(coherence) => pipeline.query_coherent(
            a,
            &sa.pose,
            b,
            &sb.pose,
            coherence,
            &mut entry.cache,
            &mut entry.scratch,
            &mut entry.report,
        ),
        None => pipeline
            .query_into(
                a,
                &sa.pose,
                b,
                &sb.pose,
                &mut entry.scratch,
                &mut entry.report,
            )
            .map(|()| FrameKind::Full),
    };
    match result {
        Ok(frame) => {
            entry.frame = frame;
            entry.error = None;
        }
        Err(e) => {
            entry.report.clear();
            entry.frame = FrameKind::Full;
            entry.error = Some(e);
        }
    }
}

/// The box of `object`'s exact surface in its own frame: its meshes' vertices' box grown by
/// the largest chordal error.
fn local_box<B: BroadPhase, M: MeshPhase>(object: &PreparedObject<B, M>) -> (DVec3, DVec3) {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    let mut chordal = 0.0_f64;
    for mesh in &object.model.meshes {
        chordal = chordal.max(mesh.chordal_error);
        for p in &mesh.positions {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
    }
    if lo.x > hi.x {
        // No mesh: an empty box at the origin.
        return (DVec3::ZERO, DVec3::ZERO);
    }
    (lo - DVec3::splat(chordal), hi + DVec3::splat(chordal))
}

/// The world box of a slot's object (the 8 corners of its local box moved), grown by
/// `margin / 2` on every side.
fn world_box<B: BroadPhase, M: MeshPhase>(slot: &Slot<B, M>, margin: f64) -> Aabb {
    let (lo, hi) = slot.local_box;
    let (mut min, mut max) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for k in 0..8 {
        let corner = DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        );
        let p = slot.pose * corner;
        min = min.min(p);
        max = max.max(p);
    }
    let grow = DVec3::splat(0.5 * margin);
    Aabb::new(min - grow, max + grow)
}
