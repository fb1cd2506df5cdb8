//! Sutherland–Hodgman clipping of polygon `a` by the edges of polygon `b`, remembering for every edge of the result
//! which outline it lies on. The labels are what turn an intersection polygon into a contact chord: the chord ends
//! are the points where the result's boundary switches from `b`'s outline to `a`'s and back (reference §2.4, §4.4).
//!
//! Tie rule: a point exactly on one of `b`'s edge lines counts as inside `b` (closed half-planes). An edge of `a`
//! that runs along an edge of `b` in the same direction is labelled *shared*; one that runs along it in the opposite
//! direction can only touch `b` from outside, so the overlap is empty.

use crate::{DVec2, cross};

/// A convex polygon under construction, in a fixed stack buffer of `CAP ≤ 128` vertices (so labels fit in `u128`).
///
/// Edge `k` runs from `points[k]` to `points[(k + 1) % len]`. Its label is *b* if bit `k` of `on_b` is set (it was
/// cut along one of `b`'s edges), *shared* if bit `k` of `shared` is set (a piece of an edge of `a` lying on an edge
/// of `b`), and *a* otherwise (a piece of an edge of `a` strictly inside `b`'s edge line).
pub(crate) struct Ring<const CAP: usize> {
    points: [DVec2; CAP],
    on_b: u128,
    shared: u128,
    /// Bit `k`: vertex `k` lies exactly on one of `b`'s edge lines (it was kept by the tie rule).
    tied: u128,
    len: usize,
}

/// The label of one edge of a [`Ring`].
#[derive(Clone, Copy, PartialEq, Eq)]
enum Label {
    A,
    B,
    Shared,
}

impl<const CAP: usize> Ring<CAP> {
    const CAPACITY_FITS_LABELS: () = assert!(CAP <= 128, "ring labels are stored in u128 bit masks");

    pub(crate) fn new() -> Self {
        let () = Self::CAPACITY_FITS_LABELS;
        Self { points: [DVec2::ZERO; CAP], on_b: 0, shared: 0, tied: 0, len: 0 }
    }

    pub(crate) fn points(&self) -> &[DVec2] {
        &self.points[..self.len]
    }

    /// Bit mask with one bit per vertex (or edge) of the ring.
    pub(crate) fn all_edges(&self) -> u128 {
        if self.len >= 128 { u128::MAX } else { (1u128 << self.len) - 1 }
    }

    /// Edges cut along `b`'s outline.
    pub(crate) fn b_edges(&self) -> u128 {
        self.on_b
    }

    /// Pieces of `a`'s edges lying on `b`'s edges (collinear, same direction).
    pub(crate) fn shared_edges(&self) -> u128 {
        self.shared
    }

    /// Vertices lying exactly on one of `b`'s edge lines.
    pub(crate) fn tied_vertices(&self) -> u128 {
        self.tied
    }

    fn label(&self, k: usize) -> Label {
        if self.on_b >> k & 1 == 1 {
            Label::B
        } else if self.shared >> k & 1 == 1 {
            Label::Shared
        } else {
            Label::A
        }
    }

    fn clear(&mut self) {
        self.on_b = 0;
        self.shared = 0;
        self.tied = 0;
        self.len = 0;
    }

    /// Appends a vertex whose outgoing edge has `label`. A vertex equal to the previous one replaces it (the
    /// zero-length edge between them vanishes); a full buffer drops the vertex, which cannot happen for convex input
    /// because every clip adds at most one vertex.
    fn push(&mut self, point: DVec2, label: Label, tied: bool) {
        let k = if self.len > 0 && self.points[self.len - 1] == point {
            self.len - 1
        } else if self.len < CAP {
            self.len += 1;
            self.len - 1
        } else {
            return;
        };
        self.points[k] = point;
        let bit = 1u128 << k;
        let was_tied = self.tied & bit != 0;
        self.on_b &= !bit;
        self.shared &= !bit;
        self.tied &= !bit;
        match label {
            Label::A => {}
            Label::B => self.on_b |= bit,
            Label::Shared => self.shared |= bit,
        }
        if tied || was_tied {
            self.tied |= bit;
        }
    }

    /// Closes the ring: a last vertex equal to the first one is merged into it.
    fn close(&mut self) {
        if self.len >= 2 && self.points[self.len - 1] == self.points[0] {
            let last = 1u128 << (self.len - 1);
            if self.tied & last != 0 {
                self.tied |= 1;
            }
            self.on_b &= !last;
            self.shared &= !last;
            self.tied &= !last;
            self.len -= 1;
        }
    }

