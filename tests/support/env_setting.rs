//! Run sizes and seeds from the environment (`STORM_EDITS=100000`, `SOAK_SECONDS=3600`, ...), so
//! that the quick CI version of a test and its long run are the same code. Included with `#[path]`.

/// The number in the environment variable `name` (digits, `_` allowed between them), or `default`
/// when it is unset or not a number.
pub fn setting(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|value| value.replace('_', "").parse().ok())
        .unwrap_or(default)
}
