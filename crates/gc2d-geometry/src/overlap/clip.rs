//! Sutherland–Hodgman clipping of polygon `a` by the edges of polygon `b`, remembering for every edge of the result
//! which outline it lies on. The labels are what turn an intersection polygon into a contact chord: the chord ends
//! are the points where the result's boundary switches from `b`'s outline to `a`'s and back (reference §2.4, §4.4).
//!
//! Tie rule: a point exactly on one of `b`'s edge lines counts as inside `b` (closed half-planes). An edge of `a`
//! that runs along an edge of `b` in the same direction is labelled *shared*; one that runs along it in the opposite
//! direction can only touch `b` from outside, so the overlap is empty.

use super::facing::Facing;
use crate::{DVec2, cross, cyclic_next, cyclic_previous};

/// Which outline an edge of the overlap polygon lies on.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(crate) enum Label {
    /// A piece of an edge of `a`, strictly inside `b`'s edge lines.
    A,
    /// Cut along an edge of `b`.
    B,
    /// A piece of an edge of `a` lying on an edge of `b` (collinear, same direction).
    Shared,
}

/// One vertex of a [`Ring`] with the label of the edge leaving it.
#[derive(Clone, Copy, PartialEq, Debug)]
pub(crate) struct RingVertex {
    pub(crate) point: DVec2,
    /// Label of the edge from this vertex to the next.
    pub(crate) edge: Label,
    /// The vertex lies exactly on one of `b`'s edge lines (it was kept by the tie rule).
    pub(crate) tied: bool,
}

/// A convex polygon under construction, in a fixed stack buffer of `CAP` vertices. Edge `k` runs from vertex `k` to
/// vertex `(k + 1) % len`.
pub(crate) struct Ring<const CAP: usize> {
    vertices: [RingVertex; CAP],
    len: usize,
}

impl<const CAP: usize> Ring<CAP> {
    pub(crate) fn new() -> Self {
        let unused = RingVertex { point: DVec2::ZERO, edge: Label::A, tied: false };
        Self { vertices: [unused; CAP], len: 0 }
    }

    pub(crate) fn vertices(&self) -> &[RingVertex] {
        &self.vertices[..self.len]
    }

    fn clear(&mut self) {
        self.len = 0;
    }

    /// Replaces the ring by the polygon `points` (distinct vertices), all edges labelled [`Label::A`].
    fn fill_from(&mut self, points: &[DVec2]) {
        for (slot, &point) in self.vertices.iter_mut().zip(points) {
            *slot = RingVertex { point, edge: Label::A, tied: false };
        }
        self.len = points.len().min(CAP);
    }

    /// Appends a vertex whose outgoing edge has label `edge`. A vertex equal to the previous one replaces it (the
    /// zero-length edge between them vanishes); a full buffer drops the vertex, which cannot happen for convex input
    /// because every clip adds at most one vertex.
    fn push(&mut self, point: DVec2, edge: Label, tied: bool) {
        if let Some(last) = self.vertices[..self.len].last_mut()
            && last.point == point
        {
            last.edge = edge;
            last.tied |= tied;
        } else if let Some(slot) = self.vertices.get_mut(self.len) {
            *slot = RingVertex { point, edge, tied };
            self.len += 1;
        }
    }

    /// Closes the ring: a last vertex equal to the first one is merged into it.
    fn close(&mut self) {
        if self.len >= 2 && self.vertices[self.len - 1].point == self.vertices[0].point {
            self.len -= 1;
            self.vertices[0].tied |= self.vertices[self.len].tied;
        }
    }

    /// Twice the signed area, summed relative to the first vertex so that far-from-origin coordinates lose no
    /// precision (a 1e-8 m overlap at 0.1 m from the origin keeps ~8 significant digits more than the plain sum).
    pub(crate) fn twice_area(&self) -> f64 {
        let vertices = self.vertices();
        let Some(first) = vertices.first() else { return 0.0 };
        let origin = first.point;
        let mut sum = 0.0;
        for pair in vertices[1..].windows(2) {
            sum += cross(pair[0].point - origin, pair[1].point - origin);
        }
        sum
    }
}

