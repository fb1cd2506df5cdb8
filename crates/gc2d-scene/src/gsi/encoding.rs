//! The text of a gsi file: UTF-8, or, for a file that is not, Latin-1 (ISO 8859-1), the encoding old gc2d files
//! with German umlauts in their comments were written in. Latin-1 maps each byte to the character of the same
//! number, so every file decodes and keeps its lines.

use std::borrow::Cow;

use super::diagnostics::{GsiWarning, GsiWarningKind};

/// Decodes a gsi file's `bytes`: as UTF-8 when they are valid UTF-8, otherwise as Latin-1, with a warning at the line
/// of the first byte that is not UTF-8.
pub fn decode_gsi(bytes: &[u8]) -> (Cow<'_, str>, Option<GsiWarning>) {
    match std::str::from_utf8(bytes) {
        Ok(text) => (Cow::Borrowed(text), None),
        Err(error) => {
            let at = error.valid_up_to();
            let before = &bytes[..at];
            let line = before.iter().filter(|&&byte| byte == b'\n').count() + 1;
            let line_start = before.iter().rposition(|&byte| byte == b'\n').map_or(0, |i| i + 1);
            // The line up to the byte is valid UTF-8, so the column counts its characters.
            let column = std::str::from_utf8(&before[line_start..]).map_or(at - line_start, |s| s.chars().count()) + 1;
            let byte = bytes[at];
            let text: String = bytes.iter().copied().map(char::from).collect();
            (Cow::Owned(text), Some(GsiWarning { line, kind: GsiWarningKind::NotUtf8 { byte, column } }))
        }
    }
}
