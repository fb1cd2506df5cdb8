//! What the gsi reader reports: errors that stop the import, warnings that do not, and the `$` comments gc2d prints.
//! Every report names the 1-based line it concerns, so a caller can show it as `file:line: message`.

use std::fmt;

use thiserror::Error;

use super::PartSizeReading;

/// One problem that makes a gsi file unusable, at a line of the file.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("line {line}: {kind}")]
pub struct GsiError {
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub kind: GsiErrorKind,
}

impl GsiError {
    /// The error as `file:line: message`, the form editors and terminals link to the source.
    pub fn located(&self, file: &str) -> String {
        format!("{file}:{}: {}", self.line, self.kind)
    }
}

/// The kinds of gsi errors, each with the words the message needs.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GsiErrorKind {
    /// Line 1 is not `PARAMETER v1.4`.
    #[error("not a gsi file: line 1 must be `PARAMETER v1.4`, found `{found}`")]
    MissingHeader {
        /// Line 1 as found (shortened).
        found: String,
    },
    /// Line 1 names another version of the language.
    #[error("gsi version `{version}` is not supported; gc2d-rs reads `PARAMETER v1.4`")]
    UnsupportedVersion {
        /// The version word as written.
        version: String,
    },
    /// A line longer than gc2d's 1023-character buffer.
    #[error("line is {length} characters long; gsi allows at most {max}", max = super::lexer::MAX_LINE_LENGTH)]
    LineTooLong {
        /// Characters on the line.
        length: usize,
    },
    /// A word that is neither a command of the current object nor an object name.
    #[error("unknown keyword `{keyword}` in {object}{}", suggestion_text(suggestion))]
    UnknownKeyword {
        /// The word as written.
        keyword: String,
        /// The object being read.
        object: &'static str,
        /// The closest known keyword, if one is close.
        suggestion: Option<&'static str>,
    },
    /// A command of another object.
    #[error("`{keyword}` is a command of {}, not of {object}{}", belongs_to.join(" and "), general_hint(belongs_to))]
    WrongObject {
        /// The command as written.
        keyword: String,
        /// The object being read.
        object: &'static str,
        /// The objects that have this command.
        belongs_to: Vec<&'static str>,
    },
    /// `GENERAL` written out: it is implicit at the top of the file and cannot be re-entered.
    #[error("GENERAL cannot be named: its commands go at the top of the file, before the first object")]
    GeneralNamed,
    /// A parameter that should be a finite number is not.
    #[error("{keyword}: `{token}` is not a finite number")]
    BadNumber {
        /// The command.
        keyword: &'static str,
        /// The offending word.
        token: String,
    },
    /// A parameter that should be a non-negative whole number is not.
    #[error("{keyword}: `{token}` is not a non-negative whole number")]
    BadWholeNumber {
        /// The command.
        keyword: &'static str,
        /// The offending word.
        token: String,
    },
    /// A command without its (first) parameter.
    #[error("{keyword} needs a parameter ({expected})")]
    MissingParameter {
        /// The command.
        keyword: &'static str,
        /// What it expects.
        expected: &'static str,
    },
    /// A command with fewer or more numbers than it takes. gc2d set a missing second number to 0 and ignored extra
    /// ones (§9.2 rules 2 and 3); either silently changes the experiment, so gc2d-rs refuses both.
    #[error("{keyword}: {}", value_count_text(expected, values, found, not_a_number))]
    ValueCount {
        /// The command.
        keyword: &'static str,
        /// How many it takes: `(least, most)`.
        expected: (usize, usize),
        /// What its values are, e.g. `x y, m` (empty for one value).
        values: &'static str,
        /// The numbers written.
        found: Vec<String>,
        /// The word where a number was still needed, if there was one.
        not_a_number: Option<String>,
    },
    /// An option word that names no known choice.
    #[error("{keyword}: {message}")]
    BadOption {
        /// The command.
        keyword: &'static str,
        /// Why, listing the valid choices.
        message: String,
    },
    /// A CORNERS block interrupted by a command, an object or the end of the file before its END.
    #[error("CORNERS block opened at line {opened_at} has no END before {interrupted_by}")]
    UnclosedCorners {
        /// Line of the CORNERS keyword.
        opened_at: usize,
        /// What came instead of END.
        interrupted_by: String,
    },
    /// A line inside CORNERS … END that is not an `x y` pair.
    #[error("inside CORNERS … END each line must be a corner `x y`; found `{found}`")]
    BadCorner {
        /// The line's content.
        found: String,
    },
    /// CORNERS in an object that has no corners.
    #[error("{object} has no CORNERS (only PARTICLE and WALL have)")]
    CornersNotAllowed {
        /// The object being read.
        object: &'static str,
    },
    /// END outside a CORNERS block.
    #[error("END without CORNERS (the file ends with END_OF_FILE)")]
    StrayEnd,
    /// A second CORNERS block in the same object.
    #[error("a second CORNERS block in the same {object} (the first is at line {first})")]
    DuplicateCorners {
        /// The object being read.
        object: &'static str,
        /// Line of the first block.
        first: usize,
    },
    /// A PARTICLE or WALL without corners.
    #[error("{object} has no CORNERS … END block")]
    MissingCorners {
        /// The object.
        object: &'static str,
    },
    /// A corner list too short to be a polygon.
    #[error("CORNERS lists {count} corners; a polygon needs at least 3")]
    TooFewCorners {
        /// Corners found.
        count: usize,
    },
    /// Corners so far out that placing them (centroid, rotation, offset) overflows f64.
    #[error("the corners are too large to place: a coordinate overflows")]
    CornersOverflow,
    /// A wall with both PISTON_* and VIB_* commands.
    #[error("a wall cannot be a piston (line {piston_line}) and vibrate (line {vibration_line}) at the same time")]
    PistonAndVibration {
        /// First PISTON_* command.
        piston_line: usize,
        /// First VIB_* command.
        vibration_line: usize,
    },
    /// A grid that cannot be laid out: non-positive or non-finite spacing, non-finite range, or too many sites.
    #[error("GENERATE_BLOCK: {reason}")]
    BadGrid {
        /// What is wrong with the grid.
        reason: String,
    },
    /// A value the scene refuses (out of range, say), found by validating the converted scene and reported at the
    /// command that set it.
    #[error(
        "{keyword}{}: {message} (scene field `{field}`)",
        if *written { "" } else { " (not written, so gc2d's default)" }
    )]
    InvalidValue {
        /// The command that set the value, or the object where no single command did.
        keyword: &'static str,
        /// Whether the command is written (false: gc2d's default was used).
        written: bool,
        /// The scene's message, with the value as the scene holds it (SI units, counter-clockwise angles,
        /// semi-axes).
        message: String,
        /// The scene field, e.g. `materials[0].gamma`.
        field: String,
    },
    /// A value the scene format has no meaning for (found while converting to a scene).
    #[error("{keyword} cannot be converted to a scene: {reason}")]
    NotConvertible {
        /// The command.
        keyword: &'static str,
        /// Why.
        reason: String,
    },
}

