//! Wall-clock timing of one operation, repeated: the median is what the report quotes.

use std::time::Instant;

/// Median and minimum wall time of `f` over `repetitions` calls (µs), after one untimed call
/// that warms caches and lazily built structures.
pub fn median_us<T>(repetitions: usize, mut f: impl FnMut() -> T) -> (f64, f64) {
    std::hint::black_box(f());
    let mut times: Vec<f64> = (0..repetitions.max(1))
        .map(|_| {
            let start = Instant::now();
            std::hint::black_box(f());
            start.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    times.sort_by(f64::total_cmp);
    (times[times.len() / 2], times[0])
}

/// Median of a non-empty list (the upper median for an even count); NaN for an empty one.
pub fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}
