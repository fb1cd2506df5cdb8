//! A scene that uses every part of the format, shared by the tests.

/// Every kind of wall, particle, block and source, with exactly known counts (see `tests/load.rs`): 36 wall
/// polygons (5 walls, a 24-segment drum, 2 funnel slabs, 3 silo walls, 4 box walls), 3 of them moving;
/// 4 explicit particles, one with a drag spring; blocks of 202 (FCC, 4 rows of 51, 50, 51, 50) and 11 particles;
/// one source.
#[allow(dead_code)]
pub const FULL_SCENE: &str = r#"// A scene using every part of the format.
Scene(
    name: "full",
    run: (time_step_s: 2e-6, end_time_s: 0.01, frames_per_second: 200, checkpoint_interval_s: 0.005, seed: 7,
          domain: (x_range_m: (-1.0, 3.5), y_range_m: (-1.0, 1.0)), max_overlap_fraction: 0.05),
    gravity: Varying(profile: SmoothStep, from_m_s2: 9.81, to_m_s2: 9.0, window_s: (0.1, 1.1), steps: 5, ramp_fraction: 0.2),
    heating: (window_s: (0.5, inf), amplitude: 0.01, frequency_hz: 2.0),
    materials: [
        (name: "sand", gamma: 0.75),
        (name: "lead", density_kg_m2: 20000, gamma: 0.75),
    ],
    walls: [
        Wall(shape: Rectangle(width_m: 0.4, height_m: 0.01), position_m: (0.0, -0.005)),
        Wall(shape: Polygon(corners_m: [(0.3, 0.0), (0.4, 0.0), (0.4, 0.05)]), surface_velocity_m_s: (0.1, 0.0)),
        Wall(shape: Square(side_m: 0.02), position_m: (0.6, 0.0),
             motion: Vibration(amplitude_m: 0.001, frequency_hz: 20, waveform: Tapping)),
        Wall(shape: CutRectangle(width_m: 0.05, height_m: 0.02, cut: 0.1), position_m: (0.8, 0.0),
             motion: Piston(direction_rad: 1.5707963267948966, force_n: 10)),
        Wall(shape: RoundSquare(side_m: 0.02, radius_m: 0.005, corners_per_rounding: 4), position_m: (1.0, 0.0),
             motion: Rotation(pivot_m: (1.0, 0.0), angular_velocity_rad_s: 1.0)),
        Drum(centre_m: (2.0, 0.5), inner_radius_m: 0.1, thickness_m: 0.01, surface_speed_m_s: 0.1, segments: 24),
        Funnel(outlet_m: (0.0, 0.3), opening_m: 0.02, slope_rad: 0.8, length_m: 0.05, thickness_m: 0.005),
        Silo(x_range_m: (3.0, 3.05), y_range_m: (0.0, 0.2), thickness_m: 0.005),
        Box(x_range_m: (-0.8, -0.6), y_range_m: (0.0, 0.1), thickness_m: 0.005),
    ],
    particles: [
        (shape: Regular(corners: 7, radius_m: 0.002), position_m: (-0.2, 0.01), angle_rad: 0.3,
         velocity_m_s: (0.1, 0.0), angular_velocity_rad_s: 2.0),
        Particle(shape: Random(recipe: (semi_axes_m: (0.002, 0.0015), size_spread: Gauss(0.2), corners: 7,
                 corner_spread: Equal(1), corner_positions: Rand2, orientation: Gauss(0.5))), position_m: (-0.22, 0.01)),
        (shape: Polygon(corners_m: [(-0.26, 0.01), (-0.25, 0.01), (-0.25, 0.02), (-0.26, 0.02)]), material: "lead",
         drag_spring: (stiffness_n_m: 50, fixing_point_m: (0.001, 0.0), pulling_start_m: (-0.255, 0.015),
                       direction_rad: 0.0, speed_m_s: 0.01, window_s: (0.0, 1.0))),
        (shape: Ellipse(corners: 12, semi_axes_m: (0.003, 0.002)), position_m: (-0.3, 0.01)),
    ],
    blocks: [
        (x_range_m: (-0.15, 0.15), y_range_m: (0.01, 0.03), grid_spacing_m: (0.006, 0.006), grid: FccGauss,
         shape: (semi_axes_m: (0.0015, 0.0015), size_spread: Equal(0.2), corners: 8, corner_spread: Gauss(1),
                 corner_positions: Rand1, orientation: Equal),
         speed_range_m_s: (0.0, 0.05), direction_range_rad: (0.0, 3.14)),
        (x_range_m: (1.95, 2.05), y_range_m: (0.45, 0.45), grid_spacing_m: (0.01, 0.01), material: "lead",
         shape: (semi_axes_m: (0.003, 0.003), corners: 4, corner_positions: SpecialRectangle)),
    ],
    sources: [
        (position_m: (0.0, 0.4), width_m: 0.02, height: AboveHighest, window_s: (0.0, 0.5), interval_s: 0.001,
         shape: (semi_axes_m: (0.00175, 0.00175), size_spread: Equal(0.25), corners: 7, corner_positions: Full)),
    ],
    view: (x_range_m: (-1.0, 3.5), y_range_m: (-0.1, 0.7)),
)
"#;
