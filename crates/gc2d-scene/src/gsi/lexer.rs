//! Splits a gsi file into lines of words (reference §9.2): checks the `PARAMETER v1.4` header and the line length,
//! takes line 2 as the identification text, collects `$` comments, drops `#` comments and blank lines, and stops at
//! END_OF_FILE.

use super::diagnostics::{Diagnostics, GsiError, GsiErrorKind, Note};
use super::keywords::END_OF_FILE;

/// gc2d reads lines into a 1024-byte buffer, so a line may hold at most 1023 characters.
pub const MAX_LINE_LENGTH: usize = 1023;

/// The header word and the only supported version.
const HEADER: &str = "PARAMETER";
const VERSION: &str = "v1.4";

/// A non-blank line after comments are removed: its 1-based number and its words.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Statement<'a> {
    pub line: usize,
    pub words: Vec<&'a str>,
}

impl Statement<'_> {
    /// The line's words joined by single spaces, for messages.
    pub fn text(&self) -> String {
        self.words.join(" ")
    }
}

/// A gsi file split into its parts.
#[derive(Debug)]
pub(super) struct Lexed<'a> {
    /// Line 2, verbatim (without the line break).
    pub identification: &'a str,
    /// The statements from line 3 on, up to END_OF_FILE.
    pub statements: Vec<Statement<'a>>,
    /// The `$` comments.
    pub notes: Vec<Note>,
    /// Line of END_OF_FILE, if present.
    pub end_of_file: Option<usize>,
}

/// Splits `text`. A missing or wrong header is fatal (the file is not gsi, so nothing else would make sense);
/// over-long lines are reported in `diagnostics` and skipped.
pub(super) fn lex<'a>(text: &'a str, diagnostics: &mut Diagnostics) -> Result<Lexed<'a>, GsiError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = text.split('\n').map(|line| line.strip_suffix('\r').unwrap_or(line)).enumerate();
    let header = lines.next().map_or("", |(_, line)| line);
    check_header(header)?;
    if header.chars().count() > MAX_LINE_LENGTH {
        diagnostics.error(1, GsiErrorKind::LineTooLong { length: header.chars().count() });
    }
    let mut identification = lines.next().map_or("", |(_, line)| line);
    if identification.chars().count() > MAX_LINE_LENGTH {
        diagnostics.error(2, GsiErrorKind::LineTooLong { length: identification.chars().count() });
        identification = "";
    }
    let mut lexed = Lexed { identification, statements: Vec::new(), notes: Vec::new(), end_of_file: None };
    for (index, line) in lines {
        let number = index + 1;
        let length = line.chars().count();
        if length > MAX_LINE_LENGTH {
            diagnostics.error(number, GsiErrorKind::LineTooLong { length });
            continue;
        }
        let trimmed = line.trim_start();
        if let Some(note) = trimmed.strip_prefix('$') {
            lexed.notes.push(Note { line: number, text: note.trim().to_string() });
            continue;
        }
        let content = trimmed.split('#').next().unwrap_or("");
        let words: Vec<&str> = content.split_ascii_whitespace().collect();
        match words.first() {
            None => {}
            Some(first) if first.eq_ignore_ascii_case(END_OF_FILE) => {
                lexed.end_of_file = Some(number);
                break;
            }
            Some(_) => lexed.statements.push(Statement { line: number, words }),
        }
    }
    Ok(lexed)
}

/// Line 1 must be `PARAMETER v1.4` (any case, any spacing).
fn check_header(line: &str) -> Result<(), GsiError> {
    let words: Vec<&str> = line.split_ascii_whitespace().collect();
    match words.as_slice() {
        [header, version, ..] if header.eq_ignore_ascii_case(HEADER) => {
            if version.eq_ignore_ascii_case(VERSION) {
                Ok(())
            } else {
                Err(GsiError { line: 1, kind: GsiErrorKind::UnsupportedVersion { version: version.to_string() } })
            }
        }
        _ => {
            let found: String = line.chars().take(40).collect();
            Err(GsiError { line: 1, kind: GsiErrorKind::MissingHeader { found } })
        }
    }
}
