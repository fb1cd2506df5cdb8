//! Tests of the gsi reader: the thesis's example file, every error class, the language rules, the conversions to
//! gc2d-rs conventions, and robustness against mutated input.

mod completeness;
mod conventions;
mod convert;
mod encoding;
mod errors;
mod language;
mod mutations;
mod piston;
mod ranges;
mod values;

use super::{GsiErrors, GsiImport, GsiWarningKind, ImportOptions, parse_gsi};

/// The thesis's example (App. B.1.8), as in the shared fixtures.
const PISTON: &str = include_str!("../testdata/piston.gsi");

/// Reads `text` with default options, panicking with the errors if it fails.
fn read(text: &str) -> GsiImport {
    match parse_gsi(text, &ImportOptions::default()) {
        Ok(import) => import,
        Err(errors) => panic!("unexpected errors:\n{errors}"),
    }
}

/// Reads `text` expecting failure.
fn read_errors(text: &str) -> GsiErrors {
    match parse_gsi(text, &ImportOptions::default()) {
        Ok(import) => panic!("expected errors, got {:?}", import.scene),
        Err(errors) => errors,
    }
}

/// A file with the header, an empty identification line, `body`, and END_OF_FILE.
fn file(body: &str) -> String {
    format!("PARAMETER v1.4\n\n{body}\nEND_OF_FILE\n")
}

/// Whether the import warned with a kind matching `predicate` at `line`.
fn warned(import: &GsiImport, line: usize, predicate: impl Fn(&GsiWarningKind) -> bool) -> bool {
    import.warnings.iter().any(|warning| warning.line == line && predicate(&warning.kind))
}
