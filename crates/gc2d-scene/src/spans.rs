//! Where each value of a RON scene sits in its text: a light-weight second pass over the source that records, for
//! every field path (`walls[2].shape.corners_m[3]`), the byte span of its value and of its key.
//!
//! serde hands the scene types values without positions, so errors found after parsing (a non-convex polygon, a
//! negative μ, a time step above the stable bound) would otherwise point nowhere. This scanner knows just enough RON
//! to walk structures: comments, strings, atoms (numbers, identifiers), `(…)`, `[…]`, `{…}`, `key: value`. It never
//! fails: on malformed text it stops and keeps what it has, so the same index also names the field at the position of
//! a parse error.
//!
//! Path syntax: struct fields are joined with `.`, list elements are `[i]`, map entries `["key"]`, tuple elements
//! `.i`. A tuple with a single element written after an identifier (`Some(…)`, an enum variant such as
//! `Equal(0.25)` or an explicit newtype `Wall((…))`) is transparent: its element has the path of the tuple itself.

use std::collections::HashMap;
use std::ops::Range;

/// The recorded spans of one value: where its key (for struct fields and map entries) and its value are.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Node {
    path: String,
    key: Option<Range<usize>>,
    value: Range<usize>,
}

/// Spans of every value in a RON text, by field path.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SpanIndex {
    nodes: Vec<Node>,
    by_path: HashMap<String, usize>,
    unclosed_at_end: Vec<usize>,
}

impl SpanIndex {
    /// Scans `text`. Never fails; malformed text yields the nodes found before the first token that does not fit.
    pub fn scan(text: &str) -> Self {
        let mut scanner =
            Scanner { text, bytes: text.as_bytes(), pos: 0, nodes: Vec::new(), depth: 0, open_brackets: Vec::new() };
        scanner.skip_trivia();
        let complete = scanner.value(String::new(), None);
        // Brackets still open where the scan stopped count as unclosed only if it stopped at the end of the text.
        let unclosed_at_end = if complete || scanner.pos < text.len() { Vec::new() } else { scanner.open_brackets };
        let mut by_path = HashMap::new();
        for (i, node) in scanner.nodes.iter().enumerate() {
            // Later (inner, transparent) nodes win: `gravity: Constant(9.81)` points `gravity` at `9.81`.
            by_path.insert(node.path.clone(), i);
        }
        Self { nodes: scanner.nodes, by_path, unclosed_at_end }
    }

    /// The byte offsets of the brackets (`(`, `[`, `{`) that the text leaves open when it ends, outermost first; empty
    /// when the text ends with every bracket closed, or the scan stopped before its end at something else.
    pub fn unclosed_at_end(&self) -> &[usize] {
        &self.unclosed_at_end
    }

    /// The span to underline for `path`: its value if written; otherwise (a defaulted field) the key of the nearest
    /// written ancestor, or the first character of its value. `None` when nothing of the path is written.
    pub fn span_of(&self, path: &str) -> Option<Range<usize>> {
        if let Some(&i) = self.by_path.get(path) {
            return Some(self.nodes[i].value.clone());
        }
        let mut prefix = path;
        while let Some(parent) = parent_path(prefix) {
            if let Some(&i) = self.by_path.get(parent) {
                let node = &self.nodes[i];
                return Some(node.key.clone().unwrap_or(node.value.start..node.value.start + 1));
            }
            prefix = parent;
        }
        None
    }

    /// The span of the outermost value that starts exactly at `offset`.
    pub fn value_starting_at(&self, offset: usize) -> Option<Range<usize>> {
        self.nodes.iter().find(|n| n.value.start == offset && n.value.end > offset).map(|n| n.value.clone())
    }

    /// The path of the innermost value or key at byte `offset`: a key gives its field's path, a value the path of
    /// the smallest value that contains the offset. `None` outside every value.
    pub fn path_at(&self, offset: usize) -> Option<&str> {
        if let Some(node) = self.nodes.iter().find(|n| n.key.as_ref().is_some_and(|k| k.contains(&offset))) {
            return Some(&node.path);
        }
        self.nodes
            .iter()
            .filter(|n| n.value.start <= offset && offset < n.value.end.max(n.value.start + 1))
            .min_by_key(|n| (n.value.end - n.value.start, std::cmp::Reverse(n.path.len())))
            .map(|n| n.path.as_str())
    }
}

