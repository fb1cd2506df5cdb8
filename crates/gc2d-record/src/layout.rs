//! A Foxglove layout for gc2d-rs recordings: a 3D panel looking straight down the z axis at the x-y plane, beside
//! two Plot panels fed by `/stats` (energies; contacts and coordination). docs/foxglove-layout.json is
//! [`default_layout`]; [`foxglove_layout`] frames another region, e.g. a scene's domain.

use gc2d_geometry::Aabb;
use serde_json::{Value, json};

/// The region the default layout frames: 1 m wide, 1 m high, centred on x = 0 above the floor y = 0.
pub fn default_view() -> Aabb {
    Aabb { min: gc2d_geometry::DVec2::new(-0.5, 0.0), max: gc2d_geometry::DVec2::new(0.5, 1.0) }
}

/// The layout of [`default_view`].
pub fn default_layout() -> Value {
    foxglove_layout(&default_view())
}

/// A layout whose 3D panel is centred on `view` and zoomed so that its larger side fits with a 10 % margin.
///
/// Camera: orthographic (`perspective: false`), polar angle `phi = 0` (looking down −z), `thetaOffset = 0` (x to
/// the right, y up), target at the view's centre. Far is kept small (100 m) so the depth buffer resolves the
/// recording's sub-millimetre layer offsets.
pub fn foxglove_layout(view: &Aabb) -> Value {
    let centre = 0.5 * (view.min + view.max);
    let size = view.max - view.min;
    let distance = 1.1 * size.x.max(size.y).max(f64::MIN_POSITIVE);
    let three_d = json!({
        "cameraState": {
            "perspective": false,
            "distance": distance,
            "phi": 0,
            "thetaOffset": 0,
            "targetOffset": [centre.x, centre.y, 0],
            "target": [0, 0, 0],
            "targetOrientation": [0, 0, 0, 1],
            "fovy": 45,
            "near": 0.001,
            "far": 100
        },
        "followMode": "follow-none",
        "followTf": crate::FRAME_ID,
        "scene": { "enableStats": false, "backgroundColor": "#ffffff", "transforms": { "visible": false } },
        "transforms": {},
        "topics": {
            "/walls": { "visible": true },
            "/particles": { "visible": true },
            "/contacts": { "visible": true },
            "/fluid": { "visible": true }
        },
        "layers": {},
        "publish": { "type": "point", "pointTopic": "/clicked_point", "poseTopic": "/move_base_simple/goal",
                     "poseEstimateTopic": "/initialpose", "poseEstimateXDeviation": 0.5,
                     "poseEstimateYDeviation": 0.5, "poseEstimateThetaDeviation": 0.26179939 },
        "imageMode": {}
    });
    let energies = plot(
        "Energies (J per unit thickness)",
        &[
            ("kinetic", "kinetic", "#4e98e2"),
            ("potential", "potential", "#f5774d"),
            ("elastic", "elastic (contacts)", "#61cbff"),
            ("dissipated", "dissipated", "#a395e2"),
        ],
    );
    let contacts = plot(
        "Contacts",
        &[("contacts", "touching pairs", "#f7df71"), ("mean_coordination", "mean coordination", "#5cd6a9")],
    );
    json!({
        "configById": {
            "3D!gc2d": three_d,
            "Plot!energies": energies,
            "Plot!contacts": contacts
        },
        "globalVariables": {},
        "userNodes": {},
        "playbackConfig": { "speed": 1 },
        "layout": {
            "direction": "row",
            "first": "3D!gc2d",
            "second": {
                "direction": "column",
                "first": "Plot!energies",
                "second": "Plot!contacts",
                "splitPercentage": 50
            },
            "splitPercentage": 62
        }
    })
}

/// A Plot panel of `/stats` fields against time: (field, label, colour).
fn plot(title: &str, series: &[(&str, &str, &str)]) -> Value {
    let paths: Vec<Value> = series
        .iter()
        .map(|(field, label, colour)| {
            json!({
                "value": format!("/stats.{field}"),
                "enabled": true,
                "timestampMethod": "receiveTime",
                "label": label,
                "color": colour
            })
        })
        .collect();
    json!({
        "foxglovePanelTitle": title,
        "paths": paths,
        "showXAxisLabels": true,
        "showYAxisLabels": true,
        "showLegend": true,
        "legendDisplay": "floating",
        "showPlotValuesInLegend": true,
        "isSynced": true,
        "xAxisVal": "timestamp",
        "sidebarDimension": 240
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/foxglove-layout.json must be [`default_layout`]; `GC2D_BLESS=1 cargo test -p gc2d-record` rewrites it.
    #[test]
    fn docs_layout_file_is_the_default_layout() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/foxglove-layout.json");
        if std::env::var_os("GC2D_BLESS").is_some() {
            let text = serde_json::to_string_pretty(&default_layout()).unwrap() + "\n";
            std::fs::write(path, text).unwrap();
        }
        let file: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        assert_eq!(file, default_layout(), "run GC2D_BLESS=1 cargo test -p gc2d-record layout to regenerate {path}");
    }

    #[test]
    fn camera_looks_straight_down_at_the_view_centre() {
        let view = Aabb { min: gc2d_geometry::DVec2::new(1.0, 2.0), max: gc2d_geometry::DVec2::new(3.0, 6.0) };
        let layout = foxglove_layout(&view);
        let camera = &layout["configById"]["3D!gc2d"]["cameraState"];
        assert_eq!(camera["phi"], 0);
        assert_eq!(camera["perspective"], false);
        assert_eq!(camera["targetOffset"], json!([2.0, 4.0, 0]));
        assert!((camera["distance"].as_f64().unwrap() - 4.4).abs() < 1e-12);
        let paths = &layout["configById"]["Plot!energies"]["paths"];
        assert_eq!(paths[0]["value"], "/stats.kinetic");
    }
}
