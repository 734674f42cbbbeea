//! Texts for the tests of the ways a whole text is read as lines (`FlatLines`, and the rope the
//! server builds from a string): every kind of line end, and long texts over many stretches.

/// Short texts with every kind of line end, an empty last line and non-ASCII characters.
pub(crate) const TEXTS: &[&str] = &[
    "",
    "\n",
    "G0 X1",
    "G0 X1\n",
    "a\r\nb\rc\n\nd",
    "\r\r\n\n\r",
    "ä\nö\r\nü",
];

/// A text of `lines` lines mixing CRLF, lone CR, LF and non-ASCII comments.
pub(crate) fn long_text(lines: usize) -> String {
    (0..lines)
        .map(|index| match index % 5 {
            0 => format!("N{index} G1 X{index}\r\n"),
            1 => "\r".to_string(),
            2 => format!("; ü {index}\n"),
            _ => format!("X{index}\n"),
        })
        .collect()
}
