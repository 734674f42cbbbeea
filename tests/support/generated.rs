//! Large programs from the shared generator (`../shared/bench/gen_program.py`), for benchmarks and
//! tests. Included with `#[path]` by each target that needs it, so there is one copy.

use std::path::Path;
use std::process::Command;

/// A deterministic program of `line_count` lines in `style` (cam3d, inc, turning, mixed); `None` when
/// the generator or python3 is not available.
pub fn generate(style: &str, line_count: usize) -> Option<String> {
    let generator = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/bench/gen_program.py");
    if !generator.exists() {
        return None;
    }
    let output = Command::new("python3")
        .arg(&generator)
        .args(["--lines", &line_count.to_string(), "--style", style])
        .output()
        .ok()?;
    if !output.status.success() {
        return None;
    }
    String::from_utf8(output.stdout).ok()
}
