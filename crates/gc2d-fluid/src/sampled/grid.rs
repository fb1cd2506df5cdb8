//! A uniform bucket grid over points or boxes: the spatial index behind Shepard's nearest nodes and the mesh's
//! inside test. Built once at load, queried without allocating.
//!
//! Why not a k-d tree crate: `kiddo` (the well-kept one) needs Rust 1.89 from version 6 on, above the workspace's
//! 1.85, and its k-nearest queries return a `Vec` per call; nodes of a CFD mesh are spread evenly enough that a
//! grid with about two nodes per bucket answers a 4-nearest query from a handful of buckets.

use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// The largest neighbour count a Shepard query may ask for (the query keeps its candidates on the stack).
pub const MAX_NEIGHBOURS: usize = 64;

/// Buckets of item indices on a uniform grid of square cells.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct BucketGrid {
    origin: DVec2,
    size: f64,
    nx: usize,
    ny: usize,
    /// Where bucket `b`'s items start in `items` (one more entry than buckets).
    start: Vec<u32>,
    items: Vec<u32>,
}

impl BucketGrid {
    /// A grid over `boxes` (min, max corners), with about `per_bucket` boxes per bucket where they are spread
    /// evenly; each box is entered in every bucket it touches.
    pub fn new(boxes: &[(DVec2, DVec2)], per_bucket: f64) -> BucketGrid {
        let (lo, hi) = boxes.iter().fold((DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)), |acc, b| {
            (acc.0.min(b.0), acc.1.max(b.1))
        });
        let (lo, hi) = if boxes.is_empty() { (DVec2::ZERO, DVec2::ONE) } else { (lo, hi) };
        let extent = hi - lo;
        let longest = extent.max_element();
        let buckets = (boxes.len() as f64 / per_bucket).max(1.0);
        let size = if longest > 0.0 {
            // Square buckets; a flat cloud (all on a line) gets buckets along its length.
            (extent.x * extent.y / buckets).sqrt().max(longest / buckets)
        } else {
            1.0
        };
        let cap = (4.0 * buckets).ceil() + 1.0;
        let nx = ((extent.x / size).floor() + 1.0).min(cap) as usize;
        let ny = ((extent.y / size).floor() + 1.0).min(cap) as usize;
        let mut grid = BucketGrid { origin: lo, size, nx, ny, start: Vec::new(), items: Vec::new() };
        let ranges: Vec<[usize; 4]> = boxes
            .iter()
            .map(|(lo, hi)| {
                let (i0, j0) = grid.clamped_cell(*lo);
                let (i1, j1) = grid.clamped_cell(*hi);
                [i0, j0, i1, j1]
            })
            .collect();
        let mut start = vec![0u32; nx * ny + 1];
        for &[i0, j0, i1, j1] in &ranges {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    start[i + nx * j + 1] += 1;
                }
            }
        }
        for b in 0..nx * ny {
            start[b + 1] += start[b];
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; start[nx * ny] as usize];
        for (index, &[i0, j0, i1, j1]) in ranges.iter().enumerate() {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let b = i + nx * j;
                    items[fill[b] as usize] = index as u32;
                    fill[b] += 1;
                }
            }
        }
        grid.start = start;
        grid.items = items;
        grid
    }

    /// The bucket holding `p`, clamped into the grid.
    pub fn clamped_cell(&self, p: DVec2) -> (usize, usize) {
        let c = (p - self.origin) / self.size;
        let clamp = |v: f64, n: usize| if v >= 0.0 { (v as usize).min(n - 1) } else { 0 };
        (clamp(c.x, self.nx), clamp(c.y, self.ny))
    }

    /// The items bucket by bucket (for points, each once): an order that keeps neighbours close in memory.
    pub fn items(&self) -> &[u32] {
        &self.items
    }

    /// The items of bucket (i, j).
    pub fn bucket(&self, i: usize, j: usize) -> &[u32] {
        let b = i + self.nx * j;
        &self.items[self.start[b] as usize..self.start[b + 1] as usize]
    }

    /// The `k` points of `points` nearest to `q` (the grid built over them), nearest first, ties by lower index.
    pub fn nearest(&self, points: &[DVec2], q: DVec2, k: usize) -> Nearest {
        let mut best = Nearest {
            len: 0,
            k: k.min(points.len()).min(MAX_NEIGHBOURS),
            d2: [0.0; MAX_NEIGHBOURS],
            index: [0; MAX_NEIGHBOURS],
        };
        if best.k == 0 {
            return best;
        }
        let (cx, cy) = self.clamped_cell(q);
        let (cx, cy) = (cx as isize, cy as isize);
        let (nx, ny) = (self.nx as isize, self.ny as isize);
        let mut r = 0isize;
        loop {
            let mut visit = |i: isize, j: isize| {
                if (0..nx).contains(&i) && (0..ny).contains(&j) {
                    for &p in self.bucket(i as usize, j as usize) {
                        best.offer((points[p as usize] - q).length_squared(), p);
                    }
                }
            };
            if r == 0 {
                visit(cx, cy);
            } else {
                for i in cx - r..=cx + r {
                    visit(i, cy - r);
                    visit(i, cy + r);
                }
                for j in cy - r + 1..cy + r {
                    visit(cx - r, j);
                    visit(cx + r, j);
                }
            }
            // Every point not visited yet lies beyond one of the visited square's sides that is still inside the
            // grid; stop when the nearest such side is farther than the k-th candidate.
            let lo = self.origin + DVec2::new((cx - r) as f64, (cy - r) as f64) * self.size;
            let hi = self.origin + DVec2::new((cx + r + 1) as f64, (cy + r + 1) as f64) * self.size;
            let sides = [
                (cx - r > 0, q.x - lo.x),
                (cx + r < nx - 1, hi.x - q.x),
                (cy - r > 0, q.y - lo.y),
                (cy + r < ny - 1, hi.y - q.y),
            ];
            let mut bound = f64::INFINITY;
            let mut open = false;
            for (is_open, d) in sides {
                if is_open {
                    open = true;
                    bound = bound.min(d.max(0.0));
                }
            }
            if !open || (best.len == best.k && bound * bound > best.d2[best.len - 1]) {
                return best;
            }
            r += 1;
        }
    }
}

