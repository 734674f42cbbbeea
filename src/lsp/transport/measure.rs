//! The switch of the side-by-side measurements in `docs/performance.md`.

/// Whether `SINUMERIK_LSP_MEASURE_WITHOUT` (a comma-separated list) turns `piece` of the performance
/// machinery off: `allocator`, `pipe-buffers`, `vmsplice` (`sys/`), `open-in-place` and
/// `literal-scan` (`open_in_place.rs`) or `diagnostics-reuse` (`publish/`). For the side-by-side
/// measurement of `docs/performance.md` only; read once.
pub fn measured_without(piece: &str) -> bool {
    static LIST: std::sync::OnceLock<Vec<String>> = std::sync::OnceLock::new();
    LIST.get_or_init(|| {
        std::env::var("SINUMERIK_LSP_MEASURE_WITHOUT")
            .unwrap_or_default()
            .split(',')
            .map(|item| item.trim().to_string())
            .collect()
    })
    .iter()
    .any(|item| item == piece)
}
