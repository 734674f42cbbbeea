//! Splitting program text into blocks: LF, CRLF and a lone CR all end a line, as on the control's
//! reader where a CR is a non-printable blank and editors treat it as a line end.

/// The byte ranges of the lines of `text`, without their terminators. A text that ends with a line
/// terminator has no extra empty line after it; an empty text has no lines.
pub fn line_ranges(text: &str) -> LineRanges<'_> {
    LineRanges {
        bytes: text.as_bytes(),
        position: 0,
    }
}

/// Iterator behind [`line_ranges`].
pub struct LineRanges<'a> {
    bytes: &'a [u8],
    position: usize,
}

impl Iterator for LineRanges<'_> {
    type Item = (usize, usize);

    fn next(&mut self) -> Option<(usize, usize)> {
        if self.position >= self.bytes.len() {
            return None;
        }
        let start = self.position;
        let rest = &self.bytes[start..];
        match memchr::memchr2(b'\n', b'\r', rest) {
            Some(offset) => {
                let end = start + offset;
                let terminator_len =
                    if rest[offset] == b'\r' && rest.get(offset + 1) == Some(&b'\n') {
                        2
                    } else {
                        1
                    };
                self.position = end + terminator_len;
                Some((start, end))
            }
            None => {
                self.position = self.bytes.len();
                Some((start, self.bytes.len()))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(text: &str) -> Vec<&str> {
        line_ranges(text)
            .map(|(start, end)| &text[start..end])
            .collect()
    }

    #[test]
    fn all_line_ends_split() {
        assert_eq!(lines("a\nb\r\nc\rd"), vec!["a", "b", "c", "d"]);
        assert_eq!(lines("a\n"), vec!["a"]);
        assert_eq!(lines("a\n\n"), vec!["a", ""]);
        assert_eq!(lines("\r\r"), vec!["", ""]);
        assert!(lines("").is_empty());
    }
}
