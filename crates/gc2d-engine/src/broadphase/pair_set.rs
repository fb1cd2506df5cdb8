//! The persistent list of candidate pairs K^B (reference §4.2, footnote 9: a list, never an N×N matrix).
//!
//! Entries live in one dense `Vec`, so the narrowphase can run over them with `par_iter_mut`. A small open-addressing
//! table (linear probing, a fixed multiplicative hash, backward-shift deletion, at most three quarters full) finds an
//! entry by its two body ids in O(1). The table is not saved in checkpoints: loading rebuilds it from the entries.
//! Nothing here depends on a random seed or on memory addresses, so the same sequence of insertions and removals
//! gives the same entry order on every run.
//!
//! The entries are kept roughly in body order (sorted by (a, b)) so that the narrowphase, which walks them in list
//! order, reads the bodies' columns in nearly ascending order: new pairs are appended and removals swap the last entry
//! in, and once the list holds more than one descent per `SORT_WHEN_DESCENTS_EXCEED` entries it is sorted again
//! (docs/performance.md, "Pairs in body order"). The descent count is a function of the list alone, so the sorts
//! fall on the same steps in every run, for any thread count and across a checkpoint.

use rayon::slice::ParallelSliceMut;
use serde::{Deserialize, Serialize};

/// One candidate pair: two bodies whose bounding boxes overlap or touch, and the engine's per-pair record.
///
/// The record (`payload`) is created with `T::default()` when the boxes start to touch and lives until they separate,
/// which is the lifetime of gc2d's collision struct (reference §4.6, §10.2 D11): the contact history (old overlap area,
/// tangential spring, warm-start features) is kept here.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PairEntry<T> {
    a: u32,
    b: u32,
    /// The engine's per-pair record.
    pub payload: T,
}

impl<T> PairEntry<T> {
    /// The smaller body id of the pair.
    #[inline]
    pub fn a(&self) -> u32 {
        self.a
    }

    /// The larger body id of the pair.
    #[inline]
    pub fn b(&self) -> u32 {
        self.b
    }
}

use crate::bodies::vec_bytes;

/// Marks an unused slot of the index table.
const EMPTY: u32 = u32::MAX;

/// The smallest index table; it doubles whenever it would become more than three quarters full.
const MIN_SLOTS: usize = 64;

/// The index table is kept at most `MAX_LOAD_NUMERATOR / MAX_LOAD_DENOMINATOR` full. Three quarters rather than a
/// half: the table then takes 5–11 bytes per pair instead of 8–16 (about 13 bytes less per grain of a dense 7-gon
/// pile), while a lookup of a listed pair still probes 2.5 slots on average and one of a pair not listed about 8
/// (linear probing), within one or two cache lines of 16 slots. Lookups happen only where pairs start or stop
/// touching, not for every pair and step.
const MAX_LOAD_NUMERATOR: usize = 3;
const MAX_LOAD_DENOMINATOR: usize = 4;

/// The list is sorted again once it holds more than one descent (an entry whose key is below its predecessor's) per
/// this many entries. Every descent is a pair out of place, whose two bodies' columns the narrowphase reads far from
/// its neighbours' (on a 100,000-grain layer whose list held one descent in 23, each cost the narrowphase about 450 ns
/// a step, and a sort costs about 80 ns per entry): at one in 64 instead of 16 the 100,000-grain and 10⁶-grain layers
/// step 10–15 % faster and the 10,000-grain piles 0–4 %, and settling piles, whose pairs change fastest, sort more
/// often and still settle as fast or faster (docs/performance.md, "The pair list closer to body order").
const SORT_WHEN_DESCENTS_EXCEED: usize = 64;

/// A list of at least this many pairs is sorted in parallel where the pool has several threads: a sort of the
/// 100,000-grain layer's 200,000 pairs took 13–15 ms on one thread here and about 28 ms of one thread's time on the
/// 16-core machine, once in about 80 steps, which on 16 threads was 7 % of the step (docs/performance.md, "The
/// layer's broadphase on many threads"). The keys are unique, so any correct sort gives the same order.
const PARALLEL_SORT_MIN_ENTRIES: usize = 1 << 14;

