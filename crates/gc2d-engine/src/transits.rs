//! Transit records of a feed pipe (issue 15 item 5): when and through which inlet each particle came in, and, for
//! each particle an outlet removes, a record of its passage from inlet to outlet. Kept only in Worlds with inlets or
//! outlets; the entries are part of the World's state (checkpoints carry them), the step's passages are not.

use crate::bodies::BodyId;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Where and when a particle came in.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct InletEntry {
    /// The inlet's index in [`crate::World::inlets`].
    pub inlet: usize,
    /// The time it was inserted (the end of the step it fell due in), s.
    pub time: f64,
}

/// A particle an outlet removed on the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transit {
    /// The particle (its body id while it was in the World).
    pub body: BodyId,
    /// How it came in: `None` for a particle present at the start or inserted by a source.
    pub entry: Option<InletEntry>,
    /// The outlet's index in [`crate::World::outlets`].
    pub outlet: usize,
    /// The time it was removed (the end of the step it crossed the outlet in), s.
    pub time: f64,
}

impl Transit {
    /// Its time from inlet to outlet, s; `None` for a particle that did not come through an inlet.
    pub fn transit_time(&self) -> Option<f64> {
        self.entry.map(|entry| self.time - entry.time)
    }
}

/// The entries of the particles inside and the passages of the last step.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct TransitLog {
    /// Entries of the particles still in the World that came through an inlet, by body id.
    entries: BTreeMap<u32, InletEntry>,
    /// Passages of the last step, in removal order; refilled every step, so not saved.
    #[serde(skip)]
    last_step: Vec<Transit>,
}

impl TransitLog {
    /// Forgets the last step's passages (at the start of a step).
    pub fn start_step(&mut self) {
        self.last_step.clear();
    }

    /// Notes that `body` came in through inlet `inlet` at `time`.
    pub fn entered(&mut self, body: BodyId, inlet: usize, time: f64) {
        self.entries.insert(body.0, InletEntry { inlet, time });
    }

    /// Notes that `body` left through outlet `outlet` at `time`.
    pub fn left(&mut self, body: BodyId, outlet: usize, time: f64) {
        let entry = self.entries.remove(&body.0);
        self.last_step.push(Transit { body, entry, outlet, time });
    }

    /// Forgets the entry of `body`, which left the World otherwise (through the domain's boundary).
    pub fn forget(&mut self, body: BodyId) {
        self.entries.remove(&body.0);
    }

    /// The passages of the last step.
    pub fn last_step(&self) -> &[Transit] {
        &self.last_step
    }

    /// Heap memory held, bytes (an estimate for the map's nodes).
    pub fn heap_bytes(&self) -> usize {
        self.entries.len() * (std::mem::size_of::<u32>() + std::mem::size_of::<InletEntry>() + 16)
            + self.last_step.capacity() * std::mem::size_of::<Transit>()
    }
}
