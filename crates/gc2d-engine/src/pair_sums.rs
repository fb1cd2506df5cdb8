//! The step's sums over the pair list (the energy ledger's contact terms, the energy the contacts store, the chatter
//! watch, the contact statistics), taken in the parallel narrowphase pass instead of a sequential one.
//!
//! Each fixed chunk of [`PAIRS_PER_CHUNK`] pairs sums its own pairs in list order; the step then adds the chunks'
//! sums in list order. The grouping depends only on the pair list, never on the thread count, so the sums stay
//! bitwise the same for any number of threads and across a checkpoint split. A pair therefore keeps none of its
//! ledger terms in its record ([`PairContact`]), only its dissipation for the contact events.

use crate::narrowphase::{LedgerTerms, PairContact};
use glam::DVec2;

/// Pairs per chunk of the narrowphase pass. Fixed, so that the sums are grouped the same way for any thread count.
/// A chunk is also the smallest piece of work a thread takes: 64 pairs of a dense pile take some 13 µs, so two threads
/// on a 2,000-grain pile (70 chunks) end a step within a few per cent of each other; chunks of 256 pairs left one
/// thread waiting for the other's last chunk and made two threads about 5 % slower there (docs/performance.md).
pub(crate) const PAIRS_PER_CHUNK: usize = 64;

/// The lowest and highest body id among a chunk's touching pairs: the force accumulation skips the chunks that touch
/// none of the bodies it adds up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BodySpan {
    lowest: u32,
    highest: u32,
}

impl Default for BodySpan {
    /// No body: meets no range.
    fn default() -> Self {
        Self { lowest: u32::MAX, highest: 0 }
    }
}

impl BodySpan {
    /// Widens the span to hold the pair {a, b} (a < b).
    #[inline]
    pub fn include(&mut self, a: u32, b: u32) {
        self.lowest = self.lowest.min(a);
        self.highest = self.highest.max(b);
    }

    /// Whether some body of the span may lie in `first..end`.
    #[inline]
    pub fn meets(&self, first: u32, end: u32) -> bool {
        self.lowest < end && self.highest >= first
    }
}

/// What one chunk of pairs adds to the step's sums.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct PairSums {
    /// The ledger's contact terms of the step.
    pub energy: LedgerTerms,
    /// Energy the contacts store after the step, J.
    pub contact_stored: f64,
    /// The chatter watch's Σ|F(n) − 2F(n−1) + F(n−2)|, N ([`crate::ForceAlternation`]).
    pub alternation: f64,
    /// The chatter watch's Σ(|F(n)| + |F(n−1)|), N.
    pub force_scale: f64,
    /// Pairs that touch.
    pub contacts: usize,
    /// Pairs whose closest-feature walk needed more than one pass.
    pub multi_pass_queries: usize,
    /// Largest overlap fraction of a touching pair.
    pub max_overlap_fraction: f64,
    /// The bodies of the touching pairs.
    pub touching_bodies: BodySpan,
}

impl PairSums {
    /// Adds the pair {a, b} (a < b) that was just evaluated: its record, the ledger terms its evaluation returned and
    /// its overlap fraction ([`crate::narrowphase::PairContext::overlap_fraction`]; 0 when it does not touch).
    #[inline]
    pub fn add_pair(&mut self, a: u32, b: u32, contact: &PairContact, energy: &LedgerTerms, overlap_fraction: f64) {
        self.contact_stored += contact.stored_energy;
        let [previous, before_previous] = contact.earlier_forces.map(|force| force.as_dvec2());
        // Only steps with a force now and two steps ago count: the first two steps of a contact and the steps after
        // its last change the force by a whole force (a Hertz force's onset alone reads 0.11) without any
        // alternation, so a bounce would read as chatter. Period-2 chatter is still seen: one that lifts off every
        // other step (F, 0, F, …) counts on its steps with a force, at the full ratio 1.
        if contact.force_on_a != DVec2::ZERO && before_previous != DVec2::ZERO {
            self.alternation += (contact.force_on_a - 2.0 * previous + before_previous).length();
            self.force_scale += contact.force_on_a.length() + previous.length();
        }
        self.multi_pass_queries += usize::from(contact.passes > 1);
        self.energy.add(energy);
        if contact.touching {
            self.contacts += 1;
            self.max_overlap_fraction = self.max_overlap_fraction.max(overlap_fraction);
            self.touching_bodies.include(a, b);
        }
    }

