//! Ball speeds of a mill run (reference ballmill.md §7.6, "Speed statistics"): distributions of |v| with √N bins, the
//! automatic warm-up cut of the median-speed series by a block stationarity test, and the series' autocorrelation.

use serde::Serialize;

/// The `q`-quantile of sorted `values` by linear interpolation; NaN when there are none.
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let position = q * (sorted.len() - 1) as f64;
    let (low, high) = (position.floor() as usize, position.ceil() as usize);
    sorted[low] + (sorted[high] - sorted[low]) * (position - low as f64)
}

/// A histogram of non-negative values over [0, largest] with ⌈√N⌉ equal bins, area-normalised (thesis §16.3).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Histogram {
    /// Bin edges (one more than the densities; none without values, or when every value is 0).
    pub bin_edges: Vec<f64>,
    /// Probability densities per bin (the histogram's area is 1; none without values, or when every value is 0).
    pub densities: Vec<f64>,
    /// Centre of the fullest bin (the lowest of equally full ones); 0 when every value is 0; NaN (null in JSON)
    /// without values.
    pub mode: f64,
}

impl Histogram {
    /// The histogram of `sorted` (ascending, non-negative) values. Without values it has no bins and no mode: a bin
    /// over [0, the smallest positive number] gave sentinel numbers (2.2e-308) in the reports. When every value is 0
    /// (balls at rest, contacts without approach) it has no bins either, since all of the sample at one point has no
    /// density (a bin [0, 0] would need an infinite one), and its mode is 0, the value every sample takes.
    pub fn of(sorted: &[f64]) -> Self {
        let n = sorted.len();
        let top = sorted.last().copied().unwrap_or(0.0);
        if n == 0 || top <= 0.0 {
            let mode = if n == 0 { f64::NAN } else { 0.0 };
            return Self { bin_edges: Vec::new(), densities: Vec::new(), mode };
        }
        let bins = (n as f64).sqrt().ceil().max(1.0) as usize;
        let width = top / bins as f64;
        let mut counts = vec![0usize; bins];
        for &v in sorted {
            counts[((v / width) as usize).min(bins - 1)] += 1;
        }
        let fullest = counts.iter().enumerate().max_by_key(|&(k, &c)| (c, std::cmp::Reverse(k))).map_or(0, |(k, _)| k);
        Self {
            bin_edges: (0..=bins).map(|k| k as f64 * width).collect(),
            densities: counts.iter().map(|&c| c as f64 / (n as f64 * width)).collect(),
            mode: (fullest as f64 + 0.5) * width,
        }
    }
}

/// The distribution of a set of speeds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpeedDistribution {
    /// How many speeds (ball × dump samples).
    pub samples: usize,
    /// Centre of the fullest histogram bin, m/s.
    pub mode_m_s: f64,
    /// Median, m/s.
    pub median_m_s: f64,
    /// 90th percentile, m/s.
    pub p90_m_s: f64,
    /// Mean, m/s.
    pub mean_m_s: f64,
    /// The histogram, √N bins over [0, largest], area 1 (edges m/s, densities s/m).
    pub histogram: Histogram,
}

impl SpeedDistribution {
    /// The distribution of `speeds` (any order).
    pub fn of(mut speeds: Vec<f64>) -> Self {
        speeds.sort_by(f64::total_cmp);
        let histogram = Histogram::of(&speeds);
        Self {
            samples: speeds.len(),
            mode_m_s: histogram.mode,
            median_m_s: quantile(&speeds, 0.5),
            p90_m_s: quantile(&speeds, 0.9),
            mean_m_s: speeds.iter().sum::<f64>() / speeds.len() as f64,
            histogram,
        }
    }
}

/// Standard deviations (of the reference blocks' means) a block mean may stray from the reference mean and still
/// count as stationary.
pub const STATIONARITY_K: f64 = 3.0;
/// Blocks the series is cut into for the stationarity test (fewer when it is short: at least 2 samples a block).
pub const STATIONARITY_BLOCKS: usize = 20;

/// Where the automatic warm-up cut fell, and the numbers the test used.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WarmUpCut {
    /// Time of the first sample of the first stationary block, s.
    pub cut_s: f64,
    /// Blocks the series was cut into.
    pub blocks: usize,
    /// Samples per block (the last block takes the remainder).
    pub block_samples: usize,
    /// Mean of the second half's block means (the reference), m/s.
    pub reference_mean_m_s: f64,
    /// Standard deviation of the second half's block means, m/s.
    pub reference_spread_m_s: f64,
}

