use gc2d_scene::Scene;
#[test]
fn scratch() {
    let text = r#"// test
Scene(
    run: (time_step_s: 1e-6, end_time_s: 0.01, seed: 3, domain: (x_range_m: (-1, 1), y_range_m: (-1, 1))),
    gravity: Constant(9.81),
    materials: [(name: "sand", gamma: 0.75)],
    walls: [
        Wall(shape: Rectangle(width_m: 0.2, height_m: 0.01), position_m: (0, -0.005)),
        Drum(centre_m: (0, 0.5), inner_radius_m: 0.1, thickness_m: 0.01, surface_speed_m_s: 0.1, segments: 24),
        Box(x_range_m: (2, 3), y_range_m: (0, 1), thickness_m: 0.01),
    ],
    particles: [
        (shape: Regular(corners: 7, radius_m: 0.002), position_m: (0, 0.01)),
        Particle(shape: Random(semi_axes_m: (0.002, 0.002), size_spread: Equal(0.25), corners: 7, corner_positions: Rand1), position_m: (0.01, 0.01)),
    ],
    blocks: [(x_range_m: (-0.05, 0.05), y_range_m: (0.02, 0.04), grid_spacing_m: (0.005, 0.005), grid: FccGauss,
              shape: (semi_axes_m: (0.002, 0.002), corners: 7, orientation: Equal))],
    sources: [(position_m: (0, 0.2), shape: (semi_axes_m: (0.002, 0.002)))],
)"#;
    match Scene::from_str(text, "t.ron") {
        Ok(s) => {
            println!("{:?}", s.gravity);
            match s.summary() {
                Ok(sum) => println!("{sum}"),
                Err(e) => println!("{}", e.render_plain()),
            }
        }
        Err(e) => println!("{}", e.render_plain()),
    }
    for bad in [
        "Scene(materials: [(name: \"a\", gamm: 0.5)])",
        "Scene(run: (seed: \"x\"))",
        "Scene(blocks: [(x_range_m: (0,1))])",
        "Scene(materials: [(name: \"a\", mu: -0.5)])",
        "Scene(walls: [Wall(shape: Polygon(corners_m: [(0,0),(1,0),(0.2,0.2),(0,1)]))])",
        "Scene(gravity: Constant(\"x\"))",
        "Scene(blocks: [(grid: FCC)])",
        "Scene(run: (time_step_s: 1e-3), particles: [(shape: Square(side_m: 0.001))])",
        "Scene(particles: [(shape: Square(side_m: 0.01)), (shape: Square(side_m: 0.01), position_m: (0.001, 0))])",
        "Scene(run: (seed: 1,)",
    ] {
        match Scene::from_str(bad, "bad.ron").and_then(|s| s.build().map(|_| ())) {
            Ok(_) => println!("OK?? {bad}"),
            Err(e) => println!("{}\n{}", e, e.render_plain()),
        }
    }
}
