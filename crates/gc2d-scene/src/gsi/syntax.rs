//! Groups the statements of a gsi file into objects (reference §9.2): GENERAL implicitly at the top, then one object
//! per object name, each a list of commands with parsed parameters and at most one CORNERS … END block.

use gc2d_geometry::DVec2;

use super::diagnostics::{Diagnostics, GsiErrorKind, GsiWarningKind};
use super::keywords::{Arity, CORNERS, Command, END, ObjectKind, is_any_keyword, objects_with_command, suggestion};
use super::lexer::Statement;

/// The parameters of one command, parsed according to its [`Arity`].
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Args<'a> {
    /// One or two floats; `given` says how many were written (a second one not written is 0).
    Numbers { values: [f64; 2], given: usize },
    /// A non-negative integer.
    Whole(u64),
    /// One or two integers (a second one not written is 0).
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
        let coordinate = |index: usize| statement.words.get(index).and_then(|word| parse_number(word).ok());
        match (coordinate(0), coordinate(1)) {
            (Some(x), Some(y)) => corners.push(DVec2::new(x, y)),
            _ => {
                diagnostics.error(statement.line, GsiErrorKind::BadCorner { found: statement.text() });
                complete = false;
            }
        }
        next += 1;
    }
}

/// Why a word is not a usable number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum NumberError {
    /// Not a number at all (a comment word, a typo).
    NotANumber,
    /// A number, but infinite or NaN (`inf`, `nan`, `1e400`), which no gsi value may be. gc2d's own "∞" is the
    /// finite `BIG_NUMBER`.
    NotFinite,
}

/// A finite float in the notation C's `strtod` reads.
pub(super) fn parse_number(word: &str) -> Result<f64, NumberError> {
    match word.parse::<f64>() {
        Ok(value) if value.is_finite() => Ok(value),
        Ok(_) => Err(NumberError::NotFinite),
        Err(_) => Err(NumberError::NotANumber),
    }
}

/// An integer of either sign.
fn parse_integer(word: &str) -> Result<i64, NumberError> {
    word.parse::<i64>().map_err(|_| NumberError::NotANumber)
}

/// Parses the parameters of `command` from `statement`'s words after the first. A command takes a fixed number
/// of values (one or two for the few documented with one); fewer or more numbers are an error naming the values
/// found. Words after the values are a comment (§9.2 rule 3), accepted with a warning. Returns `None` after
/// recording an error.
fn parse_args<'a>(command: &Command, statement: &Statement<'a>, diagnostics: &mut Diagnostics) -> Option<Args<'a>> {
    let keyword = command.name;
    let line = statement.line;
    let parameters = &statement.words[1..];
    let (least, most) = command.arity.counts();
    let taken = match command.arity {
        Arity::Flag => 0,
        Arity::Word => {
            if parameters.is_empty() {
                let expected = command.arity.describe();
                diagnostics.error(line, GsiErrorKind::MissingParameter { keyword, expected });
                return None;
            }
            1
        }
        _ => {
            // Numbers in any notation count, so that `inf` or `1.5` for a whole number is named as such below.
            let numbers = parameters.iter().take_while(|word| word.parse::<f64>().is_ok()).count();
            if let (0, Some(&first)) = (numbers, parameters.first()) {
                let token = first.to_string();
                let kind = if command.arity == Arity::Whole {
                    GsiErrorKind::BadWholeNumber { keyword, token }
                } else {
                    GsiErrorKind::BadNumber { keyword, token }
                };
                diagnostics.error(line, kind);
                return None;
            }
            if numbers < least || numbers > most {
                let found = parameters[..numbers].iter().map(|word| word.to_string()).collect();
                let not_a_number = (numbers < least).then(|| parameters.get(numbers)).flatten().map(|w| w.to_string());
                let kind = GsiErrorKind::ValueCount {
                    keyword,
                    expected: (least, most),
                    values: command.values,
                    found,
                    not_a_number,
                };
                diagnostics.error(line, kind);
                return None;
            }
            numbers
        }
    };
    let args = typed_args(command, &parameters[..taken], line, diagnostics)?;
    if let Some(rest) = parameters.get(taken..).filter(|rest| !rest.is_empty()) {
        diagnostics.warn(line, GsiWarningKind::TrailingText { keyword, text: rest.join(" ") });
    }
    Some(args)
}

/// The typed value of `values`, which has as many words as `command` takes (numbers for numeric commands).
fn typed_args<'a>(
    command: &Command,
    values: &[&'a str],
    line: usize,
    diagnostics: &mut Diagnostics,
) -> Option<Args<'a>> {
    let keyword = command.name;
    let mut bad = |kind: GsiErrorKind| {
        diagnostics.error(line, kind);
        None
    };
    match command.arity {
        Arity::Flag => Some(Args::Flag),
        Arity::Word => values.first().map(|&word| Args::Word(word)),
        Arity::Float | Arity::FloatPair | Arity::FloatOneOrTwo => {
            let mut numbers = [0.0; 2];
            for (slot, &word) in numbers.iter_mut().zip(values) {
                match parse_number(word) {
                    Ok(value) => *slot = value,
                    Err(_) => return bad(GsiErrorKind::BadNumber { keyword, token: word.to_string() }),
                }
            }
            Some(Args::Numbers { values: numbers, given: values.len() })
        }
        Arity::Whole => {
            let word = values.first().copied().unwrap_or("");
            match word.parse::<u64>() {
                Ok(value) => Some(Args::Whole(value)),
                Err(_) => bad(GsiErrorKind::BadWholeNumber { keyword, token: word.to_string() }),
            }
        }
        Arity::IntegerOneOrTwo => {
            let mut integers = [0; 2];
            for (slot, &word) in integers.iter_mut().zip(values) {
                match parse_integer(word) {
                    Ok(value) => *slot = value,
                    Err(_) => return bad(GsiErrorKind::BadNumber { keyword, token: word.to_string() }),
                }
            }
            Some(Args::Integers(integers))
        }
    }
}
