//! Shepard's inverse-distance weighting over the nearest nodes (feedpipe.md §4.4, Eqs. 3.69–3.71).

use super::domain::Domain;
use super::grid::BucketGrid;
use gc2d_geometry::DVec2;
use serde::{Deserialize, Serialize};

/// Nodes with their velocities, a grid over them and the mesh's domain.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct ShepardCloud {
    nodes: Vec<DVec2>,
    velocities: Vec<DVec2>,
    grid: BucketGrid,
    pub(crate) domain: Domain,
    power: f64,
    neighbours: usize,
}

impl ShepardCloud {
    /// A cloud weighting the `neighbours` nearest nodes by h^−power. The nodes are stored bucket by bucket, so a
    /// query reads neighbouring memory (in the order given, a query's few nodes lay scattered over the whole
    /// array, and the cache misses cost more than the arithmetic).
    pub fn new(nodes: Vec<DVec2>, velocities: Vec<DVec2>, domain: Domain, power: f64, neighbours: usize) -> Self {
        let boxes = |nodes: &[DVec2]| nodes.iter().map(|&p| (p, p)).collect::<Vec<_>>();
        let order = BucketGrid::new(&boxes(&nodes), 2.0).items().to_vec();
        let nodes: Vec<DVec2> = order.iter().map(|&i| nodes[i as usize]).collect();
        let velocities = order.iter().map(|&i| velocities[i as usize]).collect();
        let grid = BucketGrid::new(&boxes(&nodes), 2.0);
        ShepardCloud { nodes, velocities, grid, domain, power, neighbours }
    }

    /// Σ wᵢ vᵢ over the nearest nodes with wᵢ = hᵢ^−p / Σ hⱼ^−p; a node's own value at the node.
    ///
    /// Written as v₀ + Σ wᵢ (vᵢ − v₀) with v₀ the nearest node's velocity and the weights scaled by the nearest
    /// distance ((h₀/hᵢ)^p, at most 1): a constant field comes out exactly, and no weight overflows however close
    /// the point is to a node.
    pub fn interpolate(&self, p: DVec2) -> DVec2 {
        let near = self.grid.nearest(&self.nodes, p, self.neighbours);
        let v0 = self.velocities[near.index[0] as usize];
        let d0 = near.d2[0];
        if d0 == 0.0 {
            return v0;
        }
        let mut weights = 0.0;
        let mut sum = DVec2::ZERO;
        for n in 0..near.len {
            let ratio = d0 / near.d2[n];
            let w = if self.power == 2.0 { ratio } else { ratio.powf(0.5 * self.power) };
            weights += w;
            sum += w * (self.velocities[near.index[n] as usize] - v0);
        }
        v0 + sum / weights
    }

    /// The velocity of the node nearest to `p`.
    pub fn nearest_node(&self, p: DVec2) -> DVec2 {
        self.velocities[self.grid.nearest(&self.nodes, p, 1).index[0] as usize]
    }
}