/// "expected 2 values (x y, m), found 1: `0.11`" and the like.
fn value_count_text(
    expected: &(usize, usize),
    values: &str,
    found: &[String],
    not_a_number: &Option<String>,
) -> String {
    let (least, most) = *expected;
    let count = if least == most { least.to_string() } else { format!("{least} or {most}") };
    let plural = if most == 1 { "" } else { "s" };
    let what = if values.is_empty() { String::new() } else { format!(" ({values})") };
    let found_text =
        if found.is_empty() { "none".to_owned() } else { format!("{}: `{}`", found.len(), found.join(" ")) };
    let word = not_a_number.as_ref().map_or(String::new(), |word| format!(" (`{word}` is not a number)"));
    format!("expected {count} value{plural}{what}, found {found_text}{word}")
}

fn suggestion_text(suggestion: &Option<&'static str>) -> String {
    suggestion.map(|s| format!("; did you mean `{s}`?")).unwrap_or_default()
}

fn general_hint(belongs_to: &[&'static str]) -> &'static str {
    if belongs_to.contains(&"GENERAL") {
        " (GENERAL commands must come before the first object; GENERAL cannot be re-entered)"
    } else {
        ""
    }
}

/// All errors of one gsi file, in line order. The reader goes on after an error where it can, so one run names
/// every broken line.
#[derive(Debug, Clone, PartialEq, Error)]
pub struct GsiErrors(pub Vec<GsiError>);

impl fmt::Display for GsiErrors {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, error) in self.0.iter().enumerate() {
            if i > 0 {
                writeln!(f)?;
            }
            write!(f, "{error}")?;
        }
        Ok(())
    }
}

/// Something in a gsi file that gc2d-rs reads differently from what the file may intend, or ignores.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("line {line}: {kind}")]
pub struct GsiWarning {
    /// 1-based line number.
    pub line: usize,
    /// What happened.
    pub kind: GsiWarningKind,
}

