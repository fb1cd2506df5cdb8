//! Putting a parameter's value into a scene: the base scene is written out as RON with every field (the text a run
//! directory's `scene.ron` holds), the value of the field at the parameter's path is replaced in that text, found
//! through the scene crate's own span index (the paths scene errors use), and the result is loaded by the scene
//! loader, so that every generated scene is read and checked like a scene file.
//!
//! A field the written scene leaves out (an optional value that is unset, such as `run.max_impact_speed_m_s`) is
//! inserted into the structure that owns it; the loader then refuses a name the structure does not have, with its
//! suggestion of the nearest field.

use gc2d_scene::spans::SpanIndex;
use std::ops::Range;

/// Where a parameter's path lands in a scene text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Target {
    /// The value written at this span is replaced.
    Value(Range<usize>),
    /// `field: value, ` is inserted at this offset (just inside the owning structure's parenthesis).
    Insert {
        /// Byte offset.
        at: usize,
        /// The field name.
        field: String,
    },
}

/// Why a path does not lead into the scene.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PathProblem {
    /// What is wrong.
    pub message: String,
    /// What to do.
    pub help: Option<String>,
    /// Where the first unwritten field would go, if its owner is a structure: putting any value there lets the scene
    /// loader say whether the structure has such a field at all (and which name was meant).
    pub probe: Option<Target>,
}

/// The place `path` names in the scene `text`.
pub fn target(text: &str, path: &str) -> Result<Target, PathProblem> {
    let index = SpanIndex::scan(text);
    if let Some(span) = written_at(&index, path) {
        return Ok(Target::Value(span));
    }
    // The longest written ancestor and the first segment below it that is not written.
    let segments = segments(path);
    let mut written = 0;
    for k in 1..segments.len() {
        if written_at(&index, &segments[k - 1].0).is_some() {
            written = k;
        }
    }
    let (parent, parent_span) = match written {
        0 => (String::new(), root_span(text)),
        k => (segments[k - 1].0.clone(), written_at(&index, &segments[k - 1].0)),
    };
    let (missing_path, missing) = &segments[written];
    let within = if parent.is_empty() { "the scene".to_owned() } else { format!("`{parent}`") };
    match missing {
        Segment::Index(i) => {
            let count = (0..).take_while(|k| written_at(&index, &format!("{parent}[{k}]")).is_some()).count();
            Err(PathProblem {
                message: format!(
                    "`{path}`: {within} has {count} element{}, so no [{i}]",
                    if count == 1 { "" } else { "s" }
                ),
                help: Some("list elements count from 0".into()),
                probe: None,
            })
        }
        Segment::Field(field) => {
            let open = parent_span.and_then(|span| struct_open(text, span));
            match open {
                Some(at) if written + 1 == segments.len() => Ok(Target::Insert { at, field: field.clone() }),
                Some(at) => Err(PathProblem {
                    message: format!(
                        "`{path}`: {within} does not write `{missing_path}` (it is unset or has no such field)"
                    ),
                    help: Some(format!(
                        "write `{missing_path}` in the base scene, or make `{missing_path}` itself the parameter with \
                         whole values"
                    )),
                    probe: Some(Target::Insert { at, field: field.clone() }),
                }),
                None => Err(PathProblem {
                    message: format!("`{path}`: {within} is not a structure with fields"),
                    help: Some(format!("the parameter can be `{parent}` itself, with whole values")),
                    probe: None,
                }),
            }
        }
    }
}

/// Refuses a path that is not a field path as scene errors write it (`mill.rotor.rpm`, `materials[0].mu`): field
/// names of letters, digits and `_` joined by `.`, each followed by any number of `[index]`. The error says what is
/// wrong, to follow "`path` is not a field path: ".
pub fn check_syntax(path: &str) -> Result<(), String> {
    if path.is_empty() {
        return Err("the path is empty".into());
    }
    let mut rest = path;
    let mut at_start = true;
    loop {
        let end = rest.find(['.', '[', ']']).unwrap_or(rest.len());
        let field = &rest[..end];
        if field.is_empty() {
            return Err(if at_start { "empty field name at the start" } else { "empty field name after `.`" }.into());
        }
        if !field.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
            return Err(format!("`{field}`: a field name has only letters, digits and `_`"));
        }
        rest = &rest[end..];
        while let Some(inner) = rest.strip_prefix('[') {
            let Some(close) = inner.find(']') else { return Err("`[` without its closing `]`".into()) };
            let index = &inner[..close];
            if index.is_empty() || !index.bytes().all(|b| b.is_ascii_digit()) {
                return Err(format!("`[{index}]`: an index is a number, counted from 0"));
            }
            rest = &inner[close + 1..];
            match rest.chars().next() {
                None | Some('.' | '[') => {}
                Some(c) => return Err(format!("expected `.` or `[` after `]`, found `{c}`")),
            }
        }
        match rest.chars().next() {
            None => return Ok(()),
            Some('.') => {
                rest = &rest[1..];
                at_start = false;
            }
            Some(c) => return Err(format!("`{c}` without its opening `[`")),
        }
    }
}

/// `text` with `value` put at `target`.
pub fn put(text: &str, target: &Target, value: &str) -> String {
    match target {
        Target::Value(span) => format!("{}{value}{}", &text[..span.start], &text[span.end..]),
        Target::Insert { at, field } => format!("{}{field}: {value}, {}", &text[..*at], &text[*at..]),
    }
}

