//! Range checks of single values, each failing with a [`SceneError`] at the value's field path.

use crate::error::SceneError;

/// A finite number.
pub(crate) fn finite(path: &str, value: f64) -> Result<f64, SceneError> {
    if value.is_finite() { Ok(value) } else { Err(SceneError::value(path, format!("{value} is not a finite number"))) }
}

/// A finite number > 0.
pub(crate) fn positive(path: &str, value: f64) -> Result<f64, SceneError> {
    if value > 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(SceneError::value(path, format!("{value}: must be a positive finite number")))
    }
}

/// A finite number ≥ 0.
pub(crate) fn non_negative(path: &str, value: f64) -> Result<f64, SceneError> {
    if value >= 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(SceneError::value(path, format!("{value}: must be a finite number ≥ 0")))
    }
}

/// Two finite numbers.
pub(crate) fn finite_pair(path: &str, pair: [f64; 2]) -> Result<[f64; 2], SceneError> {
    if pair.iter().all(|v| v.is_finite()) {
        Ok(pair)
    } else {
        Err(SceneError::value(path, format!("({}, {}) has a component that is not a finite number", pair[0], pair[1])))
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
            format!("({}, {}): the first value must be {relation} the second", range[0], range[1]),
        ))
    }
}

/// A time window (t1, t2): no NaN, t1 ≤ t2, either end may be infinite.
pub(crate) fn window(path: &str, window: [f64; 2]) -> Result<[f64; 2], SceneError> {
    if window.iter().any(|v| v.is_nan()) || window[0] > window[1] {
        return Err(SceneError::value(
            path,
            format!("({}, {}) is not a time window: it needs t1 ≤ t2 (inf is allowed)", window[0], window[1]),
        ));
    }
    Ok(window)
}
