//! The text a scene was loaded from: its name (the file path), the text itself, and the index of where each field's
//! value sits, so that errors found at any stage can point into the file.

use crate::error::Location;
use crate::spans::SpanIndex;
use miette::NamedSource;
use std::fmt;
use std::ops::Range;

/// A scene file's name and text, with its span index.
pub struct SourceText {
    name: String,
    text: String,
    index: SpanIndex,
    named: NamedSource<String>,
}

impl SourceText {
    /// Indexes `text`, loaded from `name` (a path or any label).
    pub fn new(name: &str, text: &str) -> Self {
        Self {
            name: name.to_owned(),
            text: text.to_owned(),
            index: SpanIndex::scan(text),
            named: NamedSource::new(name, text.to_owned()),
        }
    }

    /// The file name or label.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The whole text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The text as a miette source, named after the file.
    pub fn named(&self) -> &NamedSource<String> {
        &self.named
    }

    /// The byte span to underline for a field path (see [`SpanIndex::span_of`]).
    pub fn span_of(&self, path: &str) -> Option<Range<usize>> {
        self.index.span_of(path)
    }

    /// The field path at a byte offset (see [`SpanIndex::path_at`]).
    pub fn path_at(&self, offset: usize) -> Option<&str> {
        self.index.path_at(offset)
    }

    /// The span of the value that starts exactly at `offset`, if the index has one (the outermost such value).
    pub fn value_span_at(&self, offset: usize) -> Option<Range<usize>> {
        self.index.value_starting_at(offset)
    }

    /// The offsets of the brackets the text leaves open at its end, outermost first (see
    /// [`SpanIndex::unclosed_at_end`]).
    pub fn unclosed_at_end(&self) -> &[usize] {
        self.index.unclosed_at_end()
    }

    /// The byte offset of a 1-based line and column (columns count characters, as ron's do), clamped to the text.
    pub fn offset_of(&self, line: usize, column: usize) -> usize {
        let mut offset = 0;
        for _ in 1..line {
            match self.text[offset..].find('\n') {
                Some(newline) => offset += newline + 1,
                None => return self.text.len(),
            }
        }
        let line_text = &self.text[offset..];
        let line_end = line_text.find('\n').unwrap_or(line_text.len());
        line_text[..line_end]
            .char_indices()
            .nth(column.saturating_sub(1))
            .map_or(offset + line_end, |(i, _)| offset + i)
    }

    /// The file, line and column of a byte offset, as errors and warnings give them.
    pub fn location(&self, offset: usize) -> Location {
        let (line, column) = self.line_column(offset);
        Location { file: self.name.clone(), line, column }
    }

    /// The 1-based line and column (in characters) of a byte offset.
    pub fn line_column(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &self.text[..offset];
        let line = 1 + before.matches('\n').count();
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        (line, 1 + before[line_start..].chars().count())
    }
}

impl fmt::Debug for SourceText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("SourceText").field("name", &self.name).field("bytes", &self.text.len()).finish()
    }
}

impl PartialEq for SourceText {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name && self.text == other.text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_columns_round_trip_through_offsets() {
        let source = SourceText::new("a.ron", "ab\nμ: 1\n\nx");
        assert_eq!(source.offset_of(1, 1), 0);
        assert_eq!(source.offset_of(2, 1), 3);
        assert_eq!(source.offset_of(2, 2), 5);
        assert_eq!(source.line_column(5), (2, 2));
        assert_eq!(source.offset_of(4, 1), 10);
        assert_eq!(source.offset_of(9, 9), source.text().len());
        assert_eq!(source.offset_of(1, 99), 2);
        assert_eq!(source.line_column(4), (2, 1));
        assert_eq!(source.line_column(999), (4, 2));
    }
}
