//! Upper-casing of short names without allocating: the language is case-insensitive (reference §1.1),
//! and both the statement keywords and the G-function names are looked up in upper case.

/// Upper-cases a short ASCII name into `buffer`; `None` when the name is longer than the buffer, which
/// no keyword is.
pub fn uppercase<'a>(name: &str, buffer: &'a mut [u8; 32]) -> Option<&'a str> {
    let bytes = name.as_bytes();
    if bytes.len() > buffer.len() {
        return None;
    }
    for (target, source) in buffer.iter_mut().zip(bytes) {
        *target = source.to_ascii_uppercase();
    }
    std::str::from_utf8(&buffer[..bytes.len()]).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uppercase_short_names_only() {
        let mut buffer = [0u8; 32];
        assert_eq!(uppercase("gotof", &mut buffer), Some("GOTOF"));
        let long = "A".repeat(40);
        assert_eq!(uppercase(&long, &mut buffer), None);
    }
}
