//! The fastest, median and peak memory of repeated benchmark runs, shared by the
//! lecture bench and the course bench.

use anyhow::Result;

/// The peak memory (MiB) a child printed as it exited ([`super::PEAK_MEMORY_ENV`]): its
/// last such line.
pub(super) fn printed_peak(stderr: &str) -> Option<f64> {
    stderr
        .rsplit("mechbook: peak memory ")
        .next()
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse().ok())
}

/// The fastest and the median of several runs, and the largest peak memory.
pub(super) struct Timing {
    pub fastest: f64,
    pub median: f64,
    pub peak: f64,
}

/// Runs `one` (seconds, peak MiB) `repeats` times.
pub(super) fn timed(repeats: usize, mut one: impl FnMut() -> Result<(f64, f64)>) -> Result<Timing> {
    let mut runs = Vec::new();
    for _ in 0..repeats.max(1) {
        runs.push(one()?);
    }
    Ok(Timing::of(&runs))
}

impl Timing {
    /// The fastest and median seconds and the largest peak of (seconds, peak MiB) runs; at
    /// least one.
    pub(super) fn of(runs: &[(f64, f64)]) -> Timing {
        let mut secs: Vec<f64> = runs.iter().map(|r| r.0).collect();
        secs.sort_by(f64::total_cmp);
        Timing {
            fastest: secs[0],
            median: secs[secs.len() / 2],
            peak: runs.iter().map(|r| r.1).fold(f64::NAN, f64::max),
        }
    }
}
