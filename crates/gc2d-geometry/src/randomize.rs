//! The random draws of particle generation (reference §1.2, App. B.1.6): gc2d's "special truncated Gaussian" and the
//! CONST / EQUAL / GAUSS rules for sizes, corner counts and orientations.

use rand::Rng;
use rand_distr::StandardNormal;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::str::FromStr;
use thiserror::Error;

/// Mean of the special truncated Gaussian (reference §1.2, footnote in B.1.6).
pub const TRUNCATED_GAUSSIAN_MEAN: f64 = 0.5;

/// Standard deviation of the special truncated Gaussian before truncation.
pub const TRUNCATED_GAUSSIAN_STD: f64 = 0.1;

/// Rejections after which [`truncated_gaussian`] stops and returns the mean. A draw falls outside [0, 1] with
/// probability 5.7e-7 (beyond 5σ), so only a broken generator (for example one with constant output) gets here; the
/// bound keeps such a generator from hanging the program.
const TRUNCATED_GAUSSIAN_MAX_REJECTIONS: usize = 64;

/// gc2d's "special truncated Gaussian": a normal variate with μ = 0.5 and σ = 0.1, redrawn until it lies in [0, 1]
/// (reference §1.2). It is used to scatter sizes, corner counts, orientations and grid positions "nicely" about their
/// nominal values without ever leaving the admissible interval.
pub fn truncated_gaussian<R: Rng + ?Sized>(rng: &mut R) -> f64 {
    for _ in 0..TRUNCATED_GAUSSIAN_MAX_REJECTIONS {
        let z: f64 = rng.sample(StandardNormal);
        let x = TRUNCATED_GAUSSIAN_MEAN + TRUNCATED_GAUSSIAN_STD * z;
        if (0.0..=1.0).contains(&x) {
            return x;
        }
    }
    TRUNCATED_GAUSSIAN_MEAN
}

/// How a generated particle's size, corner count or orientation scatters about its nominal value (gsi options
/// `RANDOM_SIZE`, `RANDOM_NUM_CORNERS`, `RANDOM_ROT`; reference §1.2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Randomization {
    /// `CONST`: always the nominal value; the variation is ignored.
    Const,
    /// `EQUAL`: uniform over the interval.
    Equal,
    /// `GAUSS`: the [`truncated_gaussian`] mapped onto the interval.
    Gauss,
}

impl Randomization {
    /// Where in its interval a non-constant draw lands, as a fraction in [0, 1].
    fn fraction<R: Rng + ?Sized>(self, rng: &mut R) -> f64 {
        match self {
            Randomization::Const => 0.5,
            Randomization::Equal => rng.random::<f64>(),
            Randomization::Gauss => truncated_gaussian(rng),
        }
    }

    /// A length drawn in [c(1 − I), c(1 + I)] for nominal length `nominal` = c and relative variation `variation` = I
    /// (`PART_SIZE`, `PART_VAR_SIZE`). Draws nothing from `rng` for `Const`.
    pub fn draw_size<R: Rng + ?Sized>(self, nominal: f64, variation: f64, rng: &mut R) -> f64 {
        match self {
            Randomization::Const => nominal,
            _ => nominal * (1.0 - variation + 2.0 * variation * self.fraction(rng)),
        }
    }

    /// A whole number drawn in [N − N_I, N + N_I] for nominal `nominal` = N and spread `variation` = N_I
    /// (`PART_NUM_CORNERS`, `PART_VAR_CORNERS`). The 2N_I + 1 admissible values split [0, 1] into equal bins, so
    /// `Equal` picks each with the same probability and `Gauss` favours the middle. The lower end saturates at 0.
    /// Draws nothing from `rng` for `Const`.
    pub fn draw_count<R: Rng + ?Sized>(self, nominal: usize, variation: usize, rng: &mut R) -> usize {
        match self {
            Randomization::Const => nominal,
            _ => {
                let lowest = nominal.saturating_sub(variation);
                let span = nominal.saturating_add(variation) - lowest;
                let bin = (self.fraction(rng) * (span as f64 + 1.0)) as usize;
                lowest + bin.min(span)
            }
        }
    }

    /// An orientation in radians (CCW) for nominal angle `nominal` = φ₀ (`PART_ROT`, `RANDOM_ROT`): `Const` gives φ₀,
    /// `Equal` is uniform in [0, 2π) regardless of φ₀, `Gauss` lies in ]φ₀ − π/2, φ₀ + π/2[ centred on φ₀.
    pub fn draw_rotation<R: Rng + ?Sized>(self, nominal: f64, rng: &mut R) -> f64 {
        match self {
            Randomization::Const => nominal,
            Randomization::Equal => TAU * rng.random::<f64>(),
            Randomization::Gauss => nominal - FRAC_PI_2 + PI * truncated_gaussian(rng),
        }
    }
}

/// A gsi option value that names no known choice (for example `Random_Size("NORMAL")`).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("unknown {option} value {value:?}; expected one of {expected}")]
pub struct UnknownOptionValue {
    /// Which option was being read.
    pub option: &'static str,
    /// The value as written.
    pub value: String,
    /// The accepted values.
    pub expected: &'static str,
}

impl FromStr for Randomization {
    type Err = UnknownOptionValue;