/// Dense pair entries plus an index from (a, b) to the entry's position.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(from = "SavedPairSet<T>")]
pub(crate) struct PairSet<T> {
    entries: Vec<PairEntry<T>>,
    /// Open-addressing table of entry positions; its length is zero or a power of two. Rebuilt on loading.
    #[serde(skip)]
    slots: Vec<u32>,
    /// The number of descents in `entries` (positions whose key is below the one before), kept up to date by every
    /// change; `None` after loading a checkpoint until the next [`sort_if_disordered`](Self::sort_if_disordered)
    /// counts them.
    #[serde(skip)]
    descents: Option<usize>,
}

/// What a checkpoint holds of a [`PairSet`]: its entries, in list order (the layout of the serialized `PairSet`,
/// whose other fields are skipped).
#[derive(Deserialize)]
struct SavedPairSet<T> {
    entries: Vec<PairEntry<T>>,
}

impl<T> From<SavedPairSet<T>> for PairSet<T> {
    /// The loaded list with its index table built at the smallest size that holds it; its descents are counted at
    /// the next [`sort_if_disordered`](PairSet::sort_if_disordered).
    fn from(saved: SavedPairSet<T>) -> Self {
        let mut set = Self { entries: saved.entries, slots: Vec::new(), descents: None };
        set.rebuild_index(index_size_for(set.entries.len()));
        set
    }
}

/// The smallest index table (a power of two, at least [`MIN_SLOTS`]) that holds `entries` within the load limit.
fn index_size_for(entries: usize) -> usize {
    let mut size = MIN_SLOTS;
    while entries * MAX_LOAD_DENOMINATOR > size * MAX_LOAD_NUMERATOR {
        size *= 2;
    }
    size
}

impl<T> Default for PairSet<T> {
    fn default() -> Self {
        Self { entries: Vec::new(), slots: Vec::new(), descents: Some(0) }
    }
}

/// The pair key with the smaller id first, or `None` for a body paired with itself.
#[inline]
fn ordered(a: u32, b: u32) -> Option<(u32, u32)> {
    match a.cmp(&b) {
        std::cmp::Ordering::Less => Some((a, b)),
        std::cmp::Ordering::Greater => Some((b, a)),
        std::cmp::Ordering::Equal => None,
    }
}

/// Fixed hash of an ordered pair (Fibonacci hashing of the packed 64-bit key, high bits folded down).
#[inline]
fn hash(a: u32, b: u32) -> usize {
    let key = (u64::from(a) << 32) | u64::from(b);
    let mixed = key.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    (mixed ^ (mixed >> 29)) as usize
}

impl<T> PairEntry<T> {
    /// An entry for the pair {a, b} (a < b), for tests that need a pair list without a broadphase.
    #[cfg(test)]
    pub(crate) fn for_test(a: u32, b: u32, payload: T) -> Self {
        assert!(a < b, "a pair entry holds the smaller id first");
        Self { a, b, payload }
    }

    /// The pair's key, by which the list is sorted.
    #[inline]
    fn key(&self) -> (u32, u32) {
        (self.a, self.b)
    }
}

impl<T: Default + Send> PairSet<T> {
    /// All entries: new pairs appended, removed ones replaced by the last entry, the whole list sorted by body ids
    /// from time to time.
    #[inline]
    pub(crate) fn entries(&self) -> &[PairEntry<T>] {
        &self.entries
    }

    /// All entries, mutable (only the payloads can be changed).
    #[inline]
    pub(crate) fn entries_mut(&mut self) -> &mut [PairEntry<T>] {
        &mut self.entries
    }

    /// Heap bytes of the entries and the index table, from their capacities.
    pub(crate) fn heap_bytes(&self) -> usize {
        vec_bytes(&self.entries) + vec_bytes(&self.slots)
    }

    /// Gives back the spare room of the entries, and shrinks the index table to the smallest size that holds them.
    pub(crate) fn shrink_to_fit(&mut self) {
        self.entries.shrink_to_fit();
        let size = index_size_for(self.entries.len());
        if size < self.slots.len() {
            self.rebuild_index(size);
            self.slots.shrink_to_fit();
        }
    }

    /// The entry of the pair {a, b}, if present.
    pub(crate) fn get(&self, a: u32, b: u32) -> Option<&PairEntry<T>> {
        let (a, b) = ordered(a, b)?;
        let slot = self.find(a, b).ok()?;
        Some(&self.entries[self.slots[slot] as usize])
    }

