//! Comparison of two values through their debug form with decimal numbers equal to a tolerance: an
//! incremental analysis may carry a shift of positions instead of adding increments again, which gives
//! the same positions up to the last bits of a double.

/// `Err` shows where the debug forms of `actual` and `expected` first differ beyond `tolerance`.
pub fn approx_equal(
    actual: &impl std::fmt::Debug,
    expected: &impl std::fmt::Debug,
    tolerance: f64,
) -> Result<(), String> {
    let actual = format!("{actual:?}");
    let expected = format!("{expected:?}");
    let mut left = Tokens::new(&actual);
    let mut right = Tokens::new(&expected);
    loop {
        let (a, b) = (left.next(), right.next());
        let same = match (&a, &b) {
            (None, None) => return Ok(()),
            (Some(Token::Number(x)), Some(Token::Number(y))) => {
                x == y || (x - y).abs() <= tolerance * x.abs().max(y.abs()).max(1.0)
            }
            (Some(Token::Text(x)), Some(Token::Text(y))) => x == y,
            _ => false,
        };
        if !same {
            let at = left.position.min(actual.len());
            let from = at.saturating_sub(120);
            return Err(format!(
                "values differ at {a:?} vs {b:?}, after …{}",
                actual.get(from..at).unwrap_or("")
            ));
        }
    }
}

#[derive(Debug)]
enum Token<'a> {
    Number(f64),
    Text(&'a str),
}

/// Splits a debug form into decimal numbers (those with a point or an exponent) and the text between.
struct Tokens<'a> {
    text: &'a str,
    position: usize,
}

impl<'a> Tokens<'a> {
    fn new(text: &'a str) -> Tokens<'a> {
        Tokens { text, position: 0 }
    }

    fn next(&mut self) -> Option<Token<'a>> {
        let bytes = self.text.as_bytes();
        let start = self.position;
        if start >= bytes.len() {
            return None;
        }
        if let Some(end) = self.number_end(start) {
            let literal = &self.text[start..end];
            if literal.contains(['.', 'e']) {
                if let Ok(value) = literal.parse::<f64>() {
                    self.position = end;
                    return Some(Token::Number(value));
                }
            }
        }
        // Text runs to the next place where a number may start.
        let mut end = start + 1;
        while end < bytes.len() && self.number_end(end).is_none() {
            end += 1;
        }
        while !self.text.is_char_boundary(end) {
            end += 1;
        }
        self.position = end;
        Some(Token::Text(&self.text[start..end]))
    }

    /// Where a number starting at `start` ends, if one starts there (a digit or a minus before a digit,
    /// not inside a name).
    fn number_end(&self, start: usize) -> Option<usize> {
        let bytes = self.text.as_bytes();
        let previous = start.checked_sub(1).map(|index| bytes[index]);
        if previous.is_some_and(|byte| byte.is_ascii_alphanumeric() || byte == b'_' || byte == b'.')
        {
            return None;
        }
        let mut end = start;
        if bytes.get(end) == Some(&b'-') {
            end += 1;
        }
        if !bytes.get(end).is_some_and(u8::is_ascii_digit) {
            return None;
        }
        while end < bytes.len()
            && (bytes[end].is_ascii_digit()
                || bytes[end] == b'.'
                || bytes[end] == b'e'
                || (bytes[end] == b'-' && bytes[end - 1] == b'e'))
        {
            end += 1;
        }
        Some(end)
    }
}