/// The path one level up: `a.b[2]` → `a.b`, `a.b` → `a`, `a` → ``; `None` for the root.
pub fn parent_path(path: &str) -> Option<&str> {
    if path.is_empty() {
        return None;
    }
    let cut = path.rfind(['.', '[']).unwrap_or(0);
    Some(&path[..cut])
}

/// Joins a field name onto a path.
pub fn field_path(parent: &str, field: &str) -> String {
    if parent.is_empty() { field.to_owned() } else { format!("{parent}.{field}") }
}

/// Deepest nesting the scanner follows; deeper text is skipped (the ron parser has its own recursion limit).
const MAX_DEPTH: usize = 128;

struct Scanner<'a> {
    text: &'a str,
    bytes: &'a [u8],
    pos: usize,
    nodes: Vec<Node>,
    depth: usize,
    /// Offsets of the brackets opened and not yet closed, outermost first.
    open_brackets: Vec<usize>,
}

impl Scanner<'_> {
    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.pos).copied()
    }

    /// Skips whitespace, `//` and (nested) `/* */` comments and `#![…]` attributes.
    fn skip_trivia(&mut self) {
        loop {
            match self.peek() {
                Some(b) if b.is_ascii_whitespace() => self.pos += 1,
                Some(b'/') if self.bytes.get(self.pos + 1) == Some(&b'/') => {
                    while self.peek().is_some_and(|b| b != b'\n') {
                        self.pos += 1;
                    }
                }
                Some(b'/') if self.bytes.get(self.pos + 1) == Some(&b'*') => {
                    self.pos += 2;
                    let mut level = 1;
                    while level > 0 && self.pos < self.bytes.len() {
                        if self.bytes[self.pos..].starts_with(b"/*") {
                            level += 1;
                            self.pos += 2;
                        } else if self.bytes[self.pos..].starts_with(b"*/") {
                            level -= 1;
                            self.pos += 2;
                        } else {
                            self.pos += 1;
                        }
                    }
                }
                Some(b'#') => {
                    while self.peek().is_some_and(|b| b != b']') {
                        self.pos += 1;
                    }
                    self.pos = (self.pos + 1).min(self.bytes.len());
                }
                _ => return,
            }
        }
    }

    /// Records a value at `path` starting at the current position. Returns false when the text does not continue
    /// with a value (the scan then stops).
    fn value(&mut self, path: String, key: Option<Range<usize>>) -> bool {
        let start = self.pos;
        let index = self.nodes.len();
        self.nodes.push(Node { path: path.clone(), key, value: start..self.bytes.len() });
        self.depth += 1;
        let ok = self.depth <= MAX_DEPTH && self.value_body(&path, index);
        self.depth -= 1;
        if ok {
            self.nodes[index].value.end = self.pos;
        }
        ok
    }

    fn value_body(&mut self, path: &str, index: usize) -> bool {
        match self.peek() {
            Some(b'(') => self.parenthesised(path, false),
            Some(b'[') => self.list(path),
            Some(b'{') => self.map(path),
            Some(b'"') => self.string(),
            Some(b'\'') => self.char_literal(),
            Some(b'r') if matches!(self.bytes.get(self.pos + 1), Some(b'"' | b'#')) => self.raw_string(),
            Some(b) if is_atom_byte(b) => {
                self.atom();
                let atom_end = self.pos;
                let save = self.pos;
                self.skip_trivia();
                if self.peek() == Some(b'(') {
                    self.parenthesised(path, true)
                } else {
                    self.pos = save;
                    self.nodes[index].value.end = atom_end;
                    true
                }
            }
            _ => false,
        }
    }

    fn atom(&mut self) {
        while self.peek().is_some_and(is_atom_byte) {
            self.pos += 1;
        }
    }

    fn string(&mut self) -> bool {
        self.pos += 1;
        while let Some(b) = self.peek() {
            self.pos += 1;
            match b {
                b'\\' => self.pos += 1,
                b'"' => return true,
                _ => {}
            }
        }
        false
    }

    fn char_literal(&mut self) -> bool {
        self.pos += 1;
        while let Some(b) = self.peek() {
            self.pos += 1;
            match b {
                b'\\' => self.pos += 1,
                b'\'' => return true,
                _ => {}
            }
        }
        false
    }

    fn raw_string(&mut self) -> bool {
        self.pos += 1;
        let hashes = self.bytes[self.pos..].iter().take_while(|&&b| b == b'#').count();
        self.pos += hashes;
        if self.peek() != Some(b'"') {
            return false;
        }
        self.pos += 1;
        let closing: Vec<u8> = std::iter::once(b'"').chain(std::iter::repeat_n(b'#', hashes)).collect();
        match self.bytes[self.pos..].windows(closing.len()).position(|w| w == closing.as_slice()) {
            Some(at) => {
                self.pos += at + closing.len();
                true
            }
            None => false,
        }
    }

    /// `( … )`: named fields if it starts with `identifier :`, else tuple elements.
    fn parenthesised(&mut self, path: &str, named: bool) -> bool {
        self.open();
        self.skip_trivia();
        if self.starts_with_field() {
            return self.fields(path, b')');
        }
        let first_node = self.nodes.len();
        let mut count = 0;
        loop {
            self.skip_trivia();
            match self.peek() {
                Some(b')') => {
                    self.close();
                    break;
                }
                None => return false,
                _ => {}
            }
            if !self.value(field_path(path, &count.to_string()), None) || !self.separator(b')') {
                return false;
            }
            count += 1;
        }
        if named && count == 1 {
            self.make_transparent(path, first_node);
        }
        true
    }

    /// Renames the nodes recorded since `first_node` from `path.0…` to `path…`: the single element of `Some(…)` or of
    /// an enum variant stands for the whole value.
    fn make_transparent(&mut self, path: &str, first_node: usize) {
        let element = field_path(path, "0");
        for node in &mut self.nodes[first_node..] {
            if let Some(rest) = node.path.strip_prefix(element.as_str()) {
                let rest = if path.is_empty() { rest.trim_start_matches('.') } else { rest };
                node.path = format!("{path}{rest}");
            }
        }
    }

    /// True when the text continues with `identifier :` (and not `identifier ::`).
    fn starts_with_field(&mut self) -> bool {
        let save = self.pos;
        let is_field = if self.peek().is_some_and(is_ident_start) {
            self.atom();
            self.skip_trivia();
            self.peek() == Some(b':')
        } else {
            false
        };
        self.pos = save;
        is_field
    }

    fn fields(&mut self, path: &str, close: u8) -> bool {
        loop {
            self.skip_trivia();
            match self.peek() {
                Some(b) if b == close => {
                    self.close();
                    return true;
                }
                Some(b) if is_ident_start(b) => {}
                _ => return false,
            }
            let key_start = self.pos;
            self.atom();
            let key = key_start..self.pos;
            let name = self.text[key.clone()].trim_start_matches("r#").to_owned();
            self.skip_trivia();
            if self.peek() != Some(b':') {
                return false;
            }
            self.pos += 1;
            self.skip_trivia();
            if !self.value(field_path(path, &name), Some(key)) || !self.separator(close) {
                return false;
            }
        }
    }

    fn list(&mut self, path: &str) -> bool {
        self.open();
        let mut i = 0;
        loop {
            self.skip_trivia();
            match self.peek() {
                Some(b']') => {
                    self.close();
                    return true;
                }
                None => return false,
                _ => {}
            }
            if !self.value(format!("{path}[{i}]"), None) || !self.separator(b']') {
                return false;
            }
            i += 1;
        }
    }

    fn map(&mut self, path: &str) -> bool {
        self.open();
        loop {
            self.skip_trivia();
            match self.peek() {
                Some(b'}') => {
                    self.close();
                    return true;
                }
                None => return false,
                _ => {}
            }
            let key_start = self.pos;
            let saved = self.nodes.len();
            if !self.value(String::new(), None) {
                return false;
            }
            self.nodes.truncate(saved);
            let key = key_start..self.pos;
            let name = self.text[key.clone()].to_owned();
            self.skip_trivia();
            if self.peek() != Some(b':') {
                return false;
            }
            self.pos += 1;
            self.skip_trivia();
            if !self.value(format!("{path}[{name}]"), Some(key)) || !self.separator(b'}') {
                return false;
            }
        }
    }

    /// Steps over an opening bracket at the current position and notes it as open.
    fn open(&mut self) {
        self.open_brackets.push(self.pos);
        self.pos += 1;
    }

    /// Steps over the closing bracket at the current position; the innermost open one is closed.
    fn close(&mut self) {
        self.open_brackets.pop();
        self.pos += 1;
    }

    /// After an element: a comma, or the closing bracket (left for the caller to consume).
    fn separator(&mut self, close: u8) -> bool {
        self.skip_trivia();
        match self.peek() {
            Some(b',') => {
                self.pos += 1;
                true
            }
            Some(b) if b == close => true,
            _ => false,
        }
    }
}