/// The span of the value written at exactly `path` (not an ancestor's fallback span).
fn written_at(index: &SpanIndex, path: &str) -> Option<Range<usize>> {
    let span = index.span_of(path)?;
    (index.path_at(span.start) == Some(path)).then_some(span)
}

/// The root value: the whole text after any `#![enable(…)]` attributes, from its first `(` or identifier.
fn root_span(text: &str) -> Option<Range<usize>> {
    let mut from = 0;
    while let Some(attribute) = text[from..].trim_start().strip_prefix("#![") {
        let close = attribute.find(']')?;
        from = text.len() - attribute.len() + close + 1;
    }
    let start = from + text[from..].find(|c: char| c == '(' || c.is_ascii_alphabetic())?;
    Some(start..text.len())
}

/// The offset just after the `(` that opens a structure written at `span` (`(…)` or `Name(…)`), if it is one whose
/// first entry is a field (`name: …`) or which is empty.
fn struct_open(text: &str, span: Range<usize>) -> Option<usize> {
    let value = &text[span.clone()];
    let name_end = value.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(value.len());
    let rest = &value[name_end..];
    let inner = rest.strip_prefix('(')?;
    let first = inner.trim_start();
    let is_fields = first.starts_with(')') || {
        let key_end = first.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(first.len());
        key_end > 0 && first[key_end..].trim_start().starts_with(':')
    };
    is_fields.then_some(span.start + name_end + 1)
}

/// A path's segments, each with the path up to and including it.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Segment {
    Field(String),
    Index(String),
}

fn segments(path: &str) -> Vec<(String, Segment)> {
    let mut out = Vec::new();
    let mut so_far = String::new();
    for (k, part) in path.split('.').enumerate() {
        let (field, indices) = part.split_once('[').map_or((part, ""), |(f, rest)| (f, rest));
        if !field.is_empty() {
            if k > 0 {
                so_far.push('.');
            }
            so_far.push_str(field);
            out.push((so_far.clone(), Segment::Field(field.to_owned())));
        }
        for index in indices.split('[').filter(|s| !s.is_empty()) {
            let index = index.trim_end_matches(']');
            so_far.push_str(&format!("[{index}]"));
            out.push((so_far.clone(), Segment::Index(index.to_owned())));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = "#![enable(implicit_some)]\nScene(\n    name: \"m\",\n    run: Run(\n        seed: 1,\n        end_time_s: 1.0,\n    ),\n    \
                         materials: [\n        Material(name: \"steel\", mu: 0.2),\n    ],\n    gravity: Constant(9.81),\n)";

    #[test]
    fn written_fields_are_replaced() {
        let t = target(SCENE, "run.seed").unwrap();
        assert_eq!(put(SCENE, &t, "7").lines().nth(4), Some("        seed: 7,"));
        let t = target(SCENE, "materials[0].mu").unwrap();
        assert!(put(SCENE, &t, "0.5").contains("Material(name: \"steel\", mu: 0.5)"));
    }

    #[test]
    fn unwritten_fields_are_inserted_into_their_structure() {
        let t = target(SCENE, "run.time_step_s").unwrap();
        assert!(put(SCENE, &t, "1e-5").contains("run: Run(time_step_s: 1e-5, \n        seed: 1,"));
        let t = target(SCENE, "materials[0].gamma").unwrap();
        assert!(put(SCENE, &t, "0.3").contains("Material(gamma: 0.3, name:"));
        let t = target(SCENE, "description").unwrap();
        assert!(put(SCENE, &t, "\"d\"").contains("\nScene(description: \"d\", \n"));
    }

    #[test]
    fn malformed_paths_say_what_is_wrong() {
        for path in ["run.seed", "materials[0].mu", "a[1][2].b_3", "mill"] {
            assert_eq!(check_syntax(path), Ok(()), "{path}");
        }
        let error = |path: &str| check_syntax(path).unwrap_err();
        assert_eq!(error("materials[0]mu"), "expected `.` or `[` after `]`, found `m`");
        assert_eq!(error("materials[0]."), "empty field name after `.`");
        assert_eq!(error("a..b"), "empty field name after `.`");
        assert_eq!(error("[0].mu"), "empty field name at the start");
        assert_eq!(error("a]"), "`]` without its opening `[`");
        assert_eq!(error("a[0]]"), "expected `.` or `[` after `]`, found `]`");
        assert_eq!(error("a[0"), "`[` without its closing `]`");
        assert_eq!(error("a[-1]"), "`[-1]`: an index is a number, counted from 0");
        assert_eq!(error("a-b"), "`a-b`: a field name has only letters, digits and `_`");
        assert_eq!(error(""), "the path is empty");
    }

    #[test]
    fn paths_that_lead_nowhere_say_where_they_stop() {
        let e = target(SCENE, "materials[3].mu").unwrap_err();
        assert_eq!(e.message, "`materials[3].mu`: `materials` has 1 element, so no [3]");
        let e = target(SCENE, "mill.rotor.rpm").unwrap_err();
        assert!(e.message.contains("the scene does not write `mill`"), "{}", e.message);
        let e = target(SCENE, "materials.mu").unwrap_err();
        assert!(e.message.contains("`materials` is not a structure"), "{}", e.message);
    }
}
