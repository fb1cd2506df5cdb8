//! The parser behind [`VtkFile::parse`]: the three header lines, then keyword-led sections read word by word.

use super::tokens::{Token, Tokens};
use super::{Cells, DataArray, DatasetKind, VtkError, VtkFile};

/// The data type names legacy VTK allows after a count.
const DATA_TYPES: [&str; 16] = [
    "bit",
    "unsigned_char",
    "char",
    "unsigned_short",
    "short",
    "unsigned_int",
    "int",
    "unsigned_long",
    "long",
    "float",
    "double",
    "vtktypeint64",
    "vtktypeuint64",
    "vtktypeint32",
    "vtktypeuint32",
    "vtkidtype",
];

/// The keywords that may start a section, for messages.
const SECTION_KEYWORDS: &str = "FIELD, DIMENSIONS, ORIGIN, SPACING, POINTS, X_COORDINATES, Y_COORDINATES, \
    Z_COORDINATES, CELLS, CELL_TYPES, VERTICES, LINES, POLYGONS, TRIANGLE_STRIPS, POINT_DATA or CELL_DATA";

/// The keywords that may start an array inside POINT_DATA or CELL_DATA, for messages.
const ARRAY_KEYWORDS: &str =
    "SCALARS, COLOR_SCALARS, LOOKUP_TABLE, VECTORS, NORMALS, TEXTURE_COORDINATES, TENSORS or FIELD";

pub(super) fn parse(bytes: &[u8], file: &str) -> Result<VtkFile, VtkError> {
    let error = |line: usize, message: String| VtkError::Syntax { file: file.to_string(), line, message };
    let mut header = Vec::with_capacity(3);
    let mut rest = bytes;
    // The line the words after the header start on: 4, or earlier where the file ends within its header.
    let mut first_line = 1;
    for k in 1..=3 {
        if rest.is_empty() && first_line < k {
            let message = "expected the three header lines (version, title, ASCII), found the end of the file";
            return Err(error(first_line, message.to_string()));
        }
        let end = rest.iter().position(|&b| b == b'\n');
        first_line += usize::from(end.is_some());
        let line = &rest[..end.unwrap_or(rest.len())];
        header.push(String::from_utf8_lossy(line).trim().to_string());
        rest = end.map_or(&[][..], |e| &rest[e + 1..]);
    }
    if !header[0].to_ascii_lowercase().starts_with("# vtk datafile version") {
        return Err(error(1, format!("expected `# vtk DataFile Version x.y`, found `{}`", clip(&header[0]))));
    }
    match header[2].to_ascii_uppercase().as_str() {
        "ASCII" => {}
        "BINARY" => {
            return Err(error(3, "binary VTK is not read: export as ASCII (foamToVTK -legacy -ascii)".to_string()));
        }
        other => return Err(error(3, format!("expected ASCII, found `{}`", clip(other)))),
    }
    let text = std::str::from_utf8(rest).map_err(|e| {
        let line = first_line + rest[..e.valid_up_to()].iter().filter(|&&b| b == b'\n').count();
        error(line, format!("expected text, found the byte 0x{:02x}", rest[e.valid_up_to()]))
    })?;
    let mut parser = Parser { file, tokens: Tokens::new(text, first_line) };
    parser.file_body(header[1].clone())
}

/// Shortens what the file said to a readable length for a message.
fn clip(text: &str) -> String {
    const MAX: usize = 40;
    if text.chars().count() <= MAX {
        text.to_string()
    } else {
        format!("{}...", text.chars().take(MAX).collect::<String>())
    }
}

/// A hint for a number found where a keyword belongs: the count before it was too small.
fn hint(text: &str) -> &'static str {
    if text.parse::<f64>().is_ok() { " (a number where a keyword belongs: is a count above too small?)" } else { "" }
}

/// A POINT_DATA or CELL_DATA section being read.
#[derive(Clone, Copy)]
struct Section {
    cells: bool,
    count: usize,
}

