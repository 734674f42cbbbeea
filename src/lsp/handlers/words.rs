//! A light reading of one block's words for the editor features: which word the cursor is on and
//! which axis words a block writes literally. It only locates and labels words; what they mean comes
//! from the analysis (`BlockReport`), and where this reading is unsure the features say less.

use std::ops::Range;

/// One word of a block: an address or name with what follows it.
#[derive(Debug, Clone, PartialEq)]
pub struct Word<'a> {
    /// Byte range in the line, from the first letter to the end of the value.
    pub span: Range<usize>,
    /// The address or name as written, without its value (`X`, `G`, `DIAMON`, `X1` in `X1=5`).
    pub name: &'a str,
    pub value: WordValue<'a>,
}

#[derive(Debug, Clone, PartialEq)]
pub enum WordValue<'a> {
    /// A name alone (`DIAMON`, `M`-less keywords).
    None,
    /// A constant written right after the address (`X-12`, `G90`, `N190`); `None` when the digits do
    /// not form a number this reading is sure of.
    Number(Option<f64>),
    /// `=` and the text up to the next blank outside parentheses (`AC(17)`, `R1+2`).
    Assigned(&'a str),
}

impl Word<'_> {
    /// The name in upper case.
    pub fn upper_name(&self) -> String {
        self.name.to_ascii_uppercase()
    }

    /// The number written after the address, or inside a position modifier (`AC(17)` gives 17).
    pub fn literal(&self) -> Option<f64> {
        match &self.value {
            WordValue::Number(value) => *value,
            WordValue::Assigned(text) => parse_number(text).or_else(|| {
                let (_, inner) = self.modifier()?;
                parse_number(inner)
            }),
            WordValue::None => None,
        }
    }

    /// The position modifier of an assigned value and its argument: `Z=IC(-32)` gives ("IC", "-32").
    pub fn modifier(&self) -> Option<(&str, &str)> {
        let WordValue::Assigned(text) = &self.value else {
            return None;
        };
        let open = text.find('(')?;
        let name = text[..open].trim();
        let inner = text[open + 1..].strip_suffix(')')?;
        (!name.is_empty() && name.bytes().all(|byte| byte.is_ascii_alphabetic()))
            .then_some((name, inner.trim()))
    }
}

fn parse_number(text: &str) -> Option<f64> {
    let text = text.trim();
    let digits = text.strip_prefix(['+', '-']).unwrap_or(text);
    let plain = !digits.is_empty()
        && digits
            .bytes()
            .all(|byte| byte.is_ascii_digit() || byte == b'.')
        && digits.bytes().filter(|&byte| byte == b'.').count() <= 1
        && digits.bytes().any(|byte| byte.is_ascii_digit());
    if !plain {
        return None;
    }
    text.parse::<f64>()
        .ok()
        .or_else(|| format!("{}0", text).parse().ok())
}

/// The words of a line, in order, up to its comment. Strings are skipped.
pub fn words(line: &str) -> Vec<Word<'_>> {
    let bytes = line.as_bytes();
    let mut found = Vec::new();
    let mut index = 0;
    while index < bytes.len() {
        let byte = bytes[index];
        if byte == b';' {
            break;
        }
        if byte == b'"' {
            index = line[index + 1..]
                .find('"')
                .map_or(bytes.len(), |offset| index + 1 + offset + 1);
            continue;
        }
        if !(byte.is_ascii_alphabetic() || byte == b'_' || byte == b'$') {
            index += 1;
            continue;
        }
        let start = index;
        while index < bytes.len()
            && (bytes[index].is_ascii_alphabetic() || bytes[index] == b'_' || bytes[index] == b'$')
        {
            index += 1;
        }
        let letters_end = index;
        let number_start = index;
        if index < bytes.len()
            && matches!(bytes[index], b'+' | b'-')
            && bytes
                .get(index + 1)
                .is_some_and(|next| next.is_ascii_digit() || *next == b'.')
        {
            index += 1;
        }
        while index < bytes.len() && (bytes[index].is_ascii_digit() || bytes[index] == b'.') {
            index += 1;
        }
        let number_end = index;
        if index < bytes.len() && bytes[index] == b'=' && bytes.get(index + 1) != Some(&b'=') {
            // `X=..` or `X1=..`: the digits belong to the name.
            let value_start = index + 1;
            index = value_end(bytes, value_start);
            found.push(Word {
                span: start..index,
                name: &line[start..number_end],
                value: WordValue::Assigned(&line[value_start..index]),
            });
        } else if number_end > number_start {
            found.push(Word {
                span: start..number_end,
                name: &line[start..letters_end],
                value: WordValue::Number(parse_number(&line[number_start..number_end])),
            });
        } else {
            // A name followed by letters-digits runs would have been read whole above; a name alone
            // (DIAMON, TRANS, M, IF) ends here. Skip what follows it up to a blank or an operator.
            found.push(Word {
                span: start..letters_end,
                name: &line[start..letters_end],
                value: WordValue::None,
            });
        }
    }
    found
}

