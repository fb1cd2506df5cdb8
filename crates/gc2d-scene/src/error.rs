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
pub struct SceneError {
    /// What kind of mistake.
    pub kind: ErrorKind,
    /// The field path of the offending value, e.g. `walls[2].shape.corners_m[3]` (empty for the whole scene).
    pub path: String,
    /// What is wrong, without location.
    pub message: String,
    /// What to do about it, if there is something specific to say.
    pub help: Option<String>,
    /// Where in the file, when the scene was loaded from text and the path is written there.
    pub location: Option<Location>,
    /// Further errors found in the same pass.
    pub related: Vec<SceneError>,
    label: String,
    span: Option<Range<usize>>,
    source: Option<Arc<SourceText>>,
}

impl SceneError {
    /// An error at `path`, not yet located in a text.
    pub fn new(kind: ErrorKind, path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            kind,
            path: path.into(),
            message: message.into(),
            help: None,
            location: None,
            related: Vec::new(),
            label: "here".to_owned(),
            span: None,
            source: None,
        }
    }

    /// A value out of range (the most common semantic error).
    pub fn value(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Value, path, message)
    }

    /// Adds a help line.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// Sets the text under the underline.
    pub fn with_label(mut self, label: impl Into<String>) -> Self {
        self.label = label.into();
        self
    }

    /// Attaches a further error or note.
    pub fn with_related(mut self, related: SceneError) -> Self {
        self.related.push(related);
        self
    }

    /// Points the error at its path in `source` (when the path, or an ancestor, is written there).
    pub fn located(self, source: Option<&Arc<SourceText>>) -> Self {
        let Some(source) = source else { return self };
        let span = source.span_of(&self.path);
        self.at_span(source, span)
    }

    /// Points the error at a byte span of `source` (`None`: the file is still named, without a position).
    pub(crate) fn at_span(mut self, source: &Arc<SourceText>, span: Option<Range<usize>>) -> Self {
        self.location = span.as_ref().map(|span| {
            let (line, column) = source.line_column(span.start);
            Location { file: source.name().to_owned(), line, column }
        });
        self.span = span;
        self.source = Some(Arc::clone(source));
        self.related = std::mem::take(&mut self.related).into_iter().map(|e| e.located(Some(source))).collect();
        self
    }

    /// One error for a list of them: the first, with the others attached as related. `None` for an empty list.
    pub fn combine(mut errors: Vec<SceneError>) -> Option<SceneError> {
        if errors.is_empty() {
            return None;
        }
        let mut first = errors.remove(0);
        first.related.extend(errors);
        Some(first)
    }

    /// The underlined byte span in the source text, if located.
    pub fn span(&self) -> Option<Range<usize>> {
        self.span.clone()
    }

    /// The error rendered as miette's plain-text report (no colours, no Unicode box drawing), for logs and tests.
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
        if let Some(location) = &self.location {
            write!(f, "{location}: ")?;
        }
        if !self.path.is_empty() {
            write!(f, "`{}`: ", self.path)?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for SceneError {}

impl Diagnostic for SceneError {
    fn code<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        Some(Box::new(self.kind.code()))
    }

    fn help<'a>(&'a self) -> Option<Box<dyn fmt::Display + 'a>> {
        self.help.as_ref().map(|h| Box::new(h) as Box<dyn fmt::Display>)
    }

    fn source_code(&self) -> Option<&dyn SourceCode> {
        self.source.as_ref().map(|s| s.named() as &dyn SourceCode)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        let span = self.span.clone()?;
        let label = LabeledSpan::new_with_span(Some(self.label.clone()), span.start..span.end.max(span.start));
        Some(Box::new(std::iter::once(label)))
    }

    fn related<'a>(&'a self) -> Option<Box<dyn Iterator<Item = &'a dyn Diagnostic> + 'a>> {
        if self.related.is_empty() {
            return None;
        }
        Some(Box::new(self.related.iter().map(|e| e as &dyn Diagnostic)))
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
