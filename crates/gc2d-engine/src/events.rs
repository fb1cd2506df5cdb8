//! Contact events: the begin and end of every contact episode, with the impact speeds at first touch and the
//! episode's largest overlap, dissipated energy and impulses (what collision statistics of a mill are made of).
//!
//! Recording is off unless an observer asks for it ([`crate::World::record_contact_events`]); then the World keeps
//! one [`Episode`] per touching pair in a sorted map and writes the step's events while it adds up the contact
//! forces, in pair order. The pair order does not depend on the thread count, and the open episodes are part of a
//! checkpoint, so the events of a run are the same for any number of threads and across a checkpoint split. A World
//! that does not record pays one branch per step.

use crate::bodies::BodyId;
use crate::interactions::MaterialId;
use gc2d_geometry::{DVec2, cross};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Whether a contact began or ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ContactEventKind {
    /// The bodies touched for the first time in this episode (the first step with an overlap).
    Begin,
    /// The bodies stopped touching (the first step without an overlap), or the pair left the broadphase.
    End,
}

/// What one contact episode has added up so far.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Episode {
    /// Time of the first touching step, s.
    pub begin_time: f64,
    /// Normal approach speed of the contact points at first touch, m/s (≥ 0 for an impact).
    pub impact_normal_speed: f64,
    /// Tangential (sliding) speed of the contact points at first touch, m/s (≥ 0).
    pub impact_tangential_speed: f64,
    /// The contact point at first touch, m (where the collision happened: a mill's sector maps).
    pub begin_point: DVec2,
    /// Largest overlap of the episode, as the pair's `overlap_fraction` (area fraction for the overlap-area law,
    /// depth over the smaller diameter for penetration laws).
    pub max_overlap: f64,
    /// Energy dissipated by damping and sliding over the episode, J.
    pub dissipated: f64,
    /// ∫ F dt of the force on body `a` over the episode, N·s.
    pub impulse_on_a: DVec2,
    /// ∫ x × F dt of the force on body `a` about the world origin, N·m·s (x the contact point); with the impulse
    /// it gives the angular impulse about any fixed point.
    pub moment_impulse_on_a: f64,
}

/// One contact event.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ContactEvent {
    /// Begin or end.
    pub kind: ContactEventKind,
    /// Time of the step, s.
    pub time: f64,
    /// The pair's first body (the lower id).
    pub a: BodyId,
    /// The pair's second body.
    pub b: BodyId,
    /// Their materials, in the same order.
    pub materials: [MaterialId; 2],
    /// The episode: at `Begin` its impact speeds (the totals are zero), at `End` everything.
    pub episode: Episode,
    /// At `End`, when one body is a wall turning about a pivot: the angular impulse the contact gave that wall about
    /// its pivot, N·m·s (the rotor's share of the episode); `None` otherwise.
    pub wall_angular_impulse: Option<f64>,
}

/// What one touching pair did in one step, for the log.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PairStep {
    /// The pair.
    pub a: BodyId,
    /// The pair's second body.
    pub b: BodyId,
    /// Their materials.
    pub materials: [MaterialId; 2],
    /// True when the bodies overlap this step.
    pub touching: bool,
    /// Force on `a`, N.
    pub force_on_a: DVec2,
    /// The contact point, m.
    pub point: DVec2,
    /// The overlap measure of the step.
    pub overlap_fraction: f64,
    /// Energy dissipated this step, J.
    pub dissipated: f64,
}

/// The open episodes and this step's events.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct ContactEventLog {
    /// One episode per touching pair, keyed by (a, b).
    open: BTreeMap<(u32, u32), Episode>,
    /// The events of the last step, in pair order.
    #[serde(skip)]
    events: Vec<ContactEvent>,
}

impl ContactEventLog {
    /// Forgets the last step's events.
    pub fn start_step(&mut self) {
        self.events.clear();
    }

    /// The events of the last step.
    pub fn events(&self) -> &[ContactEvent] {
        &self.events
    }

    /// The open episodes, keyed by pair.
    pub fn open(&self) -> impl Iterator<Item = (&(u32, u32), &Episode)> {
        self.open.iter()
    }

    /// True when the pair has an open episode.
    pub fn is_open(&self, a: BodyId, b: BodyId) -> bool {
        self.open.contains_key(&(a.0, b.0))
    }

    /// Opens an episode at `time` with the impact speeds at first touch, and writes its `Begin` event.
    pub fn begin(&mut self, step: &PairStep, time: f64, impact_normal_speed: f64, impact_tangential_speed: f64) {
        let episode = Episode {
            begin_time: time,
            impact_normal_speed,
            impact_tangential_speed,
            begin_point: step.point,
            ..Episode::default()
        };
        self.open.insert((step.a.0, step.b.0), episode);
        self.events.push(ContactEvent {
            kind: ContactEventKind::Begin,
            time,
            a: step.a,
            b: step.b,
            materials: step.materials,
            episode,
            wall_angular_impulse: None,
        });
    }

    /// Adds one step of an open episode (touching or the step it ends on) over `dt`.
    pub fn accumulate(&mut self, step: &PairStep, dt: f64) {
        if let Some(episode) = self.open.get_mut(&(step.a.0, step.b.0)) {
            episode.dissipated += step.dissipated;
            if step.touching {
                episode.max_overlap = episode.max_overlap.max(step.overlap_fraction);
                episode.impulse_on_a += step.force_on_a * dt;
                episode.moment_impulse_on_a += cross(step.point, step.force_on_a) * dt;
            }
        }
    }

    /// Closes the pair's episode, if open, at `time` and writes its `End` event. `wall_pivot` is the pivot of body
    /// `a` (`Some((true, P))`) or `b` (`Some((false, P))`) when that body is a wall turning about P.
    pub fn end(
        &mut self,
        a: BodyId,
        b: BodyId,
        materials: [MaterialId; 2],
        time: f64,
        wall_pivot: Option<(bool, DVec2)>,
    ) {
        let Some(episode) = self.open.remove(&(a.0, b.0)) else { return };
        let wall_angular_impulse = wall_pivot.map(|(wall_is_a, pivot)| {
            // About P: ∫ (x − P) × F dt = ∫ x × F dt − P × ∫ F dt, for the force on a; the wall b feels −F.
            let on_a = episode.moment_impulse_on_a - cross(pivot, episode.impulse_on_a);
            if wall_is_a { on_a } else { -on_a }
        });
        self.events.push(ContactEvent {
            kind: ContactEventKind::End,
            time,
            a,
            b,
            materials,
            episode,
            wall_angular_impulse,
        });
    }
}