    /// The entry of the pair {a, b}, mutable, if present.
    pub(crate) fn get_mut(&mut self, a: u32, b: u32) -> Option<&mut PairEntry<T>> {
        let (a, b) = ordered(a, b)?;
        let slot = self.find(a, b).ok()?;
        Some(&mut self.entries[self.slots[slot] as usize])
    }

    /// Adds the pair {a, b} with a default payload at the end of the list. Returns false when it was already there
    /// (its payload is kept) or when `a == b`.
    pub(crate) fn insert(&mut self, a: u32, b: u32) -> bool {
        let Some((a, b)) = ordered(a, b) else { return false };
        if (self.entries.len() + 1) * MAX_LOAD_DENOMINATOR > self.slots.len() * MAX_LOAD_NUMERATOR {
            self.grow();
        }
        match self.find(a, b) {
            Ok(_) => false,
            Err(empty) => {
                self.slots[empty] = self.entries.len() as u32;
                if self.entries.len() == self.entries.capacity() {
                    // Grow by a sixteenth rather than the doubling of `Vec::push`: the entries carry the contact
                    // records and are most of a World's memory (a sixteenth of spare room is 24 B per grain of a
                    // dense 7-gon pile, an eighth was 48, a quarter 96), and a fixed fraction keeps insertion
                    // amortised O(1): each entry is copied about 16 times while a list grows from empty.
                    self.entries.reserve_exact(self.entries.capacity() / 16 + MIN_SLOTS);
                }
                let descent = self.entries.last().is_some_and(|last| last.key() > (a, b));
                self.entries.push(PairEntry { a, b, payload: T::default() });
                if let Some(descents) = &mut self.descents {
                    *descents += usize::from(descent);
                }
                true
            }
        }
    }

    /// Removes the pair {a, b} and hands back its entry. The last entry moves into the freed position.
    pub(crate) fn remove(&mut self, a: u32, b: u32) -> Option<PairEntry<T>> {
        let (a, b) = ordered(a, b)?;
        let slot = self.find(a, b).ok()?;
        Some(self.remove_slot(slot))
    }

    /// Removes every pair that contains `body`, appending the removed entries to `ended` (last entry first).
    pub(crate) fn remove_body(&mut self, body: u32, ended: &mut Vec<PairEntry<T>>) -> usize {
        let mut removed = 0;
        for index in (0..self.entries.len()).rev() {
            let entry = &self.entries[index];
            if entry.a == body || entry.b == body {
                if let Ok(slot) = self.find(entry.a, entry.b) {
                    ended.push(self.remove_slot(slot));
                    removed += 1;
                }
            }
        }
        removed
    }

    /// The slot holding the ordered pair (a, b), or the empty slot where it would go.
    fn find(&self, a: u32, b: u32) -> Result<usize, usize> {
        if self.slots.is_empty() {
            return Err(0);
        }
        let mask = self.slots.len() - 1;
        let mut slot = hash(a, b) & mask;
        loop {
            let index = self.slots[slot];
            if index == EMPTY {
                return Err(slot);
            }
            let entry = &self.entries[index as usize];
            if entry.a == a && entry.b == b {
                return Ok(slot);
            }
            slot = (slot + 1) & mask;
        }
    }

    /// Empties `slot` by shifting later members of its probe run back (no tombstones), then swap-removes the entry
    /// (the last entry takes its position).
    fn remove_slot(&mut self, slot: usize) -> PairEntry<T> {
        let index = self.slots[slot] as usize;
        let mask = self.slots.len() - 1;
        let mut hole = slot;
        let mut probe = (slot + 1) & mask;
        loop {
            let occupant = self.slots[probe];
            if occupant == EMPTY {
                break;
            }
            let entry = &self.entries[occupant as usize];
            let home = hash(entry.a, entry.b) & mask;
            // The occupant may move into the hole if the hole lies on its probe path, i.e. in [home, probe).
            if (probe.wrapping_sub(home) & mask) >= (probe.wrapping_sub(hole) & mask) {
                self.slots[hole] = occupant;
                hole = probe;
            }
            probe = (probe + 1) & mask;
        }
        self.slots[hole] = EMPTY;
        let last = self.entries.len() - 1;
        if index != last {
            let moved = &self.entries[last];
            if let Ok(moved_slot) = self.find(moved.a, moved.b) {
                self.slots[moved_slot] = index as u32;
            }
        }
        // The positions whose predecessor changes: the freed one and the one after it (the moved entry's
        // neighbours), and the last (which goes).
        let mut touched = [index, index + 1, last];
        touched.sort_unstable();
        let before = self.descents_at(&touched);
        let removed = self.entries.swap_remove(index);
        let after = self.descents_at(&touched);
        if let Some(descents) = &mut self.descents {
            *descents = *descents + after - before;
        }
        removed
    }