/// The automatic warm-up cut of a series `values` sampled at ascending `times`: cut it into [`STATIONARITY_BLOCKS`]
/// blocks of equal sample count; take the mean μ and the standard deviation s of the block means of the second half
/// as the stationary reference; the cut is the start of the earliest block from which every block mean lies within
/// [`STATIONARITY_K`]·s of μ. Block means (rather than samples) make the test insensitive to correlation shorter than a
/// block. The second half always passes (no block mean of ten lies 3 standard deviations from their mean), so the cut
/// lies in the first half: a series that is not stationary in its second half needs a longer run, which the
/// autocorrelation and the median series' figure show. `None` with fewer than 8 samples.
pub fn warm_up_cut(times: &[f64], values: &[f64]) -> Option<WarmUpCut> {
    let n = times.len().min(values.len());
    if n < 8 {
        return None;
    }
    let blocks = STATIONARITY_BLOCKS.min(n / 2);
    let per_block = n / blocks;
    let block_mean = |b: usize| {
        let end = if b + 1 == blocks { n } else { (b + 1) * per_block };
        values[b * per_block..end].iter().sum::<f64>() / (end - b * per_block) as f64
    };
    let means: Vec<f64> = (0..blocks).map(block_mean).collect();
    let reference = &means[blocks / 2..];
    let mu = reference.iter().sum::<f64>() / reference.len() as f64;
    let spread = (reference.iter().map(|m| (m - mu).powi(2)).sum::<f64>() / (reference.len() - 1).max(1) as f64).sqrt();
    let tolerance = (STATIONARITY_K * spread).max(1e-12 * mu.abs());
    let first = (0..blocks).rev().take_while(|&b| (means[b] - mu).abs() <= tolerance).last().unwrap_or(blocks / 2);
    Some(WarmUpCut {
        cut_s: times[first * per_block],
        blocks,
        block_samples: per_block,
        reference_mean_m_s: mu,
        reference_spread_m_s: spread,
    })
}

/// The normalised autocorrelation of a uniformly sampled series and its summary numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Autocorrelation {
    /// Sampling interval of the series, s.
    pub interval_s: f64,
    /// The rotor's period, s (infinite when it stands still).
    pub rotor_period_s: f64,
    /// ρ(k) for lags k = 0, 1, … (ρ(0) = 1), lag k·interval.
    pub values: Vec<f64>,
    /// The first lag at which ρ drops below 1/e, s (a correlation time); NaN when it does not within the lags.
    pub decorrelation_lag_s: f64,
    /// The largest ρ at lags longer than one rotor period (collapse cycles show as a large value, stationary noise
    /// as a small one); NaN without such lags.
    pub max_beyond_rotor_period: f64,
}

/// Lags of the autocorrelation, in rotor periods.
pub const AUTOCORRELATION_PERIODS: f64 = 3.0;

