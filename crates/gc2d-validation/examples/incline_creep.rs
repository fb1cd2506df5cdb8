//! Draws docs/figures/incline_creep.svg: a 10 mm square on a plane 0.5° below its friction angle (μ = 0.5,
//! γ = 0.5, E = 1e7 N/m, ρ = 5000 kg/m², Δt = 9.3 µs, the automatic Δt of `scenes/incline.ron`), released at rest,
//! under the thesis law and the Winkler formulation: how far it has moved down the slope over 2 s
//! (docs/model.md, "Rocking of flat contacts").
//!
//! `cargo run --release -p gc2d-validation --example incline_creep -- docs/figures/incline_creep.svg`

use gc2d_contact::{AreaFormulation, ContactLaw, CundallStrack, NormalDamping, NormalElastic};
use gc2d_engine::schedules::GravitySchedule;
use gc2d_engine::{Integrator, InteractionTable, MassModel, SafetyLimits, World, WorldConfig};
use gc2d_geometry::{DVec2, Pose, rectangle};
use plotters::prelude::*;
use std::path::PathBuf;

const MU: f64 = 0.5;
const SIDE: f64 = 0.01;
const DT: f64 = 9.3e-6;
const END: f64 = 2.0;

/// The downhill displacement of the block, mm, every millisecond.
fn creep(formulation: AreaFormulation) -> Result<Vec<(f64, f64)>, String> {
    let law = ContactLaw {
        elastic: NormalElastic { formulation, ..NormalElastic::thesis(1e7) },
        damping: Some(NormalDamping { gamma: 0.5 }),
        friction: Some(CundallStrack { mu: MU }),
        cohesion: None,
    };
    let config = WorldConfig {
        time_step: DT,
        integrator: Integrator::default(),
        interactions: InteractionTable::uniform(law),
        mass_model: MassModel::PerUnitThickness,
        gravity: GravitySchedule::constant(9.81),
        heating: None,
        safety: SafetyLimits::default(),
        domain: None,
        seed: 1,
    };
    let mut world = World::new(config).map_err(|e| e.to_string())?;
    let slope = MU.atan() - 0.5f64.to_radians();
    let (uphill, normal) = (DVec2::from_angle(slope), DVec2::from_angle(slope).perp());
    let plane = rectangle(1.0, 0.02).map_err(|e| e.to_string())?;
    world.add_wall(&plane, Pose::new(-0.01 * normal, slope), DVec2::ZERO, Default::default());
    let block = rectangle(SIDE, SIDE).map_err(|e| e.to_string())?;
    let pose = Pose::new((0.5 * SIDE + 2e-6) * normal, slope);
    let id = world.add_particle(&block, pose, 5000.0, DVec2::ZERO, 0.0).map_err(|e| e.to_string())?;
    let start = world.bodies().pose[id.index()].position;
    let mut points = Vec::new();
    for k in 1..=(END * 1000.0) as usize {
        world.run_until(k as f64 * 1e-3).map_err(|e| e.to_string())?;
        let moved = (start - world.bodies().pose[id.index()].position).dot(uphill);
        points.push((world.time(), 1e3 * moved));
    }
    Ok(points)
}

fn draw(path: &PathBuf, thesis: &[(f64, f64)], winkler: &[(f64, f64)]) -> Result<(), Box<dyn std::error::Error>> {
    let top = thesis.iter().chain(winkler).map(|p| p.1).fold(0.0, f64::max) * 1.05;
    let root = SVGBackend::new(path, (800, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption("10 mm square, 0.5° below arctan μ = 0.5: distance moved down the slope", ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(65)
        .build_cartesian_2d(0.0..END, 0.0..top)?;
    chart.configure_mesh().x_desc("time (s)").y_desc("moved downhill (mm)").draw()?;
    for (label, points, color) in
        [("thesis law (force at the chord midpoint)", thesis, RED), ("Winkler", winkler, BLUE)]
    {
        let legend = move |(x, y): (i32, i32)| PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2));
        chart.draw_series(LineSeries::new(points.to_vec(), color.stroke_width(2)))?.label(label).legend(legend);
    }
    chart.configure_series_labels().position(SeriesLabelPosition::UpperLeft).border_style(BLACK).draw()?;
    root.present()?;
    Ok(())
}

fn main() {
    let path = std::env::args().nth(1).map_or_else(|| PathBuf::from("incline_creep.svg"), PathBuf::from);
    let runs = creep(AreaFormulation::Thesis).and_then(|t| Ok((t, creep(AreaFormulation::Winkler)?)));
    let result = runs.map_err(Into::into).and_then(|(thesis, winkler)| {
        println!(
            "after {END} s: thesis law {:.3} mm, Winkler {:.4} mm",
            thesis.last().map_or(f64::NAN, |p| p.1),
            winkler.last().map_or(f64::NAN, |p| p.1)
        );
        draw(&path, &thesis, &winkler)
    });
    if let Err(error) = result {
        eprintln!("incline_creep: {error}");
        std::process::exit(1);
    }
}