/// What the sections of the dataset said, before the structure is checked and made explicit.
#[derive(Default)]
struct Pieces {
    dimensions: Option<([usize; 3], usize)>,
    origin: Option<[f64; 3]>,
    spacing: Option<[f64; 3]>,
    points: Option<(Vec<[f64; 3]>, usize)>,
    coordinates: [Option<(Vec<f64>, usize)>; 3],
    cells: Option<(Cells, usize)>,
    cell_types: Option<(usize, usize)>,
}

struct Parser<'a> {
    file: &'a str,
    tokens: Tokens<'a>,
}

impl<'a> Parser<'a> {
    fn error(&self, line: usize, message: String) -> VtkError {
        VtkError::Syntax { file: self.file.to_string(), line, message }
    }

    /// The next word, or an error saying `what` was expected at the end of the file.
    fn next(&mut self, what: &str) -> Result<Token<'a>, VtkError> {
        match self.tokens.next() {
            Some(token) => Ok(token),
            None => Err(self.error(self.tokens.line(), format!("expected {what}, found the end of the file"))),
        }
    }

    fn count(&mut self, what: &str) -> Result<(usize, usize), VtkError> {
        let token = self.next(what)?;
        match token.text.parse::<usize>() {
            Ok(n) => Ok((n, token.line)),
            Err(_) => Err(self.error(token.line, format!("expected {what} (a count), found `{}`", clip(token.text)))),
        }
    }

    fn number(&mut self, what: &str) -> Result<f64, VtkError> {
        let token = self.next(what)?;
        match token.text.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            Ok(_) => {
                Err(self.error(token.line, format!("expected {what}, found the non-finite `{}`", clip(token.text))))
            }
            Err(_) => Err(self.error(token.line, format!("expected {what} (a number), found `{}`", clip(token.text)))),
        }
    }

    fn data_type(&mut self, what: &str) -> Result<(), VtkError> {
        let token = self.next(&format!("the data type of {what}"))?;
        if DATA_TYPES.contains(&token.text.to_ascii_lowercase().as_str()) {
            Ok(())
        } else {
            Err(self.error(
                token.line,
                format!("expected the data type of {what} (float, double, int, ...), found `{}`", clip(token.text)),
            ))
        }
    }

    fn name(&mut self, what: &str) -> Result<String, VtkError> {
        Ok(self.next(what)?.text.to_string())
    }

    /// A product of counts, refused where it overflows or exceeds what the rest of the file can hold.
    fn product(&self, factors: &[usize], line: usize, what: &str) -> Result<usize, VtkError> {
        let total = factors.iter().try_fold(1usize, |acc, &f| acc.checked_mul(f));
        match total {
            Some(n) if n <= self.tokens.remaining_len() => Ok(n),
            _ => Err(self.error(line, format!("{what}: the counts ask for more numbers than the file holds"))),
        }
    }

    fn numbers(&mut self, count: usize, what: &str) -> Result<Vec<f64>, VtkError> {
        let mut values = Vec::with_capacity(count.min(self.tokens.remaining_len() / 2 + 1));
        for i in 0..count {
            values.push(self.number(&format!("{what}: number {} of {count}", i + 1))?);
        }
        Ok(values)
    }

    fn indices(&mut self, count: usize, what: &str) -> Result<Vec<usize>, VtkError> {
        let mut values = Vec::with_capacity(count.min(self.tokens.remaining_len() / 2 + 1));
        for i in 0..count {
            values.push(self.count(&format!("{what}: entry {} of {count}", i + 1))?.0);
        }
        Ok(values)
    }

    fn triple(&mut self, what: &str) -> Result<[f64; 3], VtkError> {
        Ok([self.number(what)?, self.number(what)?, self.number(what)?])
    }

    /// Refuses a section that came before.
    fn once(&self, seen: bool, keyword: &str, line: usize) -> Result<(), VtkError> {
        if seen { Err(self.error(line, format!("a second {keyword} section"))) } else { Ok(()) }
    }

    fn peek_is(&self, keyword: &str) -> bool {
        self.tokens.peek().is_some_and(|t| t.text.eq_ignore_ascii_case(keyword))
    }

    fn file_body(&mut self, title: String) -> Result<VtkFile, VtkError> {
        let token = self.next("DATASET")?;
        if !token.text.eq_ignore_ascii_case("DATASET") {
            return Err(self.error(token.line, format!("expected DATASET, found `{}`", clip(token.text))));
        }
        let kind_token = self.next("the dataset structure")?;
        let dataset = match kind_token.text.to_ascii_uppercase().as_str() {
            "STRUCTURED_POINTS" => DatasetKind::StructuredPoints,
            "STRUCTURED_GRID" => DatasetKind::StructuredGrid,
            "RECTILINEAR_GRID" => DatasetKind::RectilinearGrid,
            "POLYDATA" => DatasetKind::PolyData,
            "UNSTRUCTURED_GRID" => DatasetKind::UnstructuredGrid,
            "FIELD" => return Err(self.error(kind_token.line, "the FIELD dataset structure is not read".to_string())),
            other => {
                return Err(self.error(
                    kind_token.line,
                    format!(
                        "expected STRUCTURED_POINTS, STRUCTURED_GRID, RECTILINEAR_GRID, POLYDATA or \
                         UNSTRUCTURED_GRID, found `{}`",
                        clip(other)
                    ),
                ));
            }
        };
        let mut pieces = Pieces::default();
        let mut file = VtkFile {
            source: self.file.to_string(),
            title,
            dataset,
            points: Vec::new(),
            cells: Cells::default(),
            point_data: Vec::new(),
            cell_data: Vec::new(),
            time_value: None,
            section_lines: [0; 2],
        };
        let mut section: Option<Section> = None;
        let mut structure_done = false;
        while let Some(token) = self.tokens.next() {
            let keyword = token.text.to_ascii_uppercase();
            let line = token.line;
            match keyword.as_str() {
                "POINT_DATA" | "CELL_DATA" => {
                    let cells = keyword == "CELL_DATA";
                    if !structure_done {
                        self.finish_structure(&mut pieces, &mut file, line)?;
                        structure_done = true;
                    }
                    let (count, _) = self.count(&format!("the number of values after {keyword}"))?;
                    let (expected, of) =
                        if cells { (file.cells.len(), "cells") } else { (file.points.len(), "points") };
                    if count != expected {
                        return Err(self.error(line, format!("{keyword} {count}, but the dataset has {expected} {of}")));
                    }
                    if file.section_lines[usize::from(cells)] != 0 {
                        return Err(self.error(line, format!("a second {keyword} section")));
                    }
                    file.section_lines[usize::from(cells)] = line;
                    section = Some(Section { cells, count });
                }
                _ => match section {
                    Some(sec) => {
                        let arrays = self.attribute(&keyword, token, sec)?;
                        let target = if sec.cells { &mut file.cell_data } else { &mut file.point_data };
                        target.extend(arrays);
                    }
                    None => self.structure_section(&keyword, token, dataset, &mut pieces, &mut file)?,
                },
            }
        }
        if !structure_done {
            self.finish_structure(&mut pieces, &mut file, self.tokens.line())?;
        }
        let last = self.tokens.line();
        for l in &mut file.section_lines {
            if *l == 0 {
                *l = last;
            }
        }
        Ok(file)
    }

    /// One section of the dataset's structure (before POINT_DATA and CELL_DATA).
    fn structure_section(
        &mut self,
        keyword: &str,
        token: Token<'a>,
        dataset: DatasetKind,
        pieces: &mut Pieces,
        file: &mut VtkFile,
    ) -> Result<(), VtkError> {
        let line = token.line;
        let structured = matches!(
            dataset,
            DatasetKind::StructuredPoints | DatasetKind::StructuredGrid | DatasetKind::RectilinearGrid
        );
        let allowed = match keyword {
            "FIELD" => true,
            "DIMENSIONS" => structured,
            "ORIGIN" | "SPACING" | "ASPECT_RATIO" => dataset == DatasetKind::StructuredPoints,
            "POINTS" => {
                matches!(dataset, DatasetKind::StructuredGrid | DatasetKind::PolyData | DatasetKind::UnstructuredGrid)
            }
            "X_COORDINATES" | "Y_COORDINATES" | "Z_COORDINATES" => dataset == DatasetKind::RectilinearGrid,
            "CELLS" | "CELL_TYPES" => dataset == DatasetKind::UnstructuredGrid,
            "VERTICES" | "LINES" | "POLYGONS" | "TRIANGLE_STRIPS" => dataset == DatasetKind::PolyData,
            "METADATA" => return Err(self.error(line, "METADATA blocks are not read".to_string())),
            _ => {
                let message = format!("expected {SECTION_KEYWORDS}, found `{}`{}", clip(token.text), hint(token.text));
                return Err(self.error(line, message));
            }
        };
        if !allowed {
            return Err(self.error(line, format!("{keyword} does not belong in a {} dataset", dataset.keyword())));
        }
        match keyword {
            "FIELD" => {
                let arrays = self.field(None)?;
                if let Some(time) = arrays.iter().find(|a| a.name == "TimeValue") {
                    file.time_value = time.values.first().copied();
                }
            }
            "DIMENSIONS" => {
                self.once(pieces.dimensions.is_some(), keyword, line)?;
                let mut dims = [0; 3];
                for d in &mut dims {
                    *d = self.count("a dimension after DIMENSIONS")?.0;
                    if *d == 0 {
                        return Err(self.error(line, "DIMENSIONS must be at least 1 each".to_string()));
                    }
                }
                pieces.dimensions = Some((dims, line));
            }
            "ORIGIN" => {
                self.once(pieces.origin.is_some(), keyword, line)?;
                pieces.origin = Some(self.triple("a coordinate of ORIGIN")?);
            }
            "SPACING" | "ASPECT_RATIO" => {
                self.once(pieces.spacing.is_some(), keyword, line)?;
                pieces.spacing = Some(self.triple("a component of SPACING")?);
            }
            "POINTS" => {
                self.once(pieces.points.is_some(), keyword, line)?;
                let (n, _) = self.count("the number of points")?;
                self.data_type("POINTS")?;
                let count = self.product(&[n, 3], line, "POINTS")?;
                let values = self.numbers(count, "POINTS")?;
                let points = values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
                pieces.points = Some((points, line));
            }
            "X_COORDINATES" | "Y_COORDINATES" | "Z_COORDINATES" => {
                let axis = usize::from(keyword.as_bytes()[0] - b'X');
                self.once(pieces.coordinates[axis].is_some(), keyword, line)?;
                let (n, _) = self.count(&format!("the number of values after {keyword}"))?;
                self.data_type(keyword)?;
                let count = self.product(&[n], line, keyword)?;
                pieces.coordinates[axis] = Some((self.numbers(count, keyword)?, line));
            }
            "CELL_TYPES" => {
                self.once(pieces.cell_types.is_some(), keyword, line)?;
                let (n, _) = self.count("the number of cell types")?;
                let count = self.product(&[n], line, "CELL_TYPES")?;
                self.indices(count, "CELL_TYPES")?;
                pieces.cell_types = Some((n, line));
            }
            _ => {
                // CELLS, VERTICES, LINES, POLYGONS, TRIANGLE_STRIPS: cell lists, all gathered into one list.
                if keyword == "CELLS" {
                    self.once(pieces.cells.is_some(), keyword, line)?;
                }
                let cells = self.cell_list(keyword, line)?;
                match &mut pieces.cells {
                    Some((all, _)) => {
                        let base = all.indices.len();
                        all.indices.extend(cells.indices);
                        all.offsets.extend(cells.offsets.iter().skip(1).map(|o| o + base));
                    }
                    None => pieces.cells = Some((cells, line)),
                }
            }
        }
        Ok(())
    }

    /// A cell list: `n size` then n groups `k i1 .. ik` (classic), or VTK 5.1's `n_offsets size` followed by the
    /// `OFFSETS` (one more than the cells) and `CONNECTIVITY` arrays.
    fn cell_list(&mut self, keyword: &str, line: usize) -> Result<Cells, VtkError> {
        let (n, _) = self.count(&format!("the number of cells after {keyword}"))?;
        let (size, _) = self.count(&format!("the number of entries after {keyword}"))?;
        if self.peek_is("OFFSETS") {
            self.tokens.next();
            self.data_type("OFFSETS")?;
            let count = self.product(&[n], line, "OFFSETS")?;
            let offsets = self.indices(count, "OFFSETS")?;
            let conn = self.next("CONNECTIVITY")?;
            if !conn.text.eq_ignore_ascii_case("CONNECTIVITY") {
                return Err(self.error(conn.line, format!("expected CONNECTIVITY, found `{}`", clip(conn.text))));
            }
            self.data_type("CONNECTIVITY")?;
            let count = self.product(&[size], line, "CONNECTIVITY")?;
            let indices = self.indices(count, "CONNECTIVITY")?;
            if n == 0 && size == 0 {
                return Ok(Cells { offsets: vec![0], indices });
            }
            let ordered =
                offsets.first() == Some(&0) && offsets.windows(2).all(|w| w[0] < w[1]) && offsets.last() == Some(&size);
            if !ordered {
                return Err(self.error(
                    line,
                    format!("{keyword}: OFFSETS must start at 0, grow and end at the CONNECTIVITY size {size}"),
                ));
            }
            return Ok(Cells { offsets, indices });
        }
        let count = self.product(&[size], line, keyword)?;
        let entries = self.indices(count, keyword)?;
        let mut cells = Cells { offsets: Vec::with_capacity(n.min(count) + 1), indices: Vec::with_capacity(count) };
        cells.offsets.push(0);
        let mut at = 0;
        for c in 0..n {
            let k = entries.get(at).copied().unwrap_or(0);
            if k == 0 || at + 1 + k > entries.len() {
                return Err(self.error(
                    line,
                    format!("{keyword} {n} {size}: cell {} of {n} needs more entries than the {size} given", c + 1),
                ));
            }
            cells.indices.extend_from_slice(&entries[at + 1..at + 1 + k]);
            cells.offsets.push(cells.indices.len());
            at += 1 + k;
        }
        if at != size {
            return Err(self.error(line, format!("{keyword} {n} {size}: the {n} cells use {at} entries, not {size}")));
        }
        Ok(cells)
    }

    /// A FIELD block: `FIELD name count`, then each array as `name components tuples type` and its numbers. In a
    /// data section, `tuples` must equal the section's count.
    fn field(&mut self, section: Option<Section>) -> Result<Vec<DataArray>, VtkError> {
        self.name("the name of the FIELD")?;
        let (count, _) = self.count("the number of arrays of the FIELD")?;
        let mut arrays = Vec::with_capacity(count.min(self.tokens.remaining_len() / 8 + 1));
        for _ in 0..count {
            let name_token = self.next("the name of a FIELD array")?;
            let name = name_token.text.to_string();
            let (components, _) = self.count(&format!("the number of components of {name}"))?;
            let (tuples, _) = self.count(&format!("the number of tuples of {name}"))?;
            self.data_type(&name)?;
            if let Some(expected) = section.map(|sec| sec.count).filter(|&c| c != tuples) {
                return Err(self.error(
                    name_token.line,
                    format!("FIELD array {name} has {tuples} tuples, but the section has {expected} values"),
                ));
            }
            let total = self.product(&[components, tuples], name_token.line, &name)?;
            let values = self.numbers(total, &format!("FIELD array {name}"))?;
            arrays.push(DataArray { name, components, values, line: name_token.line });
        }
        Ok(arrays)
    }

    /// One array of a POINT_DATA or CELL_DATA section, started by `keyword`.
    fn attribute(&mut self, keyword: &str, token: Token<'a>, section: Section) -> Result<Vec<DataArray>, VtkError> {
        let line = token.line;
        let n = section.count;
        let (name, components) = match keyword {
            "FIELD" => return self.field(Some(section)),
            "SCALARS" => {
                let name = self.name("the name of the SCALARS")?;
                self.data_type(&name)?;
                // The optional component count stands before LOOKUP_TABLE; a number followed by data is data.
                let mut components = 1;
                let mut ahead = self.tokens.clone();
                let next = ahead.next();
                let count = next.and_then(|t| t.text.parse::<usize>().ok());
                let table_follows = ahead.peek().is_some_and(|t| t.text.eq_ignore_ascii_case("LOOKUP_TABLE"));
                if let (Some(next), Some(c), true) = (next, count, table_follows) {
                    self.tokens.next();
                    if !(1..=4).contains(&c) {
                        return Err(self.error(next.line, format!("SCALARS {name}: 1 to 4 components, not {c}")));
                    }
                    components = c;
                }
                if self.peek_is("LOOKUP_TABLE") {
                    self.tokens.next();
                    self.name("the name of the LOOKUP_TABLE")?;
                }
                (name, components)
            }
            "COLOR_SCALARS" => {
                let name = self.name("the name of the COLOR_SCALARS")?;
                let (c, _) = self.count(&format!("the number of values of {name}"))?;
                (name, c)
            }
            "LOOKUP_TABLE" => {
                let name = self.name("the name of the LOOKUP_TABLE")?;
                let (size, _) = self.count(&format!("the size of LOOKUP_TABLE {name}"))?;
                let total = self.product(&[size, 4], line, "LOOKUP_TABLE")?;
                self.numbers(total, &format!("LOOKUP_TABLE {name}"))?;
                return Ok(Vec::new());
            }
            "VECTORS" | "NORMALS" => {
                let name = self.name(&format!("the name of the {keyword}"))?;
                self.data_type(&name)?;
                (name, 3)
            }
            "TENSORS" => {
                let name = self.name("the name of the TENSORS")?;
                self.data_type(&name)?;
                (name, 9)
            }
            "TEXTURE_COORDINATES" => {
                let name = self.name("the name of the TEXTURE_COORDINATES")?;
                let (dim, _) = self.count(&format!("the dimension of {name}"))?;
                self.data_type(&name)?;
                (name, dim)
            }
            _ => {
                return Err(self.error(
                    line,
                    format!(
                        "expected {ARRAY_KEYWORDS} (or POINT_DATA, CELL_DATA), found `{}`{}",
                        clip(token.text),
                        hint(token.text)
                    ),
                ));
            }
        };
        let total = self.product(&[n, components], line, &name)?;
        let values = self.numbers(total, &format!("{keyword} {name}"))?;
        Ok(vec![DataArray { name, components, values, line }])
    }

    /// Checks that the structure sections fit the dataset and makes implicit points and cells explicit.
    fn finish_structure(&self, pieces: &mut Pieces, file: &mut VtkFile, line: usize) -> Result<(), VtkError> {
        let kind = file.dataset.keyword();
        let missing = |what: &str| self.error(line, format!("expected {what} in a {kind} dataset before this line"));
        match file.dataset {
            DatasetKind::StructuredPoints => {
                let (dims, _) = pieces.dimensions.ok_or_else(|| missing("DIMENSIONS"))?;
                let origin = pieces.origin.ok_or_else(|| missing("ORIGIN"))?;
                let spacing = pieces.spacing.ok_or_else(|| missing("SPACING"))?;
                self.product(&dims, line, "DIMENSIONS (more points than the data after it can describe)")?;
                file.points = lattice_points(dims, |axis, i| origin[axis] + i as f64 * spacing[axis]);
                file.cells = lattice_cells(dims);
            }
            DatasetKind::RectilinearGrid => {
                let (dims, dims_line) = pieces.dimensions.ok_or_else(|| missing("DIMENSIONS"))?;
                let mut coords: [Vec<f64>; 3] = Default::default();
                for axis in 0..3 {
                    let name = ["X_COORDINATES", "Y_COORDINATES", "Z_COORDINATES"][axis];
                    let (values, at) = pieces.coordinates[axis].take().ok_or_else(|| missing(name))?;
                    if values.len() != dims[axis] {
                        return Err(self.error(
                            at,
                            format!(
                                "{name} has {} values, DIMENSIONS (line {dims_line}) says {}",
                                values.len(),
                                dims[axis]
                            ),
                        ));
                    }
                    coords[axis] = values;
                }
                self.product(&dims, line, "DIMENSIONS (more points than the data after it can describe)")?;
                file.points = lattice_points(dims, |axis, i| coords[axis][i]);
                file.cells = lattice_cells(dims);
            }
            DatasetKind::StructuredGrid => {
                let (dims, dims_line) = pieces.dimensions.ok_or_else(|| missing("DIMENSIONS"))?;
                let (points, at) = pieces.points.take().ok_or_else(|| missing("POINTS"))?;
                if Some(points.len()) != dims.iter().try_fold(1usize, |a, &d| a.checked_mul(d)) {
                    return Err(self.error(
                        at,
                        format!(
                            "POINTS has {} points, DIMENSIONS {} {} {} (line {dims_line}) needs their product",
                            points.len(),
                            dims[0],
                            dims[1],
                            dims[2]
                        ),
                    ));
                }
                file.points = points;
                file.cells = lattice_cells(dims);
            }
            DatasetKind::PolyData | DatasetKind::UnstructuredGrid => {
                let (points, _) = pieces.points.take().ok_or_else(|| missing("POINTS"))?;
                file.points = points;
                if let Some((cells, cells_line)) = pieces.cells.take() {
                    if let Some(&bad) = cells.indices.iter().find(|&&i| i >= file.points.len()) {
                        return Err(self.error(
                            cells_line,
                            format!("a cell names point {bad}, but there are {} points", file.points.len()),
                        ));
                    }
                    if let Some((types, types_line)) = pieces.cell_types.filter(|&(types, _)| types != cells.len()) {
                        return Err(self.error(
                            types_line,
                            format!("CELL_TYPES {types}, but CELLS (line {cells_line}) has {} cells", cells.len()),
                        ));
                    }
                    file.cells = cells;
                } else if let Some((_, types_line)) = pieces.cell_types {
                    return Err(self.error(types_line, "CELL_TYPES without CELLS".to_string()));
                }
                if file.cells.is_empty() {
                    file.cells.offsets = vec![0];
                }
            }
        }
        Ok(())
    }
}

