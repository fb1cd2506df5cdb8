//! Loading a scene: RON through serde (with `implicit_some` on by default, so optional values need no `Some(…)`), ron's
//! error positions turned into spans and field paths, then validation.

use crate::error::{ErrorKind, SceneError, suggest};
use crate::schema::Scene;
use crate::source::SourceText;
use ron::error::{Error as RonError, SpannedError};
use ron::extensions::Extensions;
use std::ops::Range;
use std::path::Path;
use std::sync::Arc;

impl Scene {
    /// Reads, parses and validates the scene file at `path`. The scene's name defaults to the file stem.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|e| {
            SceneError::new(ErrorKind::Io, "", format!("cannot read scene file {}: {e}", path.display()))
        })?;
        Scene::from_bytes(bytes, &path.display().to_string())
    }

    /// Parses and validates the scene file's contents `bytes` as [`Scene::from_str`] does; bytes that are not UTF-8
    /// are an error located at the first invalid one (byte offset, line, column and field).
    pub fn from_bytes(bytes: Vec<u8>, name: &str) -> Result<Scene, SceneError> {
        match String::from_utf8(bytes) {
            Ok(text) => Scene::from_str(&text, name),
            Err(error) => Err(invalid_utf8(&error, name)),
        }
    }

    /// Parses and validates scene `text`; `name` is the file name shown in errors (and, without directories and
    /// `.ron`, the scene's default name).
    ///
    /// Checks everything that can be checked without building the World: syntax, field names, types, ranges,
    /// material references and shapes. Time-step and initial-overlap checks need the built World; see
    /// [`Scene::build`].
    pub fn from_str(text: &str, name: &str) -> Result<Scene, SceneError> {
        // A byte-order mark, which some editors write at the start of UTF-8 files, is not part of the scene.
        let text = text.strip_prefix('\u{FEFF}').unwrap_or(text);
        let source = Arc::new(SourceText::new(name, text));
        let options = ron::Options::default().with_default_extension(Extensions::IMPLICIT_SOME);
        let mut scene: Scene = options.from_str(text).map_err(|e| from_ron_error(&e, &source))?;
        if scene.name.is_empty() {
            scene.name = default_name(name);
        }
        scene.source = Some(source);
        scene.validate()?;
        Ok(scene)
    }
}

impl Scene {
    /// The scene as RON text that [`Scene::from_str`] reads back to an equal scene (every field written but the
    /// optional sections and settings at their defaults, optional values without `Some(…)` under an `implicit_some`
    /// header). For tools that write scenes, such as the gsi importer.
    pub fn to_ron_string(&self) -> Result<String, ron::Error> {
        let config = ron::ser::PrettyConfig::new().struct_names(true).extensions(Extensions::IMPLICIT_SOME);
        ron::ser::to_string_pretty(self, config)
    }
}

/// A file that is not UTF-8, located at its first invalid byte: in the text read with invalid bytes replaced by U+FFFD
/// (identical up to that byte), so that the error names line, column and field like any other.
fn invalid_utf8(error: &std::string::FromUtf8Error, name: &str) -> SceneError {
    let bytes = error.as_bytes();
    let at = error.utf8_error().valid_up_to();
    let text = String::from_utf8_lossy(bytes);
    let source = Arc::new(SourceText::new(name, &text));
    let path = source.path_at(at).unwrap_or("").to_owned();
    let byte = bytes.get(at).copied().unwrap_or(0);
    SceneError::new(
        ErrorKind::Syntax,
        path,
        format!("invalid UTF-8 at byte {at} (0x{byte:02x}): scene files are UTF-8 text"),
    )
    .with_label("not UTF-8")
    .with_help("save the file as UTF-8 (Latin-1 letters such as ä or µ are single bytes that UTF-8 writes as two)")
    .at_span(&source, Some(at..at + char::REPLACEMENT_CHARACTER.len_utf8()))
}

/// The file name without directories and a `.ron` ending.
fn default_name(file: &str) -> String {
    let base = file.rsplit(['/', '\\']).next().unwrap_or(file);
    base.strip_suffix(".ron").unwrap_or(base).to_owned()
}

