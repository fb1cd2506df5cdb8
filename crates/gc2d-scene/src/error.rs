//! Scene errors as miette diagnostics: what is wrong, at which field path, where in which file, and (for misspelled
//! names) what was probably meant.

use crate::source::SourceText;
use miette::{Diagnostic, LabeledSpan, SourceCode};
use std::fmt;
use std::ops::Range;
use std::sync::Arc;

/// What kind of mistake an error reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// The file could not be read.
    Io,
    /// The text is not valid RON.
    Syntax,
    /// A field, variant or structure name that the format does not have.
    UnknownName,
    /// A required field is missing.
    MissingField,
    /// A value of the wrong type (a string for a number, a list of the wrong length, …).
    Type,
    /// A value out of its range, a name that refers to nothing, or an inadmissible shape.
    Value,
    /// The time step is above the stable bound.
    TimeStep,
    /// Initial bodies overlap more than the run allows.
    Overlap,
}

impl ErrorKind {
    /// A stable diagnostic code, `gc2d_scene::<kind>`.
    fn code(self) -> &'static str {
        match self {
            ErrorKind::Io => "gc2d_scene::io",
            ErrorKind::Syntax => "gc2d_scene::syntax",
            ErrorKind::UnknownName => "gc2d_scene::unknown_name",
            ErrorKind::MissingField => "gc2d_scene::missing_field",
            ErrorKind::Type => "gc2d_scene::type",
            ErrorKind::Value => "gc2d_scene::value",
            ErrorKind::TimeStep => "gc2d_scene::time_step",
            ErrorKind::Overlap => "gc2d_scene::overlap",
        }
    }
}

/// Longest line, in bytes, that a rendered error shows as its source snippet. miette's renderer pads its underlines
/// with format widths, which panic above 65,535 columns; a line of 4,096 bytes is at most 16,384 columns wide even
/// if it were all tabs. An error on (or next to) a longer line is shown without the snippet; its message still says
/// `file:line:column`.
pub const MAX_SNIPPET_LINE_BYTES: usize = 4096;

/// Most errors one report lists: the first and up to 19 related ones. A scene with more (a generated file with a
/// mistake in every entry) reports these and one last line counting the rest, so that `check` stays quick and its
/// output readable.
pub const MAX_REPORTED_ERRORS: usize = 20;

/// Where an error points: file, 1-based line and column (characters).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file name the scene was loaded from.
    pub file: String,
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.column)
    }
}

/// An error in a scene. Its `Display` reads `file:line:column: `path`: message`; as a miette diagnostic it also
/// shows the offending text underlined, a help line and any further errors found in the same pass.
#[derive(Debug, Clone)]
pub struct SceneError(Box<Details>);

#[derive(Debug, Clone)]
struct Details {
    kind: ErrorKind,
    path: String,
    message: String,
    help: Option<String>,
    location: Option<Location>,
    related: Vec<SceneError>,
    label: String,
    span: Option<Range<usize>>,
    source: Option<Arc<SourceText>>,
    more: Option<MoreErrors>,
}

/// The last line of a report cut at [`MAX_REPORTED_ERRORS`]: how many errors were found but not listed.
#[derive(Debug, Clone)]
struct MoreErrors(usize);

impl fmt::Display for MoreErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (count, s) = (self.0, if self.0 == 1 { "" } else { "s" });
        write!(f, "… and {count} more error{s} not shown (only the first {MAX_REPORTED_ERRORS} are listed)")
    }
}

impl std::error::Error for MoreErrors {}

impl Diagnostic for MoreErrors {}

impl SceneError {
    /// An error at `path`, not yet located in a text.
    pub fn new(kind: ErrorKind, path: impl Into<String>, message: impl Into<String>) -> Self {
        Self(Box::new(Details {
            kind,
            path: path.into(),
            message: message.into(),
            help: None,
            location: None,
            related: Vec::new(),
            label: "here".to_owned(),
            span: None,
            source: None,
            more: None,
        }))
    }

