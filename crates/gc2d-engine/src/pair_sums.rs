//! The step's sums over the pair list (the energy ledger's contact terms, the energy the contacts store, the chatter
//! watch, the contact statistics), taken in the parallel narrowphase pass instead of a sequential one.
//!
//! Each fixed chunk of [`PAIRS_PER_CHUNK`] pairs sums its own pairs in list order; the step then adds the chunks'
//! sums in list order. The grouping depends only on the pair list, never on the thread count, so the sums stay
//! bitwise the same for any number of threads and across a checkpoint split. A pair therefore keeps none of its
//! ledger terms in its record ([`PairContact`]), only its dissipation for the contact events.

use crate::broadphase::PairEntry;
use crate::narrowphase::{LedgerTerms, PairContact};
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

    /// Highest minus lowest body id; 0 for an empty span.
    fn width(&self) -> u32 {
        self.highest.saturating_sub(self.lowest)
    }
}

/// The most touching pairs of one chunk that [`PairSums::set_strays_apart`] sets apart.
pub(crate) const MAX_STRAYS: usize = 4;

/// Touching pairs of a chunk whose bodies lie far from those of the chunk's other touching pairs, by their positions
/// in the chunk, ascending. Until the pair list is sorted again, every removal moves the list's last pair, from
/// anywhere in the pile, into the freed place, and one such pair among neighbours makes a chunk's span reach across
/// the pile; a range of bodies that misses the rest of the chunk then adds only these (docs/performance.md, "The force
/// accumulation's ranges read a third of the pair list").
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Strays {
    positions: [u8; MAX_STRAYS],
    count: u8,
}

/// The [`MAX_STRAYS`] + 1 touching pairs of a chunk with the lowest keys, as `(key, position)` in ascending order
/// (the one offered first among equal keys); fewer where the chunk has fewer.
#[derive(Default)]
struct Extremes {
    entries: [(u32, usize); MAX_STRAYS + 1],
    len: usize,
}

impl Extremes {
    /// Takes the pair at `position` if its key is among the lowest so far.
    fn offer(&mut self, key: u32, position: usize) {
        let full = self.len == self.entries.len();
        if full && key >= self.entries[self.len - 1].0 {
            return;
        }
        let mut slot = if full { self.len - 1 } else { self.len };
        self.len += usize::from(!full);
        while slot > 0 && self.entries[slot - 1].0 > key {
            self.entries[slot] = self.entries[slot - 1];
            slot -= 1;
        }
        self.entries[slot] = (key, position);
    }

    /// The entry with the lowest key among the pairs not in `left_out`: the lowest of all those pairs while at most
    /// [`MAX_STRAYS`] are left out.
    fn first_outside(&self, left_out: &Strays) -> Option<(u32, usize)> {
        self.entries[..self.len].iter().find(|(_, position)| !left_out.contains(*position)).copied()
    }
}

impl Strays {
    /// Positions of the stray pairs in their chunk, ascending.
    pub fn positions(&self) -> &[u8] {
        &self.positions[..usize::from(self.count)]
    }

    fn contains(&self, position: usize) -> bool {
        self.positions().iter().any(|&k| usize::from(k) == position)
    }