/// The end of an assigned value: the next blank, `;` or end of line outside parentheses and brackets.
fn value_end(bytes: &[u8], mut index: usize) -> usize {
    let mut depth = 0usize;
    while index < bytes.len() {
        match bytes[index] {
            b'(' | b'[' => depth += 1,
            b')' | b']' => depth = depth.saturating_sub(1),
            b' ' | b'\t' | b';' if depth == 0 => break,
            b';' => break,
            b'"' => {
                index = bytes[index + 1..]
                    .iter()
                    .position(|&byte| byte == b'"')
                    .map_or(bytes.len() - 1, |offset| index + 1 + offset);
            }
            _ => {}
        }
        index += 1;
    }
    index.min(bytes.len())
}

/// The word whose span holds byte `offset`, or ends right at it (a cursor after the last character).
pub fn word_at<'a>(words: &'a [Word<'a>], offset: usize) -> Option<&'a Word<'a>> {
    words
        .iter()
        .find(|word| word.span.contains(&offset))
        .or_else(|| words.iter().find(|word| word.span.end == offset))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shown(line: &str) -> Vec<(String, WordValue<'_>)> {
        words(line)
            .into_iter()
            .map(|word| (line[word.span.clone()].to_string(), word.value))
            .collect()
    }

    #[test]
    fn words_run_together_split_at_letters() {
        assert_eq!(
            shown("N190 X-12 Z=AC(17) ; X stays"),
            vec![
                ("N190".to_string(), WordValue::Number(Some(190.0))),
                ("X-12".to_string(), WordValue::Number(Some(-12.0))),
                ("Z=AC(17)".to_string(), WordValue::Assigned("AC(17)")),
            ]
        );
        assert_eq!(
            shown("G90X20Z.5 DIAMON"),
            vec![
                ("G90".to_string(), WordValue::Number(Some(90.0))),
                ("X20".to_string(), WordValue::Number(Some(20.0))),
                ("Z.5".to_string(), WordValue::Number(Some(0.5))),
                ("DIAMON".to_string(), WordValue::None),
            ]
        );
    }

    #[test]
    fn assigned_values_keep_their_parentheses_and_names_their_digits() {
        let line = "X1=R1+(2 * 3) MSG(\"a ; b\") Y=IC( -3 )";
        let found = words(line);
        assert_eq!(found[0].name, "X1");
        assert_eq!(found[0].value, WordValue::Assigned("R1+(2 * 3)"));
        let y = found.iter().find(|word| word.name == "Y").unwrap();
        assert_eq!(y.modifier(), Some(("IC", "-3")));
        assert_eq!(y.literal(), Some(-3.0));
        assert!(found.iter().all(|word| word.name != "b"));
    }

    #[test]
    fn the_word_under_the_cursor_is_found() {
        let line = "N20 X75 Z=IC(-32)";
        let found = words(line);
        assert_eq!(word_at(&found, 12).unwrap().name, "Z");
        assert_eq!(word_at(&found, 7).unwrap().name, "X");
        assert!(word_at(&found, 3).is_some_and(|word| word.name == "N"));
        assert_eq!(words("").len(), 0);
    }
}
