//! Every command in the vocabulary is read by its object's converter: none is parsed and then silently dropped.

use crate::gsi::diagnostics::Diagnostics;
use crate::gsi::keywords::{Arity, ObjectKind};
use crate::gsi::lexer::lex;
use crate::gsi::reader::ObjectReader;
use crate::gsi::syntax::parse_objects;
use crate::gsi::{bodies, general, generators};

/// A valid parameter text for each command.
fn parameters(name: &str, arity: Arity) -> &'static str {
    match (name, arity) {
        ("G_TYPE", _) => "LINEAR",
        ("VIB_TYPE", _) => "TAPPING",
        ("GRID_TYPE", _) => "RECT",
        ("PART_RANDOM_POS_CORNERS", _) => "FULL",
        ("TYPE", _) => "REL",
        (_, Arity::Word) if name.contains("RANDOM") => "EQUAL",
        (_, Arity::Word) => "word",
        (_, Arity::Float) => "0.5",
        (_, Arity::FloatPair | Arity::FloatOneOrTwo) => "0.5 0.75",
        (_, Arity::Whole) => "7",
        (_, Arity::IntegerOneOrTwo) => "3 4",
        (_, Arity::Flag) => "",
    }
}

#[test]
fn every_command_of_every_object_is_consumed() {
    for kind in ObjectKind::ALL {
        let mut text = String::from("PARAMETER v1.4\n\n");
        if kind != ObjectKind::General {
            text.push_str(kind.name());
            text.push('\n');
        }
        for command in kind.commands() {
            text.push_str(&format!("{} {}\n", command.name, parameters(command.name, command.arity)));
        }
        if kind.has_corners() {
            text.push_str("CORNERS\n0 0\n1 0\n0 1\nEND\n");
        }
        let mut diagnostics = Diagnostics::default();
        let lexed = lex(&text, &mut diagnostics).expect("header");
        let objects = parse_objects(&lexed.statements, &mut diagnostics);
        let object = if kind == ObjectKind::General { objects.general } else { objects.named[0].clone() };
        let mut reader = ObjectReader::new(object, &mut diagnostics);
        match kind {
            ObjectKind::General => drop(general::read_general(&mut reader)),
            ObjectKind::Display => drop(general::read_display(&mut reader)),
            ObjectKind::Particle => drop(bodies::read_particle(&mut reader)),
            ObjectKind::Wall => drop(bodies::read_wall(&mut reader)),
            ObjectKind::GenerateBlock => drop(generators::read_block(&mut reader)),
            ObjectKind::DropSource => drop(generators::read_drop_source(&mut reader)),
        }
        assert!(reader.object.remaining().is_empty(), "{}: unread {:?}", kind.name(), reader.object.remaining());
        let unexpected: Vec<_> = diagnostics
            .errors
            .iter()
            .filter(|e| !matches!(e.kind, crate::gsi::GsiErrorKind::PistonAndVibration { .. }))
            .collect();
        assert!(unexpected.is_empty(), "{}: {unexpected:?}", kind.name());
    }
}