/// The points of a lattice of `dims` points, x fastest: `coordinate(axis, i)` is the i-th coordinate along `axis`.
fn lattice_points(dims: [usize; 3], coordinate: impl Fn(usize, usize) -> f64) -> Vec<[f64; 3]> {
    let mut points = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                points.push([coordinate(0, i), coordinate(1, j), coordinate(2, k)]);
            }
        }
    }
    points
}

/// The cells of a lattice of `dims` points: hexahedra, quads or segments along the axes with more than one point
/// (one point per cell where all three dimensions are 1). The corners of a quad are listed around it.
fn lattice_cells(dims: [usize; 3]) -> Cells {
    let cell_dims = dims.map(|d| d.saturating_sub(1).max(1));
    let corners: Vec<[usize; 3]> = {
        let ring = [[0, 0], [1, 0], [1, 1], [0, 1]];
        let mut corners = Vec::new();
        for dk in 0..=usize::from(dims[2] > 1) {
            for [a, b] in ring {
                let c = [a * usize::from(dims[0] > 1), b * usize::from(dims[1] > 1), dk];
                if !corners.contains(&c) {
                    corners.push(c);
                }
            }
        }
        corners
    };
    let mut cells = Cells { offsets: vec![0], indices: Vec::new() };
    for k in 0..cell_dims[2] {
        for j in 0..cell_dims[1] {
            for i in 0..cell_dims[0] {
                for c in &corners {
                    cells.indices.push((i + c[0]) + dims[0] * ((j + c[1]) + dims[1] * (k + c[2])));
                }
                cells.offsets.push(cells.indices.len());
            }
        }
    }
    cells
}