    /// Parses the gsi spelling `CONST`, `EQUAL` or `GAUSS`, ignoring case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_uppercase().as_str() {
            "CONST" => Ok(Randomization::Const),
            "EQUAL" => Ok(Randomization::Equal),
            "GAUSS" => Ok(Randomization::Gauss),
            _ => Err(UnknownOptionValue {
                option: "randomization",
                value: s.to_string(),
                expected: "CONST, EQUAL, GAUSS",
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    const DRAWS: usize = 100_000;

    fn mean_and_std(values: &[f64]) -> (f64, f64) {
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let variance = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, variance.sqrt())
    }

    #[test]
    fn truncated_gaussian_stays_in_unit_interval_with_mean_half_and_std_a_tenth() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let values: Vec<f64> = (0..DRAWS).map(|_| truncated_gaussian(&mut rng)).collect();
        assert!(values.iter().all(|v| (0.0..=1.0).contains(v)));
        let (mean, std) = mean_and_std(&values);
        assert!((mean - 0.5).abs() < 0.005, "mean {mean}");
        assert!((std - 0.1).abs() < 0.002, "std {std}");
        // One σ either side of the mean holds 68.3 % of a normal distribution.
        let within_one_sigma = values.iter().filter(|v| (**v - 0.5).abs() < 0.1).count() as f64 / DRAWS as f64;
        assert!((within_one_sigma - 0.6827).abs() < 0.01, "{within_one_sigma}");
    }

    #[test]
    fn equal_sizes_are_uniform_over_the_interval() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let (c, i) = (0.003, 0.25);
        let (low, high) = (c * (1.0 - i), c * (1.0 + i));
        let mut bins = [0usize; 10];
        for _ in 0..DRAWS {
            let size = Randomization::Equal.draw_size(c, i, &mut rng);
            assert!(size >= low && size <= high, "{size}");
            bins[(((size - low) / (high - low)) * 10.0).min(9.0) as usize] += 1;
        }
        for count in bins {
            // Expected 10,000 per bin, binomial σ = 95.
            assert!((count as f64 - 10_000.0).abs() < 500.0, "{bins:?}");
        }
    }

    #[test]
    fn gauss_sizes_centre_on_the_nominal_value_and_span_the_interval_at_most() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let (c, i) = (2.0, 0.5);
        let sizes: Vec<f64> = (0..DRAWS).map(|_| Randomization::Gauss.draw_size(c, i, &mut rng)).collect();
        assert!(sizes.iter().all(|s| (1.0..=3.0).contains(s)));
        let (mean, std) = mean_and_std(&sizes);
        assert!((mean - 2.0).abs() < 0.005);
        // The interval has width 2cI = 2, so σ maps to 0.2.
        assert!((std - 0.2).abs() < 0.004);
    }

    #[test]
    fn const_draws_return_the_nominal_value_and_consume_nothing() {
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let untouched = rng.clone();
        assert_eq!(Randomization::Const.draw_size(0.7, 0.5, &mut rng), 0.7);
        assert_eq!(Randomization::Const.draw_count(9, 4, &mut rng), 9);
        assert_eq!(Randomization::Const.draw_rotation(-1.25, &mut rng), -1.25);
        assert_eq!(rng, untouched);
    }

    #[test]
    fn equal_counts_hit_every_integer_in_range_equally() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let mut hits = [0usize; 13];
        for _ in 0..DRAWS {
            hits[Randomization::Equal.draw_count(9, 2, &mut rng)] += 1;
        }
        assert_eq!(hits[..7].iter().sum::<usize>() + hits[12], 0);
        for count in &hits[7..12] {
            // Expected 20,000 each, binomial σ = 126.
            assert!((*count as f64 - 20_000.0).abs() < 700.0, "{hits:?}");
        }
    }

    #[test]
    fn gauss_counts_stay_in_range_and_favour_the_nominal_count() {
        let mut rng = ChaCha8Rng::seed_from_u64(6);
        let mut hits = [0usize; 13];
        for _ in 0..DRAWS {
            hits[Randomization::Gauss.draw_count(9, 2, &mut rng)] += 1;
        }
        assert_eq!(hits[..7].iter().sum::<usize>() + hits[12], 0);
        // Five bins of width 0.2 on N(0.5, 0.1): the middle bin holds P(|z| < 1) = 68.3 %, each outer bin 0.13 %.
        assert!((hits[9] as f64 / DRAWS as f64 - 0.6827).abs() < 0.01, "{hits:?}");
        assert!(hits[7] < hits[8] && hits[8] < hits[9] && hits[9] > hits[10] && hits[10] > hits[11]);
    }

    #[test]
    fn rotation_rules_cover_their_intervals() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let phi0 = 0.4;
        let gauss: Vec<f64> = (0..DRAWS).map(|_| Randomization::Gauss.draw_rotation(phi0, &mut rng)).collect();
        assert!(gauss.iter().all(|a| *a >= phi0 - FRAC_PI_2 && *a <= phi0 + FRAC_PI_2));
        let (mean, std) = mean_and_std(&gauss);
        assert!((mean - phi0).abs() < 0.005 * PI);
        assert!((std - 0.1 * PI).abs() < 0.002 * PI);
        let equal: Vec<f64> = (0..DRAWS).map(|_| Randomization::Equal.draw_rotation(phi0, &mut rng)).collect();
        assert!(equal.iter().all(|a| (0.0..TAU).contains(a)));
        let (mean, std) = mean_and_std(&equal);
        assert!((mean - PI).abs() < 0.02);
        assert!((std - TAU / 12f64.sqrt()).abs() < 0.02);
    }

    #[test]
    fn gsi_spellings_parse_case_insensitively() {
        assert_eq!("CONST".parse(), Ok(Randomization::Const));
        assert_eq!("equal".parse(), Ok(Randomization::Equal));
        assert_eq!("Gauss".parse(), Ok(Randomization::Gauss));
        let error = "NORMAL".parse::<Randomization>().unwrap_err();
        assert_eq!(error.value, "NORMAL");
        assert!(error.to_string().contains("CONST, EQUAL, GAUSS"));
    }
}