/// Turns ron's error (a code and a line/column span) into a located scene error with its field path.
fn from_ron_error(error: &SpannedError, source: &Arc<SourceText>) -> SceneError {
    let start = source.offset_of(error.span.start.line, error.span.start.col);
    let end = source.offset_of(error.span.end.line, error.span.end.col).max(start);
    let text = source.text();
    let start = start + text[start..end].len() - text[start..end].trim_start().len();
    let span = if start < end {
        start..end
    } else {
        let next = start + text[start..].len() - text[start..].trim_start().len();
        source.value_span_at(next).unwrap_or_else(|| widen_to_token(text, next..next))
    };
    if let Some(error) = unclosed_at_end(&error.code, source, span.end.max(end)) {
        return error;
    }
    let path = source.path_at(span.start).unwrap_or("").to_owned();
    if let Some((scene_error, span)) = misread_number(&error.code, text, span.clone(), &path) {
        return scene_error.at_span(source, Some(span));
    }
    let mut scene_error = describe(&error.code, path);
    let written = &text[span.clone()];
    if scene_error.kind() == ErrorKind::Type
        && !scene_error.message().contains("found")
        && written.len() <= 40
        && !written.contains('\n')
    {
        let message = format!("{}, found `{}`", scene_error.message(), visible(written));
        scene_error = scene_error.with_message(message);
    }
    scene_error.at_span(source, Some(span))
}

/// A text that ends with brackets still open, which ron reports at the end as a missing comma (or the end of RON), told
/// as the brackets left open, located at the innermost one (with the name written before it): `Scene(run: (seed: 1)`
/// → "the file ends before `Scene(` opened at 1:1 is closed". `None` for other errors, and where the error (ending at
/// `end`) is not at the end of the text.
fn unclosed_at_end(code: &RonError, source: &Arc<SourceText>, end: usize) -> Option<SceneError> {
    let at_end_codes = matches!(
        code,
        RonError::ExpectedComma
            | RonError::Eof
            | RonError::ExpectedStructLikeEnd
            | RonError::ExpectedArrayEnd
            | RonError::ExpectedMapEnd
    );
    let (text, open) = (source.text(), source.unclosed_at_end());
    let &innermost = open.last()?;
    if !at_end_codes || !text[end.min(text.len())..].trim().is_empty() {
        return None;
    }
    let named = |offset: usize| {
        let written = opening_written(text, offset);
        let (line, column) = source.line_column(written.start);
        format!("`{}` opened at {line}:{column}", &text[written])
    };
    let listed: Vec<String> = open.iter().rev().map(|&offset| named(offset)).collect();
    let closing: String = open.iter().rev().map(|&offset| closing_bracket(text.as_bytes()[offset])).collect();
    let (message, help) = match listed.as_slice() {
        [one] => (format!("the file ends before {one} is closed"), format!("close it with `{closing}`")),
        [inner @ .., outer] => (
            format!("the file ends before {} and {outer} are closed", inner.join(", ")),
            format!("close them with `{closing}`, innermost first, where their values end"),
        ),
        [] => return None,
    };
    let span = opening_written(text, innermost);
    let path = source.path_at(span.start).unwrap_or("").to_owned();
    let error = SceneError::new(ErrorKind::Syntax, path, message).with_label("not closed").with_help(help);
    Some(error.at_span(source, Some(span)))
}

/// The opening bracket at `offset` as written, with the name right before it if it has one (`Scene(`, `Wall(`, `[`).
fn opening_written(text: &str, offset: usize) -> Range<usize> {
    let before = &text[..offset];
    let name_start = before
        .char_indices()
        .rev()
        .find(|&(_, c)| !(c.is_alphanumeric() || c == '_'))
        .map_or(0, |(i, c)| i + c.len_utf8());
    name_start..offset + 1
}

/// The bracket that closes `open`.
fn closing_bracket(open: u8) -> char {
    match open {
        b'[' => ']',
        b'{' => '}',
        _ => ')',
    }
}