    /// A value out of range (the most common semantic error).
    pub fn value(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Value, path, message)
    }

    /// What kind of mistake.
    pub fn kind(&self) -> ErrorKind {
        self.0.kind
    }

    /// The field path of the offending value, e.g. `walls[2].shape.corners_m[3]` (empty for the whole scene).
    pub fn path(&self) -> &str {
        &self.0.path
    }

    /// What is wrong, without location.
    pub fn message(&self) -> &str {
        &self.0.message
    }

    /// What to do about it, if there is something specific to say.
    pub fn help_text(&self) -> Option<&str> {
        self.0.help.as_deref()
    }

    /// Where in the file, when the scene was loaded from text and the path (or an ancestor) is written there.
    pub fn location(&self) -> Option<&Location> {
        self.0.location.as_ref()
    }

    /// Further errors found in the same pass, or notes that belong to this one.
    pub fn related_errors(&self) -> &[SceneError] {
        &self.0.related
    }

    /// How many further errors were found but left out of [`Self::related_errors`] (see [`MAX_REPORTED_ERRORS`]).
    pub fn omitted_errors(&self) -> usize {
        self.0.more.as_ref().map_or(0, |more| more.0)
    }

    /// The underlined byte span in the source text, if located.
    pub fn span(&self) -> Option<Range<usize>> {
        self.0.span.clone()
    }

    /// Adds a help line.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.0.help = Some(help.into());
        self
    }

    /// Sets the text under the underline.
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.0.label = label.into();
        self
    }

    /// Attaches a further error or note.
    pub fn with_related(mut self, related: SceneError) -> Self {
        self.0.related.push(related);
        self
    }

    /// Replaces the message (keeping everything else).
    pub(crate) fn with_message(mut self, message: String) -> Self {
        self.0.message = message;
        self
    }

    /// Points the error at its path in `source` (when the path, or an ancestor, is written there).
    pub fn located(self, source: Option<&Arc<SourceText>>) -> Self {
        let Some(source) = source else { return self };
        let span = source.span_of(&self.0.path);
        self.at_span(source, span)
    }

    /// Points the error at a byte span of `source` (`None`: the file is still named, without a position).
    pub(crate) fn at_span(mut self, source: &Arc<SourceText>, span: Option<Range<usize>>) -> Self {
        let details = &mut self.0;
        details.location = span.as_ref().map(|span| source.location(span.start));
        details.span = span;
        details.source = Some(Arc::clone(source));
        details.related = std::mem::take(&mut details.related).into_iter().map(|e| e.located(Some(source))).collect();
        self
    }

    /// True when the located span and the line of context miette shows on each side are short enough to render.
    fn snippet_fits(&self) -> bool {
        let (Some(span), Some(source)) = (&self.0.span, &self.0.source) else { return false };
        let text = source.text();
        let (start, end) = (span.start.min(text.len()), span.end.min(text.len()));
        // From the start of the line before the span's first line to the end of the line after its last one.
        let first = text[..start].rfind('\n').map_or(0, |i| text[..i].rfind('\n').map_or(0, |j| j + 1));
        let last = text[end..].find('\n').map_or(text.len(), |i| {
            let next = end + i + 1;
            text[next..].find('\n').map_or(text.len(), |j| next + j)
        });
        text.get(first..last).is_some_and(|lines| lines.split('\n').all(|line| line.len() <= MAX_SNIPPET_LINE_BYTES))
    }

    /// One error for a list of them: the first, with the others attached as related. `None` for an empty list. At
    /// most [`MAX_REPORTED_ERRORS`] are kept (with the related ones the first may already have); the report ends
    /// with a line counting the rest.
    pub fn combine(errors: Vec<SceneError>) -> Option<SceneError> {
        let mut errors = errors.into_iter();
        let mut first = errors.next()?;
        let room = MAX_REPORTED_ERRORS.saturating_sub(1 + first.0.related.len());
        first.0.related.extend(errors.by_ref().take(room));
        let omitted = errors.len() + first.omitted_errors();
        first.0.more = (omitted > 0).then_some(MoreErrors(omitted));
        Some(first)
    }

    /// The error with `count` more errors counted in its report's last line (found but never made).
    pub(crate) fn with_omitted(mut self, count: usize) -> Self {
        let omitted = self.omitted_errors() + count;
        self.0.more = (omitted > 0).then_some(MoreErrors(omitted));
        self
    }

    /// The error rendered as miette's plain-text report (no colours), for logs and tests.
    pub fn render_plain(&self) -> String {
        let mut out = String::new();
        let handler = miette::GraphicalReportHandler::new_themed(miette::GraphicalTheme::unicode_nocolor())
            .with_width(120)
            .with_links(false);
        if handler.render_report(&mut out, self).is_err() {
            return self.to_string();
        }
        out
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let details = &self.0;
        if let Some(location) = &details.location {
            write!(f, "{location}: ")?;
        }
        if !details.path.is_empty() {
            write!(f, "`{}`: ", details.path)?;
        }
        f.write_str(&details.message)
    }
}

impl std::error::Error for SceneError {}

impl Diagnostic for SceneError {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        Some(Box::new(self.0.kind.code()))
    }

    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.0.help.as_ref().map(|h| Box::new(h) as Box<dyn fmt::Display>)
    }

    fn source_code(&self) -> Option<&dyn SourceCode> {
        if !self.snippet_fits() {
            return None;
        }
        self.0.source.as_ref().map(|s| s.named() as &dyn SourceCode)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        if !self.snippet_fits() {
            return None;
        }
        let span = self.0.span.clone()?;
        let label = LabeledSpan::new_with_span(Some(self.0.label.clone()), span.start..span.end.max(span.start));
        Some(Box::new(std::iter::once(label)))
    }

    fn related<'a>(&'a self) -> Option<Box<dyn Iterator<Item = &'a dyn Diagnostic> + 'a>> {
        if self.0.related.is_empty() && self.0.more.is_none() {
            return None;
        }
        let more = self.0.more.iter().map(|m| m as &dyn Diagnostic);
        Some(Box::new(self.0.related.iter().map(|e| e as &dyn Diagnostic).chain(more)))
    }
}

/// The candidate that `found` most probably misspells: an exact match ignoring case and `_`, else the closest by
/// Jaro–Winkler similarity if it is at least 0.8.
pub fn suggest<'a>(found: &str, candidates: &[&'a str]) -> Option<&'a str> {
    let normal = |s: &str| s.to_ascii_lowercase().replace('_', "");
    if let Some(exact) = candidates.iter().find(|c| normal(c) == normal(found)) {
        return Some(exact);
    }
    candidates
        .iter()
        .map(|c| (strsim::jaro_winkler(&normal(found), &normal(c)), *c))
        .filter(|(score, _)| *score >= 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions_catch_typos_and_case_but_not_strangers() {
        let fields = ["name", "density_kg_m2", "youngs_modulus_n_m", "gamma", "mu", "cohesion_n_m"];
        assert_eq!(suggest("gamm", &fields), Some("gamma"));
        assert_eq!(suggest("density", &fields), Some("density_kg_m2"));
        assert_eq!(suggest("Youngs_Modulus_N_M", &fields), Some("youngs_modulus_n_m"));
        assert_eq!(suggest("temperature", &fields), None);
        assert_eq!(suggest("RAND1", &["Regular", "Rand1", "Rand2"]), Some("Rand1"));
        assert_eq!(suggest("fcc_gauss", &["Fcc", "FccGauss"]), Some("FccGauss"));
    }
}