    /// Adds the sums of the next chunk.
    pub fn add(&mut self, chunk: &PairSums) {
        self.energy.add(&chunk.energy);
        self.contact_stored += chunk.contact_stored;
        self.alternation += chunk.alternation;
        self.force_scale += chunk.force_scale;
        self.contacts += chunk.contacts;
        self.multi_pass_queries += chunk.multi_pass_queries;
        self.max_overlap_fraction = self.max_overlap_fraction.max(chunk.max_overlap_fraction);
        self.touching_bodies.include(chunk.touching_bodies.lowest, chunk.touching_bodies.highest);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn touching_pair(force: f64, stored_energy: f64) -> PairContact {
        PairContact {
            touching: true,
            force_on_a: DVec2::new(force, 0.0),
            earlier_forces: [glam::Vec2::new(force as f32, 0.0); 2],
            stored_energy,
            ..PairContact::default()
        }
    }

    /// Sums by chunks equal the plain sums wherever the values add exactly, and counts and maxima are exact always.
    #[test]
    fn chunk_sums_add_up_to_the_sums_over_all_pairs() {
        let pairs: Vec<_> = (0..1000).map(|k| touching_pair(f64::from(k), 0.25 * f64::from(k))).collect();
        let fraction = |k: usize| 1e-4 * k as f64;
        let terms = LedgerTerms { normal_damping: 0.5, sliding: 0.25, ..LedgerTerms::default() };
        let ids = |k: usize| (k as u32, 2 * k as u32 + 1);
        let mut whole = PairSums::default();
        pairs.iter().enumerate().for_each(|(k, pair)| whole.add_pair(ids(k).0, ids(k).1, pair, &terms, fraction(k)));
        let mut by_chunks = PairSums::default();
        for (c, chunk) in pairs.chunks(PAIRS_PER_CHUNK).enumerate() {
            let mut sums = PairSums::default();
            for (k, pair) in chunk.iter().enumerate() {
                let (a, b) = ids(c * PAIRS_PER_CHUNK + k);
                sums.add_pair(a, b, pair, &terms, fraction(c * PAIRS_PER_CHUNK + k));
            }
            by_chunks.add(&sums);
        }
        assert_eq!(by_chunks, whole);
        assert_eq!((whole.contacts, whole.max_overlap_fraction), (1000, 1e-4 * 999.0));
        assert_eq!((whole.energy.normal_damping, whole.energy.sliding), (500.0, 250.0));
        assert_eq!(whole.contact_stored, 0.25 * 999.0 * 1000.0 / 2.0);
        assert_eq!(whole.alternation, 0.0, "a steady force does not alternate");
        assert!(whole.touching_bodies.meets(0, 1) && whole.touching_bodies.meets(1999, 2000));
        assert!(!whole.touching_bodies.meets(2000, 3000));
    }

    /// A chunk's span holds every body of its touching pairs and nothing of pairs apart.
    #[test]
    fn the_span_meets_exactly_the_ranges_that_hold_a_touching_body() {
        let terms = LedgerTerms::default();
        let mut sums = PairSums::default();
        assert!(!sums.touching_bodies.meets(0, u32::MAX), "an empty chunk meets no range");
        sums.add_pair(3, 900, &PairContact::default(), &terms, 0.0);
        assert!(!sums.touching_bodies.meets(0, u32::MAX), "pairs apart are not in the span");
        sums.add_pair(10, 40, &touching_pair(1.0, 0.0), &terms, 0.0);
        sums.add_pair(12, 25, &touching_pair(1.0, 0.0), &terms, 0.0);
        assert!(sums.touching_bodies.meets(40, 41) && sums.touching_bodies.meets(0, 11));
        assert!(!sums.touching_bodies.meets(41, 100) && !sums.touching_bodies.meets(0, 10));
    }
}
