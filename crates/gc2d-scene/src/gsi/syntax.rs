//! Groups the statements of a gsi file into objects (reference §9.2): GENERAL implicitly at the top, then one object
//! per object name, each a list of commands with parsed parameters and at most one CORNERS … END block.

use gc2d_geometry::DVec2;

use super::diagnostics::{Diagnostics, GsiErrorKind, GsiWarningKind};
use super::keywords::{Arity, CORNERS, Command, END, ObjectKind, is_any_keyword, objects_with_command, suggestion};
use super::lexer::Statement;

/// The parameters of one command, parsed according to its [`Arity`].
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Args<'a> {
    /// One or two floats; `given` says how many were written (a missing second one is 0).
    Numbers { values: [f64; 2], given: usize },
    /// A non-negative integer.
    Whole(u64),
    /// Two integers (a missing second one is 0).
    Integers([i64; 2]),
    /// One word, case preserved.
    Word(&'a str),
    /// A command without parameters.
    Flag,
    /// The corners of a CORNERS … END block, as written; `complete` is false when a line of the block was refused
    /// (and reported), so the list is known to be short.
    Corners { corners: Vec<DVec2>, complete: bool },
}

/// One command of an object: its canonical name, line and parameters.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Entry<'a> {
    pub name: &'static str,
    pub line: usize,
    pub args: Args<'a>,
}

/// An object as read: its kind, the line of its name (1 for GENERAL) and its commands.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct RawObject<'a> {
    pub kind: ObjectKind,
    pub line: usize,
    entries: Vec<Entry<'a>>,
}

impl<'a> RawObject<'a> {
    fn new(kind: ObjectKind, line: usize) -> Self {
        Self { kind, line, entries: Vec::new() }
    }

    /// Adds a command; a repeated one replaces the earlier (as gc2d overwrites) with a warning, a repeated CORNERS
    /// block is an error.
    fn insert(&mut self, entry: Entry<'a>, diagnostics: &mut Diagnostics) {
        match self.entries.iter_mut().find(|existing| existing.name == entry.name) {
            Some(existing) if entry.name == CORNERS => diagnostics
                .error(entry.line, GsiErrorKind::DuplicateCorners { object: self.kind.name(), first: existing.line }),
            Some(existing) => {
                diagnostics.warn(entry.line, GsiWarningKind::Repeated { keyword: entry.name, first: existing.line });
                *existing = entry;
            }
            None => self.entries.push(entry),
        }
    }

    /// Removes and returns the command named `name` (canonical spelling), if the object has it.
    pub fn take(&mut self, name: &str) -> Option<Entry<'a>> {
        let index = self.entries.iter().position(|entry| entry.name == name)?;
        Some(self.entries.remove(index))
    }

    /// The line of the first of `names` present, without removing it.
    pub fn first_line_of(&self, names: &[&str]) -> Option<usize> {
        self.entries.iter().filter(|entry| names.contains(&entry.name)).map(|entry| entry.line).min()
    }

    /// Commands not yet taken.
    #[cfg(test)]
    pub fn remaining(&self) -> &[Entry<'a>] {
        &self.entries
    }
}

/// The objects of a file: GENERAL (implicit, line 1) and the named objects in file order.
#[derive(Debug)]
pub(super) struct Objects<'a> {
    pub general: RawObject<'a>,
    pub named: Vec<RawObject<'a>>,
}

/// Reads all statements into objects. Errors are collected and the offending line skipped, so every broken line of
/// a file is named in one pass.
pub(super) fn parse_objects<'a>(statements: &[Statement<'a>], diagnostics: &mut Diagnostics) -> Objects<'a> {
    let mut general = RawObject::new(ObjectKind::General, 1);
    let mut named: Vec<RawObject<'a>> = Vec::new();
    let mut next = 0;
    while let Some(statement) = statements.get(next) {
        next += 1;
        let Some(&first) = statement.words.first() else { continue };
        let current = named.last_mut().unwrap_or(&mut general);
        if first.eq_ignore_ascii_case(CORNERS) {
            let (corners, complete, after) = read_corners(statements, next, statement.line, diagnostics);
            next = after;
            if current.kind.has_corners() {
                let entry = Entry { name: CORNERS, line: statement.line, args: Args::Corners { corners, complete } };
                current.insert(entry, diagnostics);
            } else {
                diagnostics.error(statement.line, GsiErrorKind::CornersNotAllowed { object: current.kind.name() });
            }
        } else if first.eq_ignore_ascii_case(END) {
            diagnostics.error(statement.line, GsiErrorKind::StrayEnd);
        } else if first.eq_ignore_ascii_case(ObjectKind::General.name()) {
            diagnostics.error(statement.line, GsiErrorKind::GeneralNamed);
        } else if let Some(kind) = ObjectKind::from_name(first) {
            named.push(RawObject::new(kind, statement.line));
        } else if let Some(command) = current.kind.command(first) {
            if command.system {
                diagnostics.warn(statement.line, GsiWarningKind::SystemCommand { keyword: command.name });
            }
            if let Some(args) = parse_args(command, statement, diagnostics) {
                current.insert(Entry { name: command.name, line: statement.line, args }, diagnostics);
            }
        } else {
            let object = current.kind.name();
            let belongs_to = objects_with_command(first, current.kind);
            let kind = if belongs_to.is_empty() {
                GsiErrorKind::UnknownKeyword {
                    keyword: first.to_string(),
                    object,
                    suggestion: suggestion(first, current.kind),
                }
            } else {
                GsiErrorKind::WrongObject { keyword: first.to_string(), object, belongs_to }
            };
            diagnostics.error(statement.line, kind);
        }
    }
    Objects { general, named }
}