/// ρ(k) = Σᵢ (xᵢ − x̄)(xᵢ₊ₖ − x̄) / Σᵢ (xᵢ − x̄)² of `values` sampled every `interval` s, for lags up to
/// [`AUTOCORRELATION_PERIODS`] rotor periods and at most half the series (a quarter when the rotor stands still).
/// `None` with fewer than 4 samples or a constant series.
pub fn autocorrelation(values: &[f64], interval: f64, rotor_period: f64) -> Option<Autocorrelation> {
    let n = values.len();
    if n < 4 || interval.is_nan() || interval <= 0.0 {
        return None;
    }
    let mean = values.iter().sum::<f64>() / n as f64;
    let deviations: Vec<f64> = values.iter().map(|v| v - mean).collect();
    let variance: f64 = deviations.iter().map(|d| d * d).sum();
    if variance.is_nan() || variance <= 0.0 {
        return None;
    }
    let max_lag = if rotor_period.is_finite() {
        ((AUTOCORRELATION_PERIODS * rotor_period / interval - 1e-9).ceil() as usize).min(n / 2)
    } else {
        n / 4
    };
    let values: Vec<f64> = (0..=max_lag)
        .map(|k| deviations.iter().zip(&deviations[k..]).map(|(a, b)| a * b).sum::<f64>() / variance)
        .collect();
    let decorrelation_lag_s =
        values.iter().position(|&r| r < (-1.0f64).exp()).map_or(f64::NAN, |k| k as f64 * interval);
    let max_beyond_rotor_period = values
        .iter()
        .enumerate()
        .filter(|&(k, _)| k as f64 * interval > rotor_period)
        .map(|(_, &r)| r)
        .fold(f64::NAN, f64::max);
    Some(Autocorrelation {
        interval_s: interval,
        rotor_period_s: rotor_period,
        values,
        decorrelation_lag_s,
        max_beyond_rotor_period,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn histogram_has_sqrt_n_bins_area_one_and_the_fullest_bin_as_mode() {
        let speeds = vec![0.1, 0.2, 0.25, 0.3, 0.9, 1.0, 2.0, 3.9, 4.0];
        let d = SpeedDistribution::of(speeds);
        assert_eq!(d.histogram.densities.len(), 3);
        let area: f64 =
            d.histogram.densities.iter().zip(d.histogram.bin_edges.windows(2)).map(|(h, e)| h * (e[1] - e[0])).sum();
        assert!((area - 1.0).abs() < 1e-12);
        // Bins of 4/3 m/s: 6, 1 and 2 speeds; the mode is the first bin's centre.
        assert!((d.mode_m_s - 2.0 / 3.0).abs() < 1e-12);
        assert_eq!(d.median_m_s, 0.9);
        assert!((d.p90_m_s - 3.92).abs() < 1e-12);
    }

    /// QA P2-10 j: an empty sample gave a bin over [0, 2.2e-308] and a mode of 1.1e-308.
    #[test]
    fn an_empty_sample_has_no_bins_and_no_mode() {
        let d = SpeedDistribution::of(Vec::new());
        assert!(d.histogram.bin_edges.is_empty() && d.histogram.densities.is_empty());
        assert!(d.histogram.mode.is_nan() && d.mode_m_s.is_nan() && d.median_m_s.is_nan());
        let json = serde_json::to_string(&d).unwrap();
        assert_eq!(
            json,
            r#"{"samples":0,"mode_m_s":null,"median_m_s":null,"p90_m_s":null,"mean_m_s":null,"histogram":{"bin_edges":[],"densities":[],"mode":null}}"#
        );
    }

    /// An all-zero sample (balls at rest) gave bin edges [0, 2.2e-308] and a mode of 1.1e-308: now no bins, mode 0.
    #[test]
    fn an_all_zero_sample_has_no_bins_and_mode_zero() {
        let d = SpeedDistribution::of(vec![0.0; 4]);
        assert!(d.histogram.bin_edges.is_empty() && d.histogram.densities.is_empty());
        assert_eq!((d.samples, d.mode_m_s, d.median_m_s, d.p90_m_s, d.mean_m_s), (4, 0.0, 0.0, 0.0, 0.0));
        let json = serde_json::to_string(&d).unwrap();
        assert_eq!(
            json,
            r#"{"samples":4,"mode_m_s":0.0,"median_m_s":0.0,"p90_m_s":0.0,"mean_m_s":0.0,"histogram":{"bin_edges":[],"densities":[],"mode":0.0}}"#
        );
    }

    #[test]
    fn the_warm_up_cut_falls_where_a_step_ends() {
        // 200 samples: 60 at 5 (warm-up), then ±1 noise about 2; blocks of 10 samples, so the cut is sample 60.
        let times: Vec<f64> = (0..200).map(|i| i as f64 * 0.01).collect();
        let values: Vec<f64> = (0..200)
            .map(|i| {
                if i < 60 {
                    5.0
                } else if i % 2 == 0 {
                    3.0
                } else {
                    1.0
                }
            })
            .collect();
        let cut = warm_up_cut(&times, &values).unwrap();
        assert_eq!((cut.blocks, cut.block_samples), (20, 10));
        assert_eq!(cut.cut_s, times[60]);
        assert_eq!(cut.reference_mean_m_s, 2.0);
        // A stationary series is not cut; a short one has no test.
        assert_eq!(warm_up_cut(&times, &values[60..]).map(|c| c.cut_s), Some(0.0));
        assert!(warm_up_cut(&times[..7], &values[..7]).is_none());
    }

    #[test]
    fn autocorrelation_of_a_sine_and_of_alternating_noise() {
        // A sine of period 0.1 s sampled every 1 ms: ρ at one period is close to 1, and it first drops below 1/e
        // near a fifth of the period (cos(2π t/T) = 1/e at t = 0.1913 T; the finite series moves it by a sample).
        let values: Vec<f64> = (0..2000).map(|i| (std::f64::consts::TAU * i as f64 * 0.001 / 0.1).sin()).collect();
        let a = autocorrelation(&values, 0.001, 0.05).unwrap();
        assert_eq!(a.values.len(), 151);
        assert_eq!(a.values[0], 1.0);
        assert!((0.0185..0.0205).contains(&a.decorrelation_lag_s), "{}", a.decorrelation_lag_s);
        assert!(a.max_beyond_rotor_period > 0.9, "{}", a.max_beyond_rotor_period);
        // Alternating ±1: ρ(1) = −(n−1)/n, and |ρ| ≤ 1 at every lag; the correlation time is one sample.
        let noise: Vec<f64> = (0..100).map(|i| if i % 2 == 0 { 1.0 } else { -1.0 }).collect();
        let b = autocorrelation(&noise, 0.01, f64::INFINITY).unwrap();
        assert!((b.values[1] + 0.99).abs() < 1e-12);
        assert_eq!(b.decorrelation_lag_s, 0.01);
        assert!(b.max_beyond_rotor_period.is_nan());
        assert!(autocorrelation(&[1.0; 10], 0.01, 0.1).is_none());
    }
}
