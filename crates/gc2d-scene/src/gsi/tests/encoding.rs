//! Legacy gsi files are often Latin-1 (German umlauts in comments): a file that is not UTF-8 is read as Latin-1 with
//! a warning at the first line that is not UTF-8 (QA report 1, section 6), instead of being refused without a line.

use super::PISTON;
use crate::gsi::{GsiWarningKind, ImportOptions, decode_gsi, parse_gsi_bytes};

/// The thesis's example with line 3 replaced by a comment with `ü` written as the Latin-1 byte 0xFC.
fn latin1_piston() -> Vec<u8> {
    let mut bytes = Vec::new();
    for (i, line) in PISTON.lines().enumerate() {
        if i == 2 {
            bytes.extend_from_slice(b"$ Kolben dr\xfccke Teilchen zusammen");
        } else {
            bytes.extend_from_slice(line.as_bytes());
        }
        bytes.push(b'\n');
    }
    bytes
}

#[test]
fn a_latin1_file_is_read_with_a_warning_at_its_first_latin1_line() {
    let import = parse_gsi_bytes(&latin1_piston(), &ImportOptions::default()).expect("read as Latin-1");
    assert_eq!(import.notes[0].line, 3);
    assert_eq!(import.notes[0].text, "Kolben drücke Teilchen zusammen");
    assert_eq!(import.scene.walls.len(), 4);
    let warning = import.warnings.iter().find(|w| matches!(w.kind, GsiWarningKind::NotUtf8 { .. }));
    let warning = warning.expect("a warning about the encoding");
    assert_eq!(warning.line, 3);
    assert_eq!(
        warning.to_string(),
        "line 3: the file is not UTF-8 (byte 0xfc at column 12 is not valid UTF-8), so it is read as Latin-1 \
         (ISO 8859-1), the encoding of old gc2d files: that byte is `ü`; check the file's non-ASCII characters"
    );
}

#[test]
fn utf8_files_are_read_as_utf8_without_a_warning() {
    let text = PISTON.replace("# A piston", "# Ein Kolben drückt");
    let import = parse_gsi_bytes(text.as_bytes(), &ImportOptions::default()).expect("UTF-8");
    assert!(!import.warnings.iter().any(|w| matches!(w.kind, GsiWarningKind::NotUtf8 { .. })));
    let (decoded, warning) = decode_gsi(text.as_bytes());
    assert_eq!(decoded, text);
    assert!(warning.is_none());
}

#[test]
fn every_byte_decodes_and_errors_keep_their_lines() {
    let all: Vec<u8> = (0..=255u8).collect();
    let (decoded, warning) = decode_gsi(&all);
    assert_eq!(decoded.chars().count(), 256);
    assert!(decoded.chars().enumerate().all(|(i, c)| c as u32 == i as u32));
    assert_eq!(warning.map(|w| (w.line, w.kind)), Some((2, GsiWarningKind::NotUtf8 { byte: 0x80, column: 118 })));
    // An error after the Latin-1 line is still at its own line.
    let bytes = latin1_piston();
    let text = String::from_utf8_lossy(&bytes).replace("        Gamma               0.5", "        Gamma 0.5 0.9");
    let mut bytes = text.into_bytes();
    let position = bytes.windows(3).position(|w| w == "\u{fffd}".as_bytes()).expect("replacement character");
    bytes.splice(position..position + 3, [0xfc]);
    let errors = parse_gsi_bytes(&bytes, &ImportOptions::default()).expect_err("GAMMA has two values");
    assert_eq!(errors.0.len(), 1);
    assert_eq!(errors.0[0].line, 7);
}
