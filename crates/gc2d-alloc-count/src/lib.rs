//! A counting global allocator for tests (preamble: the hot paths must not allocate).
//!
//! A test binary installs it with
//! `#[global_allocator] static GLOBAL: gc2d_alloc_count::CountingAllocator = gc2d_alloc_count::CountingAllocator;`
//! and compares a counter before and after the code under test. Every call is forwarded to the system allocator.
//! Two counters are kept: one per thread, which other tests running in parallel in the same binary cannot disturb,
//! and one for the whole process, which also counts allocations made by rayon's workers (a test using it must be the
//! only test of its binary that runs at that time).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The system allocator with allocation counters; see the crate documentation.
pub struct CountingAllocator;

thread_local! {
    static THREAD_ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

static PROCESS_ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

impl CountingAllocator {
    fn count() {
        THREAD_ALLOCATIONS.with(|count| count.set(count.get() + 1));
        PROCESS_ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// SAFETY: every call is forwarded unchanged to the system allocator; only the counters are added, and counting
// neither allocates nor touches the memory handed out.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        Self::count();
        // SAFETY: the caller's contract for `alloc` is passed on unchanged.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract for `dealloc` is passed on unchanged.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        Self::count();
        // SAFETY: the caller's contract for `realloc` is passed on unchanged.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

/// Allocations and reallocations made so far on the calling thread.
pub fn thread_allocations() -> usize {
    THREAD_ALLOCATIONS.with(Cell::get)
}

/// Allocations and reallocations made so far on every thread of the process.
pub fn process_allocations() -> usize {
    PROCESS_ALLOCATIONS.load(Ordering::Relaxed)
}
