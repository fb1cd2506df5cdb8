//! The step's sums over the pair list (the energy ledger's contact terms, the energy the contacts store, the chatter
//! watch, the contact statistics), taken in the parallel narrowphase pass instead of a sequential one.
//!
//! Each fixed chunk of [`PAIRS_PER_CHUNK`] pairs sums its own pairs in list order; the step then adds the chunks'
//! sums in list order. The grouping depends only on the pair list, never on the thread count, so the sums stay
//! bitwise the same for any number of threads and across a checkpoint split. A pair therefore keeps none of its
//! ledger terms in its record ([`PairContact`]), only its dissipation for the contact events.

use crate::narrowphase::{LedgerTerms, PairContact, PairEvaluation};
use glam::DVec2;

/// Pairs per chunk of the narrowphase pass. Fixed, so that the sums are grouped the same way for any thread count.
/// 64 pairs of a dense pile take some 13 µs; chunks of 256 pairs made two threads about 5 % slower on a 2,000-grain
/// pile (docs/performance.md, "The chunk size").
pub(crate) const PAIRS_PER_CHUNK: usize = 64;

/// The most chunks a thread takes at a time in the narrowphase pass. Left to itself, rayon cuts the list into about
/// two pieces per thread (quarters on two threads) and cuts a piece further only when another thread steals it, so a
/// thread that ends its pieces early, or runs on a core that is slower at the moment, waits for the others' last
/// piece. Pieces of four chunks (some 50 µs of a dense pile) let the threads share the end of the pass: on two threads
/// the dense 10,000-grain pile's narrowphase took 1,495–1,534 instead of 1,646 µs a step (docs/performance.md,
/// "Smaller pieces of the narrowphase for the threads"). Which thread evaluates a chunk never changes a result.
pub(crate) const CHUNKS_PER_TASK: usize = 4;

/// What one chunk of pairs adds to the step's sums.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct PairSums {
    /// The ledger's contact terms of the step.
    pub energy: LedgerTerms,
    /// Energy the contacts store after the step, J.
    pub contact_stored: f64,
    /// The pairs' expansion virials (0 unless the World is heated), J (`heating.rs`).
    pub expansion_virial: f64,
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
}

impl PairSums {
    /// Adds the pair that was just evaluated: its record, what its evaluation returned (the ledger terms, the
    /// closest-feature passes) and its overlap fraction ([`crate::narrowphase::PairContext::overlap_fraction`]; 0
    /// when it does not touch). `HEATED`: whether the World is heated, so that the pair's expansion virial counts (as
    /// in [`crate::narrowphase::PairContext::evaluate`], a constant of the compiled code).
    #[inline]
    pub fn add_pair<const HEATED: bool>(
        &mut self,
        contact: &PairContact,
        evaluation: &PairEvaluation,
        overlap_fraction: f64,
    ) {
        self.multi_pass_queries += usize::from(evaluation.passes > 1);
        if contact.is_quiet() {
            // Nothing stored, no force now or before, an evaluation that booked nothing: every sum below would add
            // +0.0, which changes no sum (they start at +0.0 and so are never −0.0), and the pair is not touching.
            return;
        }
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
        self.energy.add(&evaluation.ledger);
        if HEATED {
            self.expansion_virial += evaluation.expansion_virial;
        }
        if contact.touching {
            self.contacts += 1;
            self.max_overlap_fraction = self.max_overlap_fraction.max(overlap_fraction);
        }
    }

    /// Adds the sums of the next chunk.
    pub fn add(&mut self, chunk: &PairSums) {
        self.energy.add(&chunk.energy);
        self.contact_stored += chunk.contact_stored;
        self.expansion_virial += chunk.expansion_virial;
        self.alternation += chunk.alternation;
        self.force_scale += chunk.force_scale;
        self.contacts += chunk.contacts;
        self.multi_pass_queries += chunk.multi_pass_queries;
        self.max_overlap_fraction = self.max_overlap_fraction.max(chunk.max_overlap_fraction);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::narrowphase::QUIET_EVALUATIONS;

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
        let terms = PairEvaluation {
            ledger: LedgerTerms { normal_damping: 0.5, sliding: 0.25, ..LedgerTerms::default() },
            passes: 1,
            expansion_virial: 0.125,
        };
        let mut whole = PairSums::default();
        pairs.iter().enumerate().for_each(|(k, pair)| whole.add_pair::<true>(pair, &terms, fraction(k)));
        let mut by_chunks = PairSums::default();
        for (c, chunk) in pairs.chunks(PAIRS_PER_CHUNK).enumerate() {
            let mut sums = PairSums::default();
            for (k, pair) in chunk.iter().enumerate() {
                sums.add_pair::<true>(pair, &terms, fraction(c * PAIRS_PER_CHUNK + k));
            }
            by_chunks.add(&sums);
        }
        assert_eq!(by_chunks, whole);
        assert_eq!((whole.contacts, whole.max_overlap_fraction), (1000, 1e-4 * 999.0));
        assert_eq!((whole.energy.normal_damping, whole.energy.sliding), (500.0, 250.0));
        assert_eq!(whole.contact_stored, 0.25 * 999.0 * 1000.0 / 2.0);
        assert_eq!(whole.expansion_virial, 125.0);
        assert_eq!(whole.alternation, 0.0, "a steady force does not alternate");
    }

    /// A quiet pair (apart, no force now or before, nothing stored) adds what its full sums would add, bit for bit:
    /// only its closest-feature passes count, whatever came before it.
    #[test]
    fn a_quiet_pair_adds_only_its_passes() {
        let quiet = PairContact { quiet_evaluations: QUIET_EVALUATIONS, ..PairContact::default() };
        let two_passes = PairEvaluation { passes: 2, ..PairEvaluation::default() };
        let loud = PairContact { quiet_evaluations: 0, ..quiet };
        assert!(quiet.is_quiet() && !loud.is_quiet());
        let before = [PairSums::default(), {
            let mut sums = PairSums::default();
            let ledger = LedgerTerms { work_walls: -1.0, ..LedgerTerms::default() };
            sums.add_pair::<false>(
                &touching_pair(3.0, 0.5),
                &PairEvaluation { ledger, passes: 1, ..PairEvaluation::default() },
                0.1,
            );
            sums
        }];
        for start in before {
            let (mut skipped, mut full) = (start, start);
            skipped.add_pair::<false>(&quiet, &two_passes, 0.0);
            full.add_pair::<false>(&loud, &two_passes, 0.0);
            assert_eq!(format!("{skipped:?}"), format!("{full:?}"));
            assert_eq!(skipped.multi_pass_queries, start.multi_pass_queries + 1);
        }
    }
}