/// The nearest points a query found: `len` of them, nearest first.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Nearest {
    /// How many were found.
    pub len: usize,
    k: usize,
    /// Their squared distances, m².
    pub d2: [f64; MAX_NEIGHBOURS],
    /// Their indices.
    pub index: [u32; MAX_NEIGHBOURS],
}

impl Nearest {
    /// Keeps the point if it is among the k nearest so far, ordered by (distance, index).
    fn offer(&mut self, d2: f64, index: u32) {
        let worse = |a: (f64, u32), b: (f64, u32)| a.0 > b.0 || (a.0 == b.0 && a.1 > b.1);
        if self.len == self.k {
            if !worse((self.d2[self.len - 1], self.index[self.len - 1]), (d2, index)) {
                return;
            }
            self.len -= 1;
        }
        let mut at = self.len;
        while at > 0 && worse((self.d2[at - 1], self.index[at - 1]), (d2, index)) {
            self.d2[at] = self.d2[at - 1];
            self.index[at] = self.index[at - 1];
            at -= 1;
        }
        self.d2[at] = d2;
        self.index[at] = index;
        self.len += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The k nearest by brute force, (distance, index) ordered.
    fn brute(points: &[DVec2], q: DVec2, k: usize) -> Vec<u32> {
        let mut all: Vec<(f64, u32)> =
            points.iter().enumerate().map(|(i, p)| ((*p - q).length_squared(), i as u32)).collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        all.iter().take(k).map(|a| a.1).collect()
    }

    #[test]
    fn nearest_matches_brute_force_inside_and_far_outside() {
        // A deterministic scatter with clusters, a lattice part (ties) and queries in and far out of the cloud.
        let mut points = Vec::new();
        let mut s = 12345u64;
        let mut rnd = || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..300 {
            points.push(DVec2::new(rnd() * 3.0, rnd()));
        }
        for i in 0..10 {
            for j in 0..10 {
                points.push(DVec2::new(i as f64 * 0.1, 2.0 + j as f64 * 0.1));
            }
        }
        let boxes: Vec<_> = points.iter().map(|&p| (p, p)).collect();
        let grid = BucketGrid::new(&boxes, 2.0);
        let mut queries =
            vec![DVec2::new(0.45, 2.45), DVec2::new(0.5, 2.5), DVec2::new(-40.0, 7.0), DVec2::new(3.1, -0.2)];
        for _ in 0..200 {
            queries.push(DVec2::new(rnd() * 4.0 - 0.5, rnd() * 4.0 - 0.5));
        }
        for q in queries {
            for k in [1, 4, 9] {
                let n = grid.nearest(&points, q, k);
                assert_eq!(n.index[..n.len].to_vec(), brute(&points, q, k), "q = {q}, k = {k}");
            }
        }
    }

    #[test]
    fn flat_and_single_point_clouds() {
        let line: Vec<DVec2> = (0..50).map(|i| DVec2::new(i as f64, 0.0)).collect();
        let grid = BucketGrid::new(&line.iter().map(|&p| (p, p)).collect::<Vec<_>>(), 2.0);
        let n = grid.nearest(&line, DVec2::new(20.2, 5.0), 2);
        assert_eq!(&n.index[..2], &[20, 21]);
        let one = [DVec2::new(1.0, 1.0)];
        let grid = BucketGrid::new(&[(one[0], one[0])], 2.0);
        let n = grid.nearest(&one, DVec2::new(-3.0, 4.0), 4);
        assert_eq!((n.len, n.index[0]), (1, 0));
    }
}