    /// The number of distinct positions among `positions` (ascending, repeats adjacent) that are descents.
    fn descents_at(&self, positions: &[usize]) -> usize {
        let mut count = 0;
        let mut previous = None;
        for &position in positions {
            if previous != Some(position) && self.is_descent(position) {
                count += 1;
            }
            previous = Some(position);
        }
        count
    }

    /// Whether the entry at `position` has a key below its predecessor's (false at 0 and past the end).
    fn is_descent(&self, position: usize) -> bool {
        position > 0 && position < self.entries.len() && self.entries[position - 1].key() > self.entries[position].key()
    }

    /// The descents counted from scratch, one pass over the list.
    fn count_descents(&self) -> usize {
        (1..self.entries.len()).filter(|&position| self.is_descent(position)).count()
    }

    /// Sorts the entries by their body ids when more than one in `SORT_WHEN_DESCENTS_EXCEED` is a descent, and
    /// rebuilds the index. Returns whether it sorted. The keys are unique, so the order is the same on every run.
    pub(crate) fn sort_if_disordered(&mut self) -> bool {
        let descents = self.descents.unwrap_or_else(|| self.count_descents());
        self.descents = Some(descents);
        if descents * SORT_WHEN_DESCENTS_EXCEED <= self.entries.len() {
            return false;
        }
        if self.entries.len() >= PARALLEL_SORT_MIN_ENTRIES && rayon::current_num_threads() > 1 {
            self.entries.par_sort_unstable_by_key(PairEntry::key);
        } else {
            self.entries.sort_unstable_by_key(PairEntry::key);
        }
        self.descents = Some(0);
        self.rebuild_index(self.slots.len());
        true
    }

    /// Doubles the index table and re-inserts every entry in list order.
    fn grow(&mut self) {
        self.rebuild_index((self.slots.len() * 2).max(MIN_SLOTS));
    }
}

impl<T> PairSet<T> {
    /// Fills an index table of `size` slots (a power of two) with every entry's position.
    fn rebuild_index(&mut self, size: usize) {
        self.slots.clear();
        self.slots.resize(size, EMPTY);
        let mask = size - 1;
        for (index, entry) in self.entries.iter().enumerate() {
            let mut slot = hash(entry.a, entry.b) & mask;
            while self.slots[slot] != EMPTY {
                slot = (slot + 1) & mask;
            }
            self.slots[slot] = index as u32;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::collections::BTreeMap;

    #[test]
    fn pairs_are_stored_with_the_smaller_id_first_and_never_with_themselves() {
        let mut set = PairSet::<u8>::default();
        assert!(set.insert(7, 3));
        assert!(!set.insert(3, 7));
        assert!(!set.insert(4, 4));
        assert_eq!((set.entries()[0].a(), set.entries()[0].b()), (3, 7));
        assert!(set.get(7, 3).is_some());
    }

    #[test]
    fn matches_an_ordered_map_under_random_insertions_and_removals() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut set = PairSet::<u32>::default();
        let mut model = BTreeMap::new();
        for step in 0..20_000u32 {
            let a = rng.random_range(0..60);
            let b = rng.random_range(0..60);
            if a == b {
                continue;
            }
            let key = (a.min(b), a.max(b));
            if rng.random_bool(0.55) {
                let added = set.insert(a, b);
                assert_eq!(added, !model.contains_key(&key));
                if added {
                    set.get_mut(a, b).unwrap().payload = step;
                    model.insert(key, step);
                }
            } else {
                let removed = set.remove(a, b).map(|e| e.payload);
                assert_eq!(removed, model.remove(&key));
            }
            assert_eq!(set.entries().len(), model.len());
        }
        for entry in set.entries() {
            assert_eq!(model.get(&(entry.a(), entry.b())), Some(&entry.payload));
        }
    }

    #[test]
    fn the_descent_count_follows_every_change_and_a_sort_keeps_every_pair_findable() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut set = PairSet::<u32>::default();
        let mut model = BTreeMap::new();
        let mut sorts = 0;
        for step in 0..20_000u32 {
            let (a, b) = (rng.random_range(0..80), rng.random_range(0..80));
            if rng.random_bool(0.5) {
                if set.insert(a, b) {
                    set.get_mut(a, b).unwrap().payload = step;
                    model.insert((a.min(b), a.max(b)), step);
                }
            } else if let Some(entry) = set.remove(a, b) {
                assert_eq!(model.remove(&(entry.a(), entry.b())), Some(entry.payload));
            }
            assert_eq!(set.descents, Some(set.count_descents()), "step {step}");
            if step % 50 == 0 && set.sort_if_disordered() {
                sorts += 1;
                assert!(set.entries.is_sorted_by_key(PairEntry::key));
                assert_eq!(set.descents, Some(0));
            }
            assert!(set.count_descents() * SORT_WHEN_DESCENTS_EXCEED <= set.entries.len() || step % 50 != 0);
        }
        assert!(sorts > 10, "only {sorts} sorts");
        for (&(a, b), &payload) in &model {
            assert_eq!(set.get(b, a).map(|e| e.payload), Some(payload));
        }
    }