/// Clips the counter-clockwise convex polygon `a` by the edges of the counter-clockwise convex polygon `b` that
/// `facing` keeps (the others could change nothing but round-off).
///
/// Returns the ring holding `a ∩ b` (one of `first` or `second`, which are scratch buffers), or `None` when the
/// interiors are disjoint (some edge line of `b` has all of the remaining polygon on its closed outer side).
///
/// The edges are taken in cyclic order starting next to `b`'s vertex farthest towards `a`. In a shallow contact the
/// first one or two clips leave a sliver of three or four vertices, so the remaining edges cost a few side tests
/// each.
pub(crate) fn clip<'r, const CAP: usize>(
    a: &[DVec2],
    b: &[DVec2],
    facing: &Facing,
    first: &'r mut Ring<CAP>,
    second: &'r mut Ring<CAP>,
) -> Option<&'r Ring<CAP>> {
    let m = b.len();
    first.fill_from(a);
    let (mut current, mut spare) = (first, second);
    let mut j = cyclic_previous(facing.top, m);
    for _ in 0..m {
        let next = cyclic_next(j, m);
        if !facing.skips_edge_of_b(b[j], b[next]) {
            match clip_by_line(current, spare, b[j], b[next] - b[j]) {
                LineClip::Empty => return None,
                LineClip::Unchanged => {}
                LineClip::Clipped => std::mem::swap(&mut current, &mut spare),
            }
        }
        j = next;
    }
    Some(current)
}

enum LineClip {
    Empty,
    Unchanged,
    Clipped,
}

/// Labels as shared, in place, the `a` edges of `ring` lying on the line, and marks the vertices on it as tied.
/// Only called when no vertex is strictly outside the line, so such edges run in the line's direction.
fn mark_shared_edges<const CAP: usize>(ring: &mut Ring<CAP>, origin: DVec2, direction: DVec2) {
    let n = ring.len;
    let on_line = |p: DVec2| cross(direction, p - origin) == 0.0;
    for k in 0..n {
        let next = ring.vertices[cyclic_next(k, n)].point;
        let vertex = &mut ring.vertices[k];
        if on_line(vertex.point) {
            vertex.tied = true;
            if on_line(next) && vertex.edge == Label::A {
                vertex.edge = Label::Shared;
            }
        }
    }
}

/// One Sutherland–Hodgman step: keeps the part of `src` on the closed inner (left) side of the directed line.
/// A quick first sweep settles the common cases (nothing inside: empty; nothing outside: unchanged); the clip
/// itself recomputes the sides as it streams, which is cheaper than storing them.
fn clip_by_line<const CAP: usize>(
    src: &mut Ring<CAP>,
    dst: &mut Ring<CAP>,
    origin: DVec2,
    direction: DVec2,
) -> LineClip {
    let side = |p: DVec2| cross(direction, p - origin);
    // Plain comparisons (cheaper than f64::min/max) skip NaN sides, so an all-NaN polygon counts as empty.
    let (mut lowest, mut highest) = (f64::INFINITY, f64::NEG_INFINITY);
    for vertex in src.vertices() {
        let s = side(vertex.point);
        lowest = if s < lowest { s } else { lowest };
        highest = if s > highest { s } else { highest };
    }
    if highest <= 0.0 {
        return LineClip::Empty;
    }
    if lowest >= 0.0 {
        if lowest == 0.0 {
            mark_shared_edges(src, origin, direction);
        }
        return LineClip::Unchanged;
    }
    dst.clear();
    let vertices = src.vertices();
    // Walk the edges previous → current, starting with the closing edge (last → first vertex).
    let Some(&last) = vertices.last() else { return LineClip::Empty };
    let (mut p, mut label, mut tied) = (last.point, last.edge, last.tied);
    let mut sp = side(p);
    for vertex in vertices {
        let q = vertex.point;
        let sq = side(q);
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
        (p, label, tied, sp) = (q, vertex.edge, vertex.tied, sq);
    }
    dst.close();
    LineClip::Clipped
}
