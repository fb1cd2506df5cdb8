//! Which source or inlet inserted each particle added during a run, so that messages and tables can name it the way
//! the scene does (`sources[1] #17`: the particle that source inserted after 17 others), as they name the bodies of
//! the start (`blocks[1] #17`).
//!
//! Body ids only grow and insertions take the next id, so the log is run-length encoded: consecutive ids from the
//! same inserter share one run. A scene without sources or inlets keeps an empty log; a source inserting one particle
//! at a time between other insertions costs 20 bytes per run.

use crate::BodyId;
use serde::{Deserialize, Serialize};

/// What inserts particles during a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Inserter {
    /// The drop source of this index (in the order the sources were added).
    Source(u32),
    /// The inlet of this index (in the order the inlets were added).
    Inlet(u32),
}

/// How a particle came into the World during the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Insertion {
    /// The source or inlet that inserted it.
    pub by: Inserter,
    /// How many particles the same inserter had inserted before it (0 for its first).
    pub ordinal: u32,
}

/// Consecutive body ids inserted by one inserter.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
struct InsertionRun {
    first: u32,
    count: u32,
    by: Inserter,
    /// The ordinal of `first` among its inserter's particles.
    first_ordinal: u32,
}

/// The inserter of every particle added during the run, by body id.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct InsertionLog {
    runs: Vec<InsertionRun>,
}

impl InsertionLog {
    /// Records that `by` inserted body `id`, whose id is above every id recorded before.
    pub(crate) fn record(&mut self, id: BodyId, by: Inserter) {
        if let Some(last) = self.runs.last_mut()
            && last.by == by
            && last.first + last.count == id.0
        {
            last.count += 1;
            return;
        }
        let first_ordinal =
            self.runs.iter().rev().find(|run| run.by == by).map_or(0, |run| run.first_ordinal + run.count);
        self.runs.push(InsertionRun { first: id.0, count: 1, by, first_ordinal });
    }

    /// How body `id` was inserted; `None` for a body of the start (or an id never used).
    pub fn of(&self, id: BodyId) -> Option<Insertion> {
        let index = self.runs.partition_point(|run| run.first + run.count <= id.0);
        let run = self.runs.get(index).filter(|run| run.first <= id.0)?;
        Some(Insertion { by: run.by, ordinal: run.first_ordinal + (id.0 - run.first) })
    }

    /// Heap bytes of the log, from its capacity.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.runs.capacity() * std::mem::size_of::<InsertionRun>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_inserted_body_is_named_by_its_inserter_and_count() {
        let mut log = InsertionLog::default();
        // Bodies 0–4 are the start; two sources and an inlet then insert 5, 6, 7 (source 0), 8 (source 1), 9 (inlet
        // 0), 10 (source 0), 12 (source 1; 11 was a body added by hand).
        let inserted = [
            (5, Inserter::Source(0)),
            (6, Inserter::Source(0)),
            (7, Inserter::Source(0)),
            (8, Inserter::Source(1)),
            (9, Inserter::Inlet(0)),
            (10, Inserter::Source(0)),
            (12, Inserter::Source(1)),
        ];
        for (id, by) in inserted {
            log.record(BodyId(id), by);
        }
        assert_eq!(log.runs.len(), 5, "5, 6 and 7 share a run");
        let named = |id| log.of(BodyId(id)).map(|i| (i.by, i.ordinal));
        assert_eq!(named(4), None);
        assert_eq!(named(5), Some((Inserter::Source(0), 0)));
        assert_eq!(named(7), Some((Inserter::Source(0), 2)));
        assert_eq!(named(8), Some((Inserter::Source(1), 0)));
        assert_eq!(named(9), Some((Inserter::Inlet(0), 0)));
        assert_eq!(named(10), Some((Inserter::Source(0), 3)));
        assert_eq!(named(11), None);
        assert_eq!(named(12), Some((Inserter::Source(1), 1)));
        assert_eq!(named(13), None);
    }
}