    /// A list long enough to be sorted in parallel ends in the same order, every pair findable, on 1 to 4 threads.
    #[test]
    fn a_long_list_sorts_to_the_same_order_on_any_thread_count() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let mut unsorted = PairSet::<u32>::default();
        while unsorted.entries.len() < PARALLEL_SORT_MIN_ENTRIES + 1000 {
            let (a, b) = (rng.random_range(0..5_000), rng.random_range(0..5_000));
            if unsorted.insert(a, b) {
                unsorted.get_mut(a, b).unwrap().payload = a ^ b;
            }
        }
        let mut sorted_keys = None;
        for threads in 1..=4 {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let mut set = unsorted.clone();
            assert!(pool.install(|| set.sort_if_disordered()), "{threads} threads: a shuffled list is sorted");
            let keys: Vec<_> = set.entries().iter().map(PairEntry::key).collect();
            assert!(keys.is_sorted(), "{threads} threads");
            assert_eq!(sorted_keys.get_or_insert_with(|| keys.clone()), &keys, "{threads} threads");
            assert!(
                set.entries().iter().all(|e| set.get(e.b(), e.a()).is_some_and(|found| found.payload == e.a() ^ e.b()))
            );
        }
    }

    #[test]
    fn a_loaded_list_counts_its_descents_before_deciding_to_sort() {
        let mut set = PairSet::<u8>::default();
        for (a, b) in [(5, 6), (1, 2), (3, 4), (0, 9)] {
            set.insert(a, b);
        }
        let bytes = postcard::to_allocvec(&set).unwrap();
        let mut loaded: PairSet<u8> = postcard::from_bytes(&bytes).unwrap();
        assert_eq!(loaded.descents, None);
        assert!(loaded.sort_if_disordered());
        let keys: Vec<_> = loaded.entries().iter().map(PairEntry::key).collect();
        assert_eq!(keys, [(0, 9), (1, 2), (3, 4), (5, 6)]);
        assert!(loaded.get(9, 0).is_some() && loaded.get(4, 3).is_some());
        assert!(!loaded.sort_if_disordered());
    }

    #[test]
    fn removing_a_body_hands_back_all_its_pairs() {
        let mut set = PairSet::<u8>::default();
        for (a, b) in [(0, 1), (1, 2), (2, 3), (1, 3)] {
            set.insert(a, b);
        }
        let mut ended = Vec::new();
        assert_eq!(set.remove_body(1, &mut ended), 3);
        let mut keys: Vec<_> = ended.iter().map(|e| (e.a(), e.b())).collect();
        keys.sort_unstable();
        assert_eq!(keys, [(0, 1), (1, 2), (1, 3)]);
        assert_eq!(set.entries().len(), 1);
        assert!(set.get(2, 3).is_some());
    }
}