/// The errors ron gives for a number it read in pieces, told as what was written (with the number's span): a negative
/// whole number, whose sign ron leaves out of "out of bounds, found `1`"; a fraction where a whole number belongs,
/// which ron reports as "expected comma" at its point or as an invalid digit at its exponent; a number where a variant belongs (`gravity: 9.81`), which ron
/// takes for an identifier and suggests writing `r#9.81`. `None` for every other error.
fn misread_number(code: &RonError, text: &str, span: Range<usize>, path: &str) -> Option<(SceneError, Range<usize>)> {
    match code {
        RonError::IntegerOutOfBounds => {
            let number = number_around(text, span.start);
            let written = &text[number.clone()];
            let message = if written.starts_with('-') {
                format!("found `{written}`: this field takes a whole number ≥ 0")
            } else {
                format!("found `{written}`: too large a whole number for this field")
            };
            Some((SceneError::new(ErrorKind::Type, path, message).with_label("out of range"), number))
        }
        RonError::InvalidIntegerDigit { digit: 'e' | 'E', base: 10 } | RonError::ExpectedComma => {
            // ron stops an integer at its point ("expected comma" there) or at its exponent's `e`.
            let stopped_at_point = text.as_bytes().get(span.start) == Some(&b'.')
                && span.start > 0
                && text.as_bytes()[span.start - 1].is_ascii_digit();
            if matches!(code, RonError::ExpectedComma) && !stopped_at_point {
                return None;
            }
            let number = number_around(text, span.start);
            let written = &text[number.clone()];
            written.parse::<f64>().ok()?;
            let message = format!("expected a whole number, found `{written}`");
            Some((SceneError::new(ErrorKind::Type, path, message).with_label("not a whole number"), number))
        }
        RonError::SuggestRawIdentifier(identifier) if identifier.parse::<f64>().is_ok() => {
            let help = if path == "gravity" {
                format!("a constant g is written `gravity: Constant({identifier})`")
            } else {
                "write one of the field's variants, `Name(…)`; docs/scene-format.md lists them".to_owned()
            };
            let message = format!("expected one of this field's variants, found the number `{identifier}`");
            let error = SceneError::new(ErrorKind::Type, path, message).with_label("a number").with_help(help);
            Some((error, span))
        }
        _ => None,
    }
}

/// The span of the number literal (digits, sign, point, exponent, `_`) around byte `at` of `text`.
fn number_around(text: &str, at: usize) -> Range<usize> {
    let bytes = text.as_bytes();
    let is_part = |b: u8| b.is_ascii_digit() || matches!(b, b'.' | b'e' | b'E' | b'+' | b'-' | b'_');
    let mut start = at.min(bytes.len());
    while start > 0 && is_part(bytes[start - 1]) {
        start -= 1;
    }
    let mut end = at.min(bytes.len());
    while end < bytes.len() && is_part(bytes[end]) {
        end += 1;
    }
    start..end
}

/// `written` with control characters (a NUL, a tab) shown as `U+0000`, so that a message does not print them as
/// blanks.
fn visible(written: &str) -> String {
    written.chars().map(|c| if c.is_control() { format!("U+{:04X}", u32::from(c)) } else { c.to_string() }).collect()
}

/// An empty span grows to the word (or the single character) at its start, so there is something to underline.
fn widen_to_token(text: &str, span: Range<usize>) -> Range<usize> {
    if span.end > span.start {
        return span;
    }
    let start = span.start.min(text.len());
    let word_end = text[start..].find(|c: char| !(c.is_alphanumeric() || c == '_')).map_or(text.len(), |i| start + i);
    if word_end > start {
        return start..word_end;
    }
    let next = text[start..].chars().next().map_or(0, char::len_utf8);
    start..start + next
}

