//! The test areas of the density and stress maps are squares whose side is the report's `grid_cell` (QA docs 13).

mod common;

use approx::assert_relative_eq;
use common::{DENSITY, G, block_of_squares, contact, rectangle, wall};
use gc2d_analysis::density::MAX_GRID_CELLS_PER_AXIS;
use gc2d_analysis::{AnalyzeOptions, BodyRef, Grid, Rect, SceneKind, analyze_snapshot};
use gc2d_geometry::DVec2;

fn assert_square_cells(grid: &Grid, region: Rect) {
    for (_, _, cell) in grid.cells() {
        assert_relative_eq!(cell.size().x, grid.side, max_relative = 1e-9);
        assert_relative_eq!(cell.size().y, grid.side, max_relative = 1e-9);
    }
    // The cells span the region's width exactly and reach past its top by less than one cell.
    assert_relative_eq!(grid.region.min.x, region.min.x, epsilon = 1e-12);
    assert_relative_eq!(grid.region.max.x, region.max.x, epsilon = 1e-9 * region.size().x);
    assert_relative_eq!(grid.region.min.y, region.min.y, epsilon = 1e-12);
    assert!(grid.region.max.y >= region.max.y * (1.0 - 1e-12), "{grid:?}");
    assert!(grid.region.max.y < region.max.y + grid.side, "{grid:?}");
}

#[test]
fn a_flat_region_gets_square_cells_of_the_side_reported() {
    // The bundled pile's region: 0.1424 m × 0.0223 m, with its automatic cell of 0.04065 m gave 4 × 1 areas of
    // 0.0356 × 0.0223 m, reported as 0.04065.
    let region = Rect::new(DVec2::ZERO, DVec2::new(0.14236, 0.02227));
    let grid = Grid::with_cell_size(region, 0.04065);
    assert_eq!((grid.nx, grid.ny, grid.capped), (4, 1, false));
    assert_relative_eq!(grid.side, 0.14236 / 4.0, max_relative = 1e-12);
    assert_square_cells(&grid, region);
    let grid = Grid::with_cell_size(region, 0.01);
    assert_eq!((grid.nx, grid.ny, grid.capped), (14, 3, false));
    assert_square_cells(&grid, region);
}

#[test]
fn a_side_too_small_is_capped_and_the_cells_stay_square() {
    let wide = Rect::new(DVec2::new(-0.07, 0.0), DVec2::new(0.07236, 0.02227));
    let grid = Grid::with_cell_size(wide, 1e-6);
    assert!(grid.capped);
    assert_eq!((grid.nx, grid.ny), (MAX_GRID_CELLS_PER_AXIS, 157));
    assert_relative_eq!(grid.side, 0.14236 / 1000.0, max_relative = 1e-12);
    assert_square_cells(&grid, wide);
    let tall = Rect::new(DVec2::ZERO, DVec2::new(0.0105, 1.0));
    let grid = Grid::with_cell_size(tall, 1e-6);
    assert!(grid.capped && grid.ny <= MAX_GRID_CELLS_PER_AXIS && grid.side >= 1e-3, "{grid:?}");
    assert_eq!(grid.nx, 10);
    assert_square_cells(&grid, tall);
    assert!(!Grid::with_cell_size(tall, 0.002).capped);
}

/// The values of column `name` of a CSV table.
fn column(table: &str, name: &str) -> Vec<f64> {
    let mut lines = table.lines();
    let index = lines.next().unwrap().split(',').position(|h| h == name).unwrap();
    lines.map(|line| line.split(',').nth(index).unwrap().parse().unwrap()).collect()
}

#[test]
fn the_reported_grid_cell_is_the_size_of_the_areas_in_both_maps() {
    // A block of 12 × 3 squares on a floor, each carrying the weight of those above it.
    let (nx, ny, d) = (12, 3, 0.002);
    let mut block = block_of_squares(nx, ny, d, 0.0);
    block.walls = vec![wall(0, rectangle(DVec2::new(-d, -d), DVec2::new((nx + 1) as f64 * d, 0.0)))];
    let weight = DENSITY * d * d * G;
    for i in 0..nx {
        let x = (i as f64 + 0.5) * d;
        let floor = DVec2::new(0.0, ny as f64 * weight);
        block.contacts.push(contact(BodyRef::Particle(i), BodyRef::Wall(0), floor, DVec2::new(x, 0.0)));
        for j in 1..ny {
            let above = DVec2::new(0.0, (ny - j) as f64 * weight);
            let point = DVec2::new(x, j as f64 * d);
            block.contacts.push(contact(
                BodyRef::Particle(j * nx + i),
                BodyRef::Particle((j - 1) * nx + i),
                above,
                point,
            ));
        }
        if i + 1 < nx {
            for j in 0..ny {
                let point = DVec2::new((i + 1) as f64 * d, (j as f64 + 0.5) * d);
                block.contacts.push(contact(
                    BodyRef::Particle(j * nx + i),
                    BodyRef::Particle(j * nx + i + 1),
                    DVec2::ZERO,
                    point,
                ));
            }
        }
    }
    let out = std::env::temp_dir().join(format!("gc2d-analysis-{}-square-grid", std::process::id()));
    // 2.5 d over a width of 12 d gives 5 columns of 2.4 d; the old grid made its 2 rows 1.5 d high.
    let options = AnalyzeOptions { scene: SceneKind::Pile, grid_cell: Some(2.5 * d), ..Default::default() };
    let report = analyze_snapshot(&block, &options, &out).expect("analysis");
    let pile = report.pile.expect("pile report");
    assert_eq!(pile.particles, nx * ny);
    assert_relative_eq!(pile.grid_cell, 2.4 * d, max_relative = 1e-12);
    assert_eq!((pile.grid_size, pile.grid_capped), ([5, 2], false));
    let density = std::fs::read_to_string(out.join("density_grid.csv")).unwrap();
    let (widths, heights) = (column(&density, "width"), column(&density, "height"));
    assert_eq!(widths.len(), 10);
    for size in widths.iter().chain(&heights) {
        assert_relative_eq!(*size, pile.grid_cell, max_relative = 1e-9);
    }
    // stress_grid.csv gives the centres: neighbours lie one grid_cell apart along both axes.
    let stress = std::fs::read_to_string(out.join("stress_grid.csv")).unwrap();
    for name in ["x", "y"] {
        let mut centres = column(&stress, name);
        centres.sort_by(f64::total_cmp);
        centres.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        assert!(centres.len() >= 2, "{name}: {centres:?}");
        for pair in centres.windows(2) {
            assert_relative_eq!(pair[1] - pair[0], pile.grid_cell, max_relative = 1e-9);
        }
    }
    let _ = std::fs::remove_dir_all(&out);
}