/// Bytes of numbers and identifiers (and of anything else that is not RON punctuation, so the scan never stalls on
/// an unexpected character inside an atom). Non-ASCII bytes belong to atoms, which keeps spans on char boundaries.
fn is_atom_byte(b: u8) -> bool {
    !(b.is_ascii_whitespace() || b"()[]{},:\"'/#".contains(&b))
}

fn is_ident_start(b: u8) -> bool {
    b.is_ascii_alphabetic() || b == b'_' || b >= 0x80
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = r#"// header
#![enable(implicit_some)]
Scene(
    run: (time_step_s: 2e-6, /* inline */ seed: 7),
    gravity: Constant(9.81),
    materials: [(name: "sand", mu: -0.1)],
    walls: [
        Wall(shape: Polygon(corners_m: [(0.0, 0.0), (1.0, 0.0), (0.5, 1.0)])),
        Wall((shape: Square(side_m: 1.0))),
    ],
    view: Some((x_range_m: (0, 1))),
    extra: {"a": 1},
)"#;

    fn text_of(index: &SpanIndex, path: &str) -> String {
        TEXT[index.span_of(path).unwrap()].to_owned()
    }

    #[test]
    fn fields_elements_and_transparent_tuples_get_their_value_spans() {
        let index = SpanIndex::scan(TEXT);
        assert_eq!(text_of(&index, "run.time_step_s"), "2e-6");
        assert_eq!(text_of(&index, "run.seed"), "7");
        assert_eq!(text_of(&index, "gravity"), "9.81");
        assert_eq!(text_of(&index, "materials[0].mu"), "-0.1");
        assert_eq!(text_of(&index, "materials[0].name"), "\"sand\"");
        assert_eq!(text_of(&index, "walls[0].shape.corners_m[2]"), "(0.5, 1.0)");
        assert_eq!(text_of(&index, "walls[0].shape.corners_m[2].1"), "1.0");
        assert_eq!(text_of(&index, "walls[1].shape.side_m"), "1.0");
        assert_eq!(text_of(&index, "view.x_range_m"), "(0, 1)");
        assert_eq!(text_of(&index, "extra[\"a\"]"), "1");
    }

    #[test]
    fn defaulted_fields_point_at_the_nearest_written_key() {
        let index = SpanIndex::scan(TEXT);
        assert_eq!(text_of(&index, "materials[0].density_kg_m2"), "(");
        assert_eq!(text_of(&index, "run.end_time_s"), "run");
        assert_eq!(text_of(&index, "heating.window_s"), "S");
    }

    #[test]
    fn positions_map_back_to_paths() {
        let index = SpanIndex::scan(TEXT);
        let at = |needle: &str| index.path_at(TEXT.find(needle).unwrap()).map(str::to_owned);
        assert_eq!(at("-0.1").as_deref(), Some("materials[0].mu"));
        assert_eq!(at("mu:").as_deref(), Some("materials[0].mu"));
        assert_eq!(at("(0.5, 1.0)").as_deref(), Some("walls[0].shape.corners_m[2]"));
        assert_eq!(at("Scene").as_deref(), Some(""));
    }

    #[test]
    fn malformed_text_keeps_what_was_found() {
        let broken = "Scene(run: (seed: 7, time_step_s: ), walls: [";
        let index = SpanIndex::scan(broken);
        assert_eq!(&broken[index.span_of("run.seed").unwrap()], "7");
        assert_eq!(index.path_at(broken.find(")").unwrap()), Some("run.time_step_s"));
        for cut in 0..TEXT.len() {
            if TEXT.is_char_boundary(cut) {
                let _ = SpanIndex::scan(&TEXT[..cut]);
            }
        }
    }

    #[test]
    fn parent_paths() {
        assert_eq!(parent_path("a.b[2]"), Some("a.b"));
        assert_eq!(parent_path("a.b"), Some("a"));
        assert_eq!(parent_path("a"), Some(""));
        assert_eq!(parent_path(""), None);
    }
}
