//! Typed access to the commands of one raw object: each getter takes the command out of the object (so a test can
//! check that every command is read), applies gc2d's default when it is absent, and records where the value came
//! from.

use std::fmt::Display;
use std::str::FromStr;

use gc2d_engine::TimeWindow;
use gc2d_geometry::DVec2;

use super::diagnostics::{Diagnostics, GsiErrorKind, GsiWarningKind};
use super::keywords::CORNERS;
use super::scene::{Bounds, Sourced};
use super::syntax::{Args, Entry, RawObject};

/// A raw object being converted, with the diagnostics its conversion reports to.
pub(super) struct ObjectReader<'a, 'd> {
    pub object: RawObject<'a>,
    pub diagnostics: &'d mut Diagnostics,
}

impl<'a, 'd> ObjectReader<'a, 'd> {
    pub fn new(object: RawObject<'a>, diagnostics: &'d mut Diagnostics) -> Self {
        Self { object, diagnostics }
    }

    /// The line of the object's name.
    pub fn line(&self) -> usize {
        self.object.line
    }

    fn default<T>(&self, value: T) -> Sourced<T> {
        Sourced::default_for(value, self.object.line)
    }

    /// The numbers of a float command with how many were written, or `None` if it is absent.
    pub fn numbers(&mut self, name: &str) -> Option<(usize, [f64; 2], usize)> {
        match self.object.take(name) {
            Some(entry) => match entry.args {
                Args::Numbers { values, given } => Some((entry.line, values, given)),
                _ => None,
            },
            None => None,
        }
    }

    /// A one-float command.
    pub fn float(&mut self, name: &str, default: f64) -> Sourced<f64> {
        match self.numbers(name) {
            Some((line, [value, _], _)) => Sourced::written(value, line),
            None => self.default(default),
        }
    }

    /// A one-float angle that gc2d counts clockwise, returned counter-clockwise (negated). `default` is gc2d's.
    pub fn clockwise_angle(&mut self, name: &str, default: f64) -> Sourced<f64> {
        self.float(name, default).map(|angle| -angle)
    }

    /// A two-float command.
    pub fn pair(&mut self, name: &str, default: [f64; 2]) -> Sourced<[f64; 2]> {
        match self.numbers(name) {
            Some((line, values, _)) => Sourced::written(values, line),
            None => self.default(default),
        }
    }

    /// A two-float command read as a vector.
    pub fn vector(&mut self, name: &str, default: [f64; 2]) -> Sourced<DVec2> {
        self.pair(name, default).map(DVec2::from_array)
    }

    /// A two-float command read as a time window.
    pub fn window(&mut self, name: &str, default: [f64; 2]) -> Sourced<TimeWindow> {
        self.pair(name, default).map(|[start, end]| TimeWindow::new(start, end))
    }

    /// A two-float command read as a range.
    pub fn bounds(&mut self, name: &str, default: [f64; 2]) -> Sourced<Bounds> {
        self.pair(name, default).map(|[min, max]| Bounds { min, max })
    }

    /// A non-negative integer command.
    pub fn whole(&mut self, name: &str, default: u64) -> Sourced<u64> {
        match self.object.take(name) {
            Some(Entry { line, args: Args::Whole(value), .. }) => Sourced::written(value, line),
            _ => self.default(default),
        }
    }

    /// A non-negative integer command without a default (`ID`).
    pub fn optional_whole(&mut self, name: &str) -> Option<Sourced<u64>> {
        match self.object.take(name) {
            Some(Entry { line, args: Args::Whole(value), .. }) => Some(Sourced::written(value, line)),
            _ => None,
        }
    }

    /// A two-integer command.
    pub fn integers(&mut self, name: &str, default: [i64; 2]) -> Sourced<[i64; 2]> {
        match self.object.take(name) {
            Some(Entry { line, args: Args::Integers(values), .. }) => Sourced::written(values, line),
            _ => self.default(default),
        }
    }

    /// A word command, case preserved.
    pub fn word(&mut self, name: &str, default: &str) -> Sourced<String> {
        match self.object.take(name) {
            Some(Entry { line, args: Args::Word(word), .. }) => Sourced::written(word.to_string(), line),
            _ => self.default(default.to_string()),
        }
    }

    /// An option word parsed by `T::from_str`; an unknown value is an error and gives the default.
    pub fn option<T>(&mut self, name: &'static str, default: T) -> Sourced<T>
    where
        T: FromStr,
        T::Err: Display,
    {
        match self.object.take(name) {
            Some(Entry { line, args: Args::Word(word), .. }) => match word.parse::<T>() {
                Ok(value) => Sourced::written(value, line),
                Err(error) => {
                    self.diagnostics.error(line, GsiErrorKind::BadOption { keyword: name, message: error.to_string() });
                    self.default(default)
                }
            },
            _ => self.default(default),
        }
    }

    /// The line of a parameterless command, if present.
    pub fn flag(&mut self, name: &str) -> Option<usize> {
        self.object.take(name).map(|entry| entry.line)
    }

    /// The CORNERS block, if present, and whether all its lines were read (see [`Args::Corners`]).
    pub fn corners(&mut self) -> Option<(Sourced<Vec<DVec2>>, bool)> {
        match self.object.take(CORNERS) {
            Some(Entry { line, args: Args::Corners { corners, complete }, .. }) => {
                Some((Sourced::written(corners, line), complete))
            }
            _ => None,
        }
    }

    /// Warns `warning` (a [`GsiWarningKind::DefaultUsed`]) at `value`'s line where the file did not write it and
    /// gc2d's default was used.
    pub fn warn_if_defaulted<T>(&mut self, value: &Sourced<T>, warning: GsiWarningKind) {
        if !value.origin.is_written() {
            self.diagnostics.warn(value.line(), warning);
        }
    }

    /// The line of the first of `names` written in the object, if any.
    pub fn first_line_of(&self, names: &[&str]) -> Option<usize> {
        self.object.first_line_of(names)
    }
}
