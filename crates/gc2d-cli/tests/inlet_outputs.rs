//! Inlet and outlet counters in a run's outputs (issue 15 item 3): their columns in `timeseries.csv` balance the fed
//! particles on every row, a resumed series keeps them, and `summary.json` lists each inlet and outlet by name.

use gc2d_cli::outputs::{RunStatus, Summary, TIME_SERIES_COLUMNS, TimeSeriesWriter};
use gc2d_engine::World;
use gc2d_scene::Scene;

/// An inlet at the floor feeding 20 disks per second upward at 1 m/s, an outlet across the top at 0.2 m (reached in
/// 0.2 s) and an unnamed one beside it that nothing crosses.
fn world() -> World {
    let text = r#"Scene(
    run: (time_step_s: 1e-3, end_time_s: 1.0),
    gravity: Constant(0.0),
    materials: [(name: "glass", density_kg_m2: 1e4, youngs_modulus_n_m: 1e5)],
    inlets: [(name: "feed", from_m: (-0.05, 0.0), to_m: (0.05, 0.0), rate_per_s: 20, velocity_m_s: (0.0, 1.0),
              shape: (semi_axes_m: (0.01, 0.01), disk: true))],
    outlets: [(name: "top", from_m: (0.05, 0.2), to_m: (-0.05, 0.2)), (from_m: (1.0, 0.0), to_m: (1.0, 1.0))],
)"#;
    Scene::from_str(text, "feed.ron").unwrap().build().unwrap()
}

#[test]
fn the_counter_columns_balance_on_every_row_and_survive_a_resume() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("timeseries.csv");
    let mut world = world();
    let mut series = TimeSeriesWriter::create(&path).unwrap();
    series.append(&world).unwrap();
    for _ in 0..50 {
        for _ in 0..10 {
            world.step().unwrap();
        }
        series.append(&world).unwrap();
    }
    drop(series);
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let extra = ["inlet_feed_injected", "inlet_feed_postponed", "outlet_top_removed", "outlet_1_removed"];
    assert_eq!(header[TIME_SERIES_COLUMNS.len()..], [&extra[..], &["removed_by_domain"]].concat());
    let column = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let rows: Vec<Vec<f64>> = lines.map(|l| l.split(',').map(|v| v.parse().unwrap()).collect()).collect();
    assert_eq!(rows.len(), 51);
    for row in &rows {
        let removed = row[column("outlet_top_removed")] + row[column("outlet_1_removed")];
        assert_eq!(
            row[column("inlet_feed_injected")],
            row[column("particles")] + removed + row[column("removed_by_domain")]
        );
    }
    let last = rows.last().unwrap();
    // Due at steps 1, 51, …, 451 (10 by t = 0.5 s); those fed by step 251 have crossed y = 0.2 m by step 500.
    assert_eq!((last[column("inlet_feed_injected")], last[column("outlet_top_removed")]), (10.0, 6.0));

    // A resumed run keeps the header with its counter columns and the rows up to its time.
    let series = TimeSeriesWriter::continue_at(&path, 0.25, 5e-4, 0.01).unwrap();
    drop(series);
    let kept = std::fs::read_to_string(&path).unwrap();
    assert_eq!(kept.lines().next(), text.lines().next());
    assert_eq!(kept.lines().count(), 1 + 26);
    // Resumed where an interrupted run stopped between two rows: the last row it wrote there, off the rows'
    // cadence, is dropped, as the unsplit run has no row at that time.
    let last = kept.lines().last().unwrap().to_owned();
    let off_cadence = format!("0.253,{}", last.split_once(',').unwrap().1);
    std::fs::write(&path, format!("{kept}{off_cadence}\n")).unwrap();
    drop(TimeSeriesWriter::continue_at(&path, 0.253, 5e-4, 0.01).unwrap());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), kept);
}

#[test]
fn the_summary_lists_each_inlet_and_outlet_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let mut world = world();
    for _ in 0..500 {
        world.step().unwrap();
    }
    let chatter = gc2d_cli::chatter::ChatterWatch::default().summary();
    let summary = Summary::of(&world, std::path::Path::new("feed.ron"), RunStatus::Completed, chatter, 0.0);
    summary.write(&dir.path().join("summary.json")).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap()).unwrap();
    assert_eq!(json["particles_injected"], 10);
    assert_eq!(json["particles_removed_at_outlets"], 6);
    assert_eq!(json["injections_postponed"], 0);
    assert_eq!(json["inlets"][0]["name"], "feed");
    assert_eq!(json["inlets"][0]["injected"], 10);
    assert_eq!(json["outlets"][0]["name"], "top");
    assert_eq!(json["outlets"][0]["removed"], 6);
    assert_eq!(json["outlets"][1]["name"], "1");
    assert_eq!(json["outlets"][1]["removed"], 0);
}
