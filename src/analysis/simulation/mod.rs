//! What turns the control's executed blocks into the path the tool takes (docs/simulation.md):
//! stages that stream over the executed moves in execution order (corners), and the machining time
//! of each move (time).

pub mod corner_geometry;
pub mod corners;
pub mod time;

pub use corners::CornerStage;

/// Whether `text` may program a contour definition: one of the words (`RND`, `RNDM`, `CHF`, `CHR`,
/// `ANG` or their configured names) followed by `=`. A mention in a comment only makes a program run
/// through the interpreter when it need not; a program without any runs in program order.
pub fn mentions_contour_words(text: &str, config: &crate::config::MachineConfig) -> bool {
    let names = &config.contours;
    let words = [
        names.radius_name.as_str(),
        names.chamfer_name.as_str(),
        names.angle_name.as_str(),
        "RNDM",
        "CHF",
    ];
    // Looks back from each `=` (rare in most programs) for the name written before it.
    let bytes = text.as_bytes();
    bytes.iter().enumerate().any(|(at, &byte)| {
        if byte != b'=' {
            return false;
        }
        let mut end = at;
        while end > 0 && matches!(bytes[end - 1], b' ' | b'\t') {
            end -= 1;
        }
        let mut start = end;
        while start > 0 && is_name_byte(bytes[start - 1]) && end - start <= 32 {
            start -= 1;
        }
        let name = &bytes[start..end];
        words
            .iter()
            .any(|word| name.eq_ignore_ascii_case(word.as_bytes()))
    })
}

fn is_name_byte(byte: u8) -> bool {
    byte.is_ascii_alphanumeric() || byte == b'_' || byte == b'$'
}

#[cfg(test)]
mod corner_geometry_tests;