/// The message, kind, path and help for one ron error code found at `path`.
fn describe(code: &RonError, path: String) -> SceneError {
    let list = |names: &[&str]| names.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ");
    let did_you_mean = |found: &str, expected: &[&str]| {
        suggest(found, expected).map_or(String::new(), |s| format!(", did you mean `{s}`?"))
    };
    match code {
        RonError::NoSuchStructField { expected, found, outer } => {
            let owner = outer.as_deref().map_or(String::new(), |o| format!(" of `{o}`"));
            SceneError::new(
                ErrorKind::UnknownName,
                path,
                format!("unknown field `{found}`{}", did_you_mean(found, expected)),
            )
            .with_help(format!("the fields{owner} are {}", list(expected)))
            .with_label("unknown field")
        }
        RonError::NoSuchEnumVariant { expected, found, outer } => {
            let owner = outer.as_deref().map_or(String::new(), |o| format!(" of `{o}`"));
            SceneError::new(
                ErrorKind::UnknownName,
                path,
                format!("unknown variant `{found}`{}", did_you_mean(found, expected)),
            )
            .with_help(format!("the variants{owner} are {}", list(expected)))
            .with_label("unknown variant")
        }
        RonError::ExpectedDifferentStructName { expected, found } => SceneError::new(
            ErrorKind::UnknownName,
            path,
            format!("expected a `{expected}` here, found `{found}`{}", did_you_mean(found, &[expected])),
        )
        .with_help(format!("write `{expected}(…)` or just `(…)`")),
        RonError::MissingStructField { field, outer } => {
            let owner = outer.as_deref().map_or(String::new(), |o| format!(" in `{o}`"));
            let full_path = crate::spans::field_path(&path, field);
            SceneError::new(ErrorKind::MissingField, full_path, format!("missing field `{field}`{owner}"))
                .with_help("this field has no default; see docs/scene-format.md")
                .with_label("this structure needs it")
        }
        RonError::DuplicateStructField { field, .. } => {
            SceneError::new(ErrorKind::Syntax, path, format!("field `{field}` is given twice"))
        }
        RonError::InvalidValueForType { expected, found } => {
            SceneError::new(ErrorKind::Type, path, format!("expected {expected}, found {found}"))
                .with_label("wrong type")
        }
        RonError::ExpectedDifferentLength { expected, found } => {
            SceneError::new(ErrorKind::Type, path, format!("expected {expected}, found {found} elements"))
                .with_label("wrong length")
        }
        RonError::ExpectedStructLikeEnd => match path.rsplit_once('.') {
            Some((tuple, index)) if !index.is_empty() && index.bytes().all(|b| b.is_ascii_digit()) => {
                SceneError::new(ErrorKind::Type, tuple, format!("this tuple takes {index} values, found more"))
                    .with_label("one value too many")
            }
            _ => SceneError::new(ErrorKind::Syntax, path, lowercase_first(&code.to_string())),
        },
        RonError::ExpectedFloat
        | RonError::ExpectedInteger
        | RonError::IntegerOutOfBounds
        | RonError::ExpectedBoolean
        | RonError::ExpectedString
        | RonError::ExpectedArray
        | RonError::ExpectedMap
        | RonError::ExpectedOption
        | RonError::ExpectedUnit
        | RonError::ExpectedStructLike
        | RonError::ExpectedNamedStructLike(_) => {
            SceneError::new(ErrorKind::Type, path, lowercase_first(&code.to_string())).with_label("wrong type")
        }
        // Where a variant belongs and `(…)` is written without one: a wall entry written as a particle may be.
        RonError::ExpectedIdentifier => {
            let help = match wall_variants() {
                variants if is_wall_entry(&path) && !variants.is_empty() => format!(
                    "a wall entry names its kind before its parentheses: {} (docs/scene-format.md)",
                    variants.iter().map(|v| format!("`{v}(…)`")).collect::<Vec<_>>().join(", ")
                ),
                _ => "a variant is written with its name before its parentheses, `Name(…)`; docs/scene-format.md \
                      lists each field's variants"
                    .to_owned(),
            };
            SceneError::new(ErrorKind::Type, path, lowercase_first(&code.to_string()))
                .with_label("wrong type")
                .with_help(help)
        }
        other => SceneError::new(ErrorKind::Syntax, path, lowercase_first(&other.to_string())),
    }
}

/// Whether `path` is an entry of the scene's `walls` list (`walls[2]`).
fn is_wall_entry(path: &str) -> bool {
    path.strip_prefix("walls[")
        .and_then(|rest| rest.strip_suffix(']'))
        .is_some_and(|i| i.bytes().all(|b| b.is_ascii_digit()))
}

/// The variant names of a wall entry, as serde knows them (read from its refusal of a name that is none).
fn wall_variants() -> &'static [&'static str] {
    match ron::from_str::<crate::schema::WallItem>("NotAWallKind") {
        Err(ron::error::SpannedError { code: RonError::NoSuchEnumVariant { expected, .. }, .. }) => expected,
        _ => &[],
    }
}

fn lowercase_first(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or(String::new(), |c| c.to_lowercase().chain(chars).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_names_drop_directories_and_the_extension() {
        assert_eq!(default_name("scenes/pile.ron"), "pile");
        assert_eq!(default_name("C:\\x\\silo.ron"), "silo");
        assert_eq!(default_name("inline"), "inline");
    }

    #[test]
    fn empty_spans_widen_to_the_word() {
        let text = "a: gamm, b";
        assert_eq!(widen_to_token(text, 3..3), 3..7);
        assert_eq!(widen_to_token(text, 7..7), 7..8);
        assert_eq!(widen_to_token(text, 10..10), 10..10);
        assert_eq!(widen_to_token(text, 0..2), 0..2);
    }
}