    /// Twice the signed area, summed relative to the first vertex so that far-from-origin coordinates lose no
    /// precision (a 1e-8 m overlap at 0.1 m from the origin keeps ~8 significant digits more than the plain sum).
    pub(crate) fn twice_area(&self) -> f64 {
        let pts = self.points();
        let Some(&origin) = pts.first() else { return 0.0 };
        let mut sum = 0.0;
        for k in 1..pts.len().saturating_sub(1) {
            sum += cross(pts[k] - origin, pts[k + 1] - origin);
        }
        sum
    }
}

/// Clips the counter-clockwise convex polygon `a` by every edge of the counter-clockwise convex polygon `b`.
///
/// Returns the ring holding `a ∩ b` (one of `first` or `second`, which are scratch buffers), or `None` when the
/// interiors are disjoint (some edge line of `b` has all of the remaining polygon on its closed outer side).
pub(crate) fn clip<'r, const CAP: usize>(
    a: &[DVec2],
    b: &[DVec2],
    first: &'r mut Ring<CAP>,
    second: &'r mut Ring<CAP>,
) -> Option<&'r Ring<CAP>> {
    let m = b.len();
    let mut cutting: u64 = 0;
    first.clear();
    for &p in a {
        first.push(p, Label::A, false);
    }
    first.close();
    // Pre-pass over the original vertices: rejects separated pairs cheaply and skips the edges of b whose line does
    // not cut a (in a shallow contact, most of them).
    for j in 0..m {
        let (origin, direction) = (b[j], b[(j + 1) % m] - b[j]);
        let (mut any_inside, mut any_outside, mut any_on) = (false, false, false);
        for &p in a {
            let side = cross(direction, p - origin);
            any_inside |= side > 0.0;
            any_outside |= side < 0.0;
            any_on |= side == 0.0;
        }
        if !any_inside {
            return None;
        }
        if any_outside {
            cutting |= 1 << j;
        } else if any_on {
            mark_shared_edges(first, origin, direction);
        }
    }
    let (mut current, mut spare) = (first, second);
    while cutting != 0 {
        let j = cutting.trailing_zeros() as usize;
        cutting &= cutting - 1;
        let (origin, direction) = (b[j], b[(j + 1) % m] - b[j]);
        match clip_by_line(current, spare, origin, direction) {
            LineClip::Empty => return None,
            LineClip::Unchanged => {}
            LineClip::Clipped => std::mem::swap(&mut current, &mut spare),
        }
    }
    Some(current)
}

enum LineClip {
    Empty,
    Unchanged,
    Clipped,
}

/// Labels as shared, in place, the `a` edges of `ring` lying on the line, and marks their ends as tied. Only called
/// when no vertex is strictly outside the line, so such edges run in the line's direction.
fn mark_shared_edges<const CAP: usize>(ring: &mut Ring<CAP>, origin: DVec2, direction: DVec2) {
    let n = ring.len;
    for k in 0..n {
        let next = (k + 1) % n;
        let on_line = |p: DVec2| cross(direction, p - origin) == 0.0;
        if on_line(ring.points[k]) {
            ring.tied |= 1 << k;
            if on_line(ring.points[next]) && ring.label(k) == Label::A {
                ring.shared |= 1 << k;
            }
        }
    }
}

/// One Sutherland–Hodgman step: keeps the part of `src` on the closed inner (left) side of the directed line.
fn clip_by_line<const CAP: usize>(src: &mut Ring<CAP>, dst: &mut Ring<CAP>, origin: DVec2, direction: DVec2) -> LineClip {
    let n = src.len;
    let mut sides = [0.0; CAP];
    let (mut any_inside, mut any_outside) = (false, false);
    for (side, &p) in sides.iter_mut().zip(src.points()) {
        *side = cross(direction, p - origin);
        any_inside |= *side > 0.0;
        any_outside |= *side < 0.0;
    }
    if !any_inside {
        return LineClip::Empty;
    }
    if !any_outside {
        mark_shared_edges(src, origin, direction);
        return LineClip::Unchanged;
    }
    dst.clear();
    for k in 0..n {
        let next = (k + 1) % n;
        let (p, q) = (src.points[k], src.points[next]);
        let (sp, sq) = (sides[k], sides[next]);
        let label = src.label(k);
        let tied = src.tied >> k & 1 == 1;
        let crossing = || p + (q - p) * (sp / (sp - sq));
        if sp > 0.0 {
            dst.push(p, label, tied);
            if sq < 0.0 {
                dst.push(crossing(), Label::B, false);
            }
        } else if sp == 0.0 {
            let kept = if sq > 0.0 {
                label
            } else if sq == 0.0 {
                if label == Label::A { Label::Shared } else { label }
            } else {
                Label::B
            };
            dst.push(p, kept, true);
        } else if sq > 0.0 {
            dst.push(crossing(), label, false);
        }
    }
    dst.close();
    LineClip::Clipped
}