    /// Adds the pair at `position` (below 256: chunks hold [`PAIRS_PER_CHUNK`] pairs); there must be room.
    fn push(&mut self, position: usize) {
        self.positions[usize::from(self.count)] = position as u8;
        self.count += 1;
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
    /// The bodies of the touching pairs that are not strays.
    pub core_bodies: BodySpan,
    /// The touching pairs set apart from the others ([`Self::set_strays_apart`]).
    pub strays: Strays,
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

    /// After the chunk's pairs are added: sets apart the touching pairs that lie far from the others, at most
    /// [`MAX_STRAYS`], and keeps the span of the rest as `core_bodies`. Leaving out, one at a time, the pair that
    /// holds the lowest or the highest body of the remaining ones (whichever leaves the narrower span) gives the
    /// narrowest span with [`MAX_STRAYS`] left out; the strays are the fewest first ones that come within twice that
    /// width, and none unless they at least halve the chunk's span (a chunk of neighbours keeps all its pairs, as does
    /// one with more far pairs than strays). A pass of two comparisons a pair settles most chunks; the rest take
    /// two more passes. A function of the chunk alone, and which pairs a range reads never changes the sums.
    pub fn set_strays_apart(&mut self, chunk: &[PairEntry<PairContact>]) {
        self.keep_every_pair_in_the_core();
        if !self.may_have_strays(chunk) {
            return;
        }
        // Only the pairs with the few lowest first bodies and the few highest second bodies can be left out. The
        // second bodies are offered from the chunk's end: in a chunk in list order they then mostly fall, and most
        // offers are turned down at once.
        let touching = |(_, pair): &(usize, &PairEntry<PairContact>)| pair.payload.touching;
        let (mut lowest, mut highest) = (Extremes::default(), Extremes::default());
        chunk.iter().enumerate().filter(touching).for_each(|(k, pair)| lowest.offer(pair.a(), k));
        chunk.iter().enumerate().rev().filter(touching).for_each(|(k, pair)| highest.offer(u32::MAX - pair.b(), k));
        let span_without = |left_out: &Strays| match (lowest.first_outside(left_out), highest.first_outside(left_out)) {
            (Some((a, _)), Some((b_complement, _))) => BodySpan { lowest: a, highest: u32::MAX - b_complement },
            _ => BodySpan::default(),
        };
        // Left out one by one: the first n of `left_out` leave `spans[n]`.
        let mut left_out = Strays::default();
        let mut spans = [self.touching_bodies; MAX_STRAYS + 1];
        for n in 0..MAX_STRAYS {
            let candidates = [lowest.first_outside(&left_out), highest.first_outside(&left_out)];
            let narrowest = candidates
                .into_iter()
                .flatten()
                .map(|(_, k)| {
                    let mut trial = left_out;
                    trial.push(k);
                    (k, span_without(&trial))
                })
                .min_by_key(|(_, span)| span.width());
            let Some((k, span)) = narrowest else { break };
            left_out.push(k);
            spans[n + 1] = span;
        }
        let best = spans[usize::from(left_out.count)].width();
        let whole = self.touching_bodies.width();
        let kept = (0..=usize::from(left_out.count))
            .find(|&n| u64::from(spans[n].width()) <= 2 * u64::from(best))
            .filter(|&n| 2 * u64::from(spans[n].width()) <= u64::from(whole))
            .unwrap_or(0);
        left_out.positions()[..kept].iter().for_each(|&k| self.strays.push(usize::from(k)));
        self.strays.positions[..kept].sort_unstable();
        self.core_bodies = spans[kept];
    }

    /// Sets no pair apart: the core is every touching pair (for a single range of bodies, which reads every chunk
    /// that holds a touching pair anyway).
    pub fn keep_every_pair_in_the_core(&mut self) {
        self.strays = Strays::default();
        self.core_bodies = self.touching_bodies;
    }

    /// Whether leaving out at most [`MAX_STRAYS`] touching pairs could halve the chunk's span, checked in one pass
    /// of two comparisons a pair: a span [L, H] at most half as wide lies at least a quarter of the width in from one
    /// end, so at most [`MAX_STRAYS`] pairs reach into the lowest or into the highest quarter. A chunk of neighbours
    /// fails this, and is done; so is a span under four bodies wide, which has nothing worth setting apart.
    fn may_have_strays(&self, chunk: &[PairEntry<PairContact>]) -> bool {
        let span = self.touching_bodies;
        let quarter = span.width() / 4;
        if quarter == 0 {
            return false;
        }
        let (mut in_lowest, mut in_highest) = (0, 0);
        for pair in chunk.iter().filter(|pair| pair.payload.touching) {
            in_lowest += usize::from(pair.a() < span.lowest + quarter);
            in_highest += usize::from(pair.b() > span.highest - quarter);
        }
        in_lowest <= MAX_STRAYS || in_highest <= MAX_STRAYS
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

    /// The chunk of `keys` (touching where `touching` says) with its sums and strays set apart.
    fn chunk_with_strays(keys: &[(u32, u32)], touching: impl Fn(usize) -> bool) -> PairSums {
        let chunk: Vec<PairEntry<PairContact>> = keys
            .iter()
            .enumerate()
            .map(|(k, &(a, b))| {
                let contact = if touching(k) { touching_pair(1.0, 0.0) } else { PairContact::default() };
                PairEntry::for_test(a, b, contact)
            })
            .collect();
        let mut sums = PairSums::default();
        chunk.iter().for_each(|p| sums.add_pair(p.a(), p.b(), &p.payload, &LedgerTerms::default(), 0.0));
        sums.set_strays_apart(&chunk);
        sums
    }

    /// Pairs of bodies far from the chunk's others (a removal moved them in) are set apart, the rest keep their span;
    /// a chunk of neighbours has none, and pairs apart count for nothing.
    #[test]
    fn pairs_far_from_the_rest_of_their_chunk_are_set_apart() {
        let neighbours: Vec<(u32, u32)> = (0..60).map(|k| (1000 + k / 2, 1000 + k / 2 + 140)).collect();
        let plain = chunk_with_strays(&neighbours, |_| true);
        assert_eq!(plain.strays.positions(), &[] as &[u8]);
        assert_eq!(plain.core_bodies, plain.touching_bodies);

        let mut polluted = neighbours.clone();
        polluted[7] = (9885, 9886);
        polluted[40] = (3, 8986);
        polluted[50] = (20, 25);
        let sums = chunk_with_strays(&polluted, |_| true);
        assert_eq!(sums.strays.positions(), &[7, 40, 50]);
        assert_eq!(sums.core_bodies, BodySpan { lowest: 1000, highest: 1169 });
        assert!(sums.touching_bodies.meets(9885, 9886) && !sums.core_bodies.meets(9000, 10_000));

        // The far pairs apart: nothing to set apart.
        let apart = chunk_with_strays(&polluted, |k| ![7, 40, 50].contains(&k));
        assert_eq!(apart.strays.positions(), &[] as &[u8]);
        // More far pairs than strays: setting four apart would not narrow the chunk, so none are.
        let mut crowded = neighbours.clone();
        for (slot, far) in [(1, 5000), (2, 6000), (3, 7000), (4, 8000), (5, 9000), (6, 9500)] {
            crowded[slot] = (far, far + 1);
        }
        let crowded_sums = chunk_with_strays(&crowded, |_| true);
        assert_eq!(crowded_sums.strays.positions(), &[] as &[u8]);
        assert_eq!(crowded_sums.core_bodies, crowded_sums.touching_bodies);
    }
}
