//! VTK XML files for ParaView: one `.vtu` (unstructured grid, ASCII) per exported time with every particle's real
//! outline as a polygon cell (a disk traced as the pictures trace it) and the particle columns as cell data, and
//! a `.pvd` collection listing the `.vtu` files with their times, so that ParaView opens the series as one dataset.

use super::rows::ParticleRow;
use gc2d_engine::{BodyId, World};
use gc2d_geometry::{DVec2, TracedOutline};
use std::fmt::Write as _;
use std::path::Path;

/// VTK's cell type of a polygon.
const VTK_POLYGON: u8 = 7;

/// The `.vtu` text of the particles `rows` of `world`.
pub fn particles_vtu(world: &World, rows: &[ParticleRow]) -> String {
    let bodies = world.bodies();
    let outlines: Vec<Vec<DVec2>> = rows
        .iter()
        .map(|row| match bodies.shape_view(BodyId(row.state.id)).traced_outline() {
            TracedOutline::Convex(vertices) => vertices.into_owned(),
            // Particles are polygons and disks; a ring is a chamber wall's outline.
            TracedOutline::Ring { outer, .. } => outer,
        })
        .collect();
    let points: usize = outlines.iter().map(Vec::len).sum();
    let mut xml = String::new();
    let _ = writeln!(xml, r#"<?xml version="1.0"?>"#);
    let _ = writeln!(xml, r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian">"#);
    let _ = writeln!(xml, "<UnstructuredGrid>");
    let _ = writeln!(xml, r#"<Piece NumberOfPoints="{points}" NumberOfCells="{}">"#, rows.len());
    let _ = writeln!(xml, "<Points>");
    let _ = writeln!(xml, r#"<DataArray type="Float64" NumberOfComponents="3" format="ascii">"#);
    for p in outlines.iter().flatten() {
        let _ = writeln!(xml, "{:e} {:e} 0", p.x, p.y);
    }
    let _ = writeln!(xml, "</DataArray>\n</Points>\n<Cells>");
    let _ = writeln!(xml, r#"<DataArray type="Int64" Name="connectivity" format="ascii">"#);
    let mut next = 0usize;
    for outline in &outlines {
        let ids: Vec<String> = (next..next + outline.len()).map(|k| k.to_string()).collect();
        let _ = writeln!(xml, "{}", ids.join(" "));
        next += outline.len();
    }
    let _ = writeln!(xml, "</DataArray>");
    let _ = writeln!(xml, r#"<DataArray type="Int64" Name="offsets" format="ascii">"#);
    let mut offset = 0usize;
    for outline in &outlines {
        offset += outline.len();
        let _ = write!(xml, "{offset} ");
    }
    let _ = writeln!(xml, "\n</DataArray>");
    let _ = writeln!(xml, r#"<DataArray type="UInt8" Name="types" format="ascii">"#);
    let _ = writeln!(xml, "{}", vec![VTK_POLYGON.to_string(); rows.len()].join(" "));
    let _ = writeln!(xml, "</DataArray>\n</Cells>");
    let _ = writeln!(xml, r#"<CellData Scalars="id" Vectors="velocity">"#);
    scalar(&mut xml, "id", "Int64", rows.iter().map(|r| r.state.id.to_string()));
    scalar(
        &mut xml,
        "material",
        "Int32",
        rows.iter().map(|r| bodies.material[r.state.id as usize].index().to_string()),
    );
    scalar(&mut xml, "corners", "Int32", rows.iter().map(|r| r.corners.to_string()));
    vector(&mut xml, "velocity", rows.iter().map(|r| (r.state.vx_m_s, r.state.vy_m_s)));
    scalar(&mut xml, "angular_velocity", "Float64", rows.iter().map(|r| format!("{:e}", r.state.omega_rad_s)));
    vector(&mut xml, "force", rows.iter().map(|r| (r.state.fx_n, r.state.fy_n)));
    scalar(&mut xml, "torque", "Float64", rows.iter().map(|r| format!("{:e}", r.state.torque_n_m)));
    scalar(&mut xml, "contacts", "Int32", rows.iter().map(|r| r.state.contacts.to_string()));
    scalar(&mut xml, "angle", "Float64", rows.iter().map(|r| format!("{:e}", r.state.phi_rad)));
    let _ = writeln!(xml, "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>");
    xml
}

fn scalar(xml: &mut String, name: &str, kind: &str, values: impl Iterator<Item = String>) {
    let _ = writeln!(xml, r#"<DataArray type="{kind}" Name="{name}" format="ascii">"#);
    let _ = writeln!(xml, "{}", values.collect::<Vec<_>>().join(" "));
    let _ = writeln!(xml, "</DataArray>");
}

fn vector(xml: &mut String, name: &str, values: impl Iterator<Item = (f64, f64)>) {
    let _ = writeln!(xml, r#"<DataArray type="Float64" Name="{name}" NumberOfComponents="3" format="ascii">"#);
    let texts: Vec<String> = values.map(|(x, y)| format!("{x:e} {y:e} 0")).collect();
    let _ = writeln!(xml, "{}", texts.join(" "));
    let _ = writeln!(xml, "</DataArray>");
}

/// The `.pvd` text of a series of `.vtu` files, each with its time, s; file names relative to the `.pvd`'s folder.
pub fn collection(entries: &[(f64, &Path)]) -> String {
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"LittleEndian\">\n<Collection>\n",
    );
    for (time, file) in entries {
        let _ = writeln!(xml, r#"<DataSet timestep="{time:e}" group="" part="0" file="{}"/>"#, file.display());
    }
    xml.push_str("</Collection>\n</VTKFile>\n");
    xml
}
