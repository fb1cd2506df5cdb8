//! Range checks of single values, each failing with a [`SceneError`] at the value's field path.

use crate::error::SceneError;

/// A finite number.
pub(crate) fn finite(path: &str, value: f64) -> Result<f64, SceneError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(SceneError::value(path, format!("{} is not a finite number", number(value))))
    }
}

/// A finite number > 0.
pub(crate) fn positive(path: &str, value: f64) -> Result<f64, SceneError> {
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(SceneError::value(path, format!("{}: must be a positive finite number", number(value))))
    }
}

/// A finite number ≥ 0.
pub(crate) fn non_negative(path: &str, value: f64) -> Result<f64, SceneError> {
    if value >= 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(SceneError::value(path, format!("{}: must be a finite number ≥ 0", number(value))))
    }
}

/// Two finite numbers.
pub(crate) fn finite_pair(path: &str, pair: [f64; 2]) -> Result<[f64; 2], SceneError> {
    if pair.iter().all(|v| v.is_finite()) {
        Ok(pair)
    } else {
        Err(SceneError::value(
            path,
            format!("({}, {}) has a component that is not a finite number", number(pair[0]), number(pair[1])),
        ))
    }
}

/// Finite (min, max) with min < max (`strict`) or min ≤ max.
pub(crate) fn ordered_range(path: &str, range: [f64; 2], strict: bool) -> Result<[f64; 2], SceneError> {
    finite_pair(path, range)?;
    let ordered = if strict { range[0] < range[1] } else { range[0] <= range[1] };
    if ordered {
        Ok(range)
    } else {
        let relation = if strict { "less than" } else { "at most" };
        Err(SceneError::value(
            path,
            format!("({}, {}): the first value must be {relation} the second", number(range[0]), number(range[1])),
        ))
    }
}

/// A time window (t1, t2): no NaN, t1 ≤ t2, either end may be infinite.
pub(crate) fn window(path: &str, window: [f64; 2]) -> Result<[f64; 2], SceneError> {
    if window.iter().any(|v| v.is_nan()) || window[0] > window[1] {
        return Err(SceneError::value(
            path,
            format!(
                "({}, {}) is not a time window: it needs t1 ≤ t2 (inf is allowed)",
                number(window[0]),
                number(window[1])
            ),
        ));
    }
    Ok(window)
}

/// A finite number in `[min, max]`, the physically sensible range of what `path` holds (`what`, in `unit`).
pub(crate) fn in_range(
    path: &str,
    value: f64,
    [min, max]: [f64; 2],
    unit: &str,
    what: &str,
) -> Result<f64, SceneError> {
    if value >= min && value <= max {
        Ok(value)
    } else {
        Err(SceneError::value(
            path,
            format!("{} {unit}: {what} must lie between {} and {} {unit}", number(value), number(min), number(max)),
        )
        .with_label("out of range"))
    }
}

/// A number as a person writes it in a scene: plain for 0 and for 1e-4 ≤ |x| < 1e7, else in exponent form, so that
/// 1e-320 reads `1e-320` instead of 330 digits and 1e23 reads `1e23`. Both forms are the shortest that reads back
/// to the same f64.
pub(crate) fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e7).contains(&x.abs()) { format!("{x}") } else { format!("{x:e}") }
}

/// A computed number rounded to `digits` significant digits (at least 1) and written as [`number`] writes it: a
/// time summed step by step reads 0.3, not 0.29999999999908655, and a derived modulus 1.07802e11, not
/// 1.0780219780219778e11. For messages; files keep every digit.
pub fn significant_digits(x: f64, digits: usize) -> String {
    number(rounded_to_significant_digits(x, digits))
}

/// `x` rounded to `digits` significant digits (at least 1), as a number: the value [`significant_digits`] writes, for
/// files that give a nominal value (a dump's time k·T) without the last bits of its computation.
pub fn rounded_to_significant_digits(x: f64, digits: usize) -> f64 {
    format!("{x:.*e}", digits.max(1) - 1).parse().unwrap_or(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        assert_eq!(number(1e-320), "1e-320");
        assert_eq!(number(-2.5e23), "-2.5e23");
        assert_eq!(number(1e308), "1e308");
        assert_eq!(number(0.0001), "0.0001");
        assert_eq!(number(9.81), "9.81");
        assert_eq!(number(-1.0), "-1");
        assert_eq!(number(0.0), "0");
        assert_eq!(number(f64::NAN), "NaN");
        assert_eq!(number(f64::NEG_INFINITY), "-inf");
        assert_eq!(number(12_345_678.0), "1.2345678e7");
    }
}