/// The kinds of gsi warnings.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GsiWarningKind {
    /// MUE_DYNAMISCH is read but, as in gc2d, not used (erratum E41).
    #[error("MUE_DYNAMISCH is read but not used (gc2d documents it as unused; friction uses MUE_STATISCH)")]
    UnusedDynamicFriction,
    /// EMAIL is ignored: gc2d-rs sends no mail.
    #[error("EMAIL is ignored: gc2d-rs sends no mail")]
    EmailIgnored,
    /// A command given twice in one object; the later value counts.
    #[error("{keyword} is given again (first at line {first}); this later value is used")]
    Repeated {
        /// The command.
        keyword: &'static str,
        /// Line of the earlier one.
        first: usize,
    },
    /// Only the last DISPLAY object is used (§9.2).
    #[error("DISPLAY is replaced by the one at line {used}; only the last DISPLAY counts")]
    DisplayReplaced {
        /// Line of the DISPLAY that is used.
        used: usize,
    },
    /// Words after a command's values: gc2d ignores them (§9.2 rule 3, an inline comment without `#`), and so does
    /// gc2d-rs, but says so in case they are a typo.
    #[error(
        "{keyword}: the text after the parameters, `{text}`, is ignored (gc2d reads it as a comment; start comments with \
         `#` to silence this)"
    )]
    TrailingText {
        /// The command.
        keyword: &'static str,
        /// The ignored words, joined by single spaces.
        text: String,
    },
    /// The file is not UTF-8, so it is read as Latin-1; the warning is at the line of the first byte that is not
    /// UTF-8.
    #[error(
        "the file is not UTF-8 (byte {byte:#04x} at column {column} is not valid UTF-8), so it is read as Latin-1 \
         (ISO 8859-1), the encoding of old gc2d files: that byte is `{}`; check the file's non-ASCII characters",
        char::from(*byte)
    )]
    NotUtf8 {
        /// The first byte that is not UTF-8.
        byte: u8,
        /// Its column in the line, in characters from 1.
        column: usize,
    },
    /// A command that decides the experiment is not written, so gc2d's documented default is used.
    #[error("{object} has no {keyword}: gc2d's default {default} is used, so {consequence}")]
    DefaultUsed {
        /// The command.
        keyword: &'static str,
        /// The object that lacks it.
        object: &'static str,
        /// The default, as written in a gsi file, with its unit.
        default: &'static str,
        /// What the default means for the run.
        consequence: &'static str,
    },
    /// A corner list in clockwise order, re-oriented.
    #[error("CORNERS are clockwise; gc2d requires counter-clockwise, so the order is reversed")]
    ClockwiseCorners,
    /// COM given together with POSITION_ABSOLUT, which makes gc2d ignore it.
    #[error("COM is ignored because the PARTICLE has POSITION_ABSOLUT")]
    ComIgnored,
    /// G with one value but a G_TYPE that changes g: g stays at that value.
    #[error("G has one value, so g1 = g2 and G_TYPE {profile} changes nothing; write `G g1 g2` for a change")]
    GravityWithoutEndValue {
        /// The G_TYPE as written.
        profile: String,
    },
    /// Line 2 is free identification text, but this one looks like a command.
    #[error("line 2 is the identification text and is not read as a command, yet it starts with `{keyword}`")]
    IdentificationLooksLikeCommand {
        /// The command it starts with.
        keyword: &'static str,
    },
    /// No END_OF_FILE: the file may be truncated.
    #[error("no END_OF_FILE; the file may be truncated")]
    MissingEndOfFile,
    /// A System command (gc2d's checkpoint state), taken as written.
    #[error("{keyword} is a gc2d System command for checkpoints; it is taken as written")]
    SystemCommand {
        /// The command.
        keyword: &'static str,
    },
    /// Auto mode found that PART_SIZE must be full axes: read as semi-axes, a grid block would start overlapping.
    #[error(
        "read as semi-axes, PART_SIZE of this GENERATE_BLOCK gives particles up to {:.3} mm across on a grid whose \
         nearest sites are {:.3} mm apart, so neighbours would overlap by {:.0} % of their size; the file is therefore \
         read with PART_SIZE as full axes (semi-axes = PART_SIZE / 2) throughout; import with the semi-axes \
         convention to override",
        1e3 * semi_axes_diameter, 1e3 * spacing, 100.0 * (1.0 - spacing / semi_axes_diameter)
    )]
    PartSizeReadAsFullAxes {
        /// Largest particle size in the semi-axes reading, m.
        semi_axes_diameter: f64,
        /// Distance between nearest grid sites, m.
        spacing: f64,
    },
    /// A grid block whose particles overlap their neighbours at the grid spacing in the reading used.
    #[error(
        "particles of this GENERATE_BLOCK are up to {:.3} mm across (PART_SIZE read as {reading}) on a grid whose \
         nearest sites are {:.3} mm apart: neighbours overlap by up to {:.0} % of their size and the run starts \
         with strong repulsion",
        1e3 * diameter, 1e3 * spacing, 100.0 * (1.0 - spacing / diameter)
    )]
    GridNeighboursOverlap {
        /// Largest particle size in the reading used, m.
        diameter: f64,
        /// Distance between nearest grid sites, m.
        spacing: f64,
        /// How PART_SIZE was read.
        reading: PartSizeReading,
    },
    /// A command written in the file that the RON scene cannot express, so the converter leaves it out.
    #[error("{keyword} is not converted: {consequence}")]
    NotConverted {
        /// The command.
        keyword: &'static str,
        /// What leaving it out means for the run.
        consequence: String,
    },
}

/// A `$` comment: gc2d prints these to the screen when it reads the file, and so does the importer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Note {
    /// 1-based line number.
    pub line: usize,
    /// The text after `$`, trimmed.
    pub text: String,
}

/// Errors and warnings collected while reading one file.
#[derive(Debug, Default)]
pub(super) struct Diagnostics {
    pub errors: Vec<GsiError>,
    pub warnings: Vec<GsiWarning>,
}

impl Diagnostics {
    pub fn error(&mut self, line: usize, kind: GsiErrorKind) {
        self.errors.push(GsiError { line, kind });
    }

    pub fn warn(&mut self, line: usize, kind: GsiWarningKind) {
        self.warnings.push(GsiWarning { line, kind });
    }
}