/// Reads corner lines from `statements[start..]` up to END. Returns the corners, whether every line was a corner
/// and the block was closed, and the index of the first statement after the block. A keyword before END ends the
/// block with an error and is left for the caller.
fn read_corners(
    statements: &[Statement<'_>],
    start: usize,
    opened_at: usize,
    diagnostics: &mut Diagnostics,
) -> (Vec<DVec2>, bool, usize) {
    let mut corners = Vec::new();
    let mut complete = true;
    let mut next = start;
    loop {
        let Some(statement) = statements.get(next) else {
            let interrupted_by = "the end of the file".to_string();
            diagnostics.error(opened_at, GsiErrorKind::UnclosedCorners { opened_at, interrupted_by });
            return (corners, false, next);
        };
        let first = statement.words.first().copied().unwrap_or("");
        if first.eq_ignore_ascii_case(END) {
            return (corners, complete, next + 1);
        }
        if let Some(keyword) = is_any_keyword(first) {
            let interrupted_by = format!("`{keyword}` at line {}", statement.line);
            diagnostics.error(statement.line, GsiErrorKind::UnclosedCorners { opened_at, interrupted_by });
            return (corners, false, next);
        }
        let coordinate = |index: usize| statement.words.get(index).and_then(|word| parse_number(word));
        match (coordinate(0), coordinate(1)) {
            (Some(x), Some(y)) if x.is_finite() && y.is_finite() => corners.push(DVec2::new(x, y)),
            _ => {
                diagnostics.error(statement.line, GsiErrorKind::BadCorner { found: statement.text() });
                complete = false;
            }
        }
        next += 1;
    }
}

/// A float as C's `strtod` reads it, except that NaN is refused. "inf" is accepted (gc2d's ∞ defaults).
pub(super) fn parse_number(word: &str) -> Option<f64> {
    word.parse::<f64>().ok().filter(|value| !value.is_nan())
}

/// Parses the parameters of `command` from `statement`'s words after the first. Words after the parameters are a
/// comment (§9.2 rule 3). Returns `None` after recording an error.
fn parse_args<'a>(command: &Command, statement: &Statement<'a>, diagnostics: &mut Diagnostics) -> Option<Args<'a>> {
    let keyword = command.name;
    let line = statement.line;
    let parameters = &statement.words[1..];
    if command.arity == Arity::Flag {
        return Some(Args::Flag);
    }
    let Some(&first) = parameters.first() else {
        diagnostics.error(line, GsiErrorKind::MissingParameter { keyword, expected: command.arity.describe() });
        return None;
    };
    let bad_number = |token: &str| GsiErrorKind::BadNumber { keyword, token: token.to_string() };
    match command.arity {
        Arity::Float => match parse_number(first) {
            Some(value) => Some(Args::Numbers { values: [value, 0.0], given: 1 }),
            None => {
                diagnostics.error(line, bad_number(first));
                None
            }
        },
        Arity::FloatPair => {
            let Some(value) = parse_number(first) else {
                diagnostics.error(line, bad_number(first));
                return None;
            };
            let (second, given) = second_parameter(keyword, parameters.get(1), line, parse_number, diagnostics);
            Some(Args::Numbers { values: [value, second], given })
        }
        Arity::Whole => match first.parse::<u64>() {
            Ok(value) => Some(Args::Whole(value)),
            Err(_) => {
                diagnostics.error(line, GsiErrorKind::BadWholeNumber { keyword, token: first.to_string() });
                None
            }
        },
        Arity::IntegerPair => {
            let parse_integer = |word: &str| word.parse::<i64>().ok();
            let Some(value) = parse_integer(first) else {
                diagnostics.error(line, bad_number(first));
                return None;
            };
            let (second, _) = second_parameter(keyword, parameters.get(1), line, parse_integer, diagnostics);
            Some(Args::Integers([value, second]))
        }
        Arity::Word => Some(Args::Word(first)),
        Arity::Flag => Some(Args::Flag),
    }
}

/// The second parameter of a two-parameter command and how many parameters were given. Missing, it is 0 (§9.2
/// rule 2); a word that is not a number is taken as the start of a comment, with a warning, and the value is 0.
fn second_parameter<T: Default>(
    keyword: &'static str,
    word: Option<&&str>,
    line: usize,
    parse: impl Fn(&str) -> Option<T>,
    diagnostics: &mut Diagnostics,
) -> (T, usize) {
    match word {
        None => (T::default(), 1),
        Some(word) => match parse(word) {
            Some(value) => (value, 2),
            None => {
                diagnostics.warn(line, GsiWarningKind::SecondParameterNotANumber { keyword, token: word.to_string() });
                (T::default(), 1)
            }
        },
    }
}
