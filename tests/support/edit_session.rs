//! An editing session for the storm and soak runs: a deterministic generated program (realistic
//! blocks: absolute and incremental moves, arcs, `=AC`/`=IC`, R parameters, comments with umlauts,
//! now and then a faulty block), and a local copy of the document that makes random edits of the
//! kinds an editor sends and applies them the way the protocol defines, so the server's text can be
//! compared with it. Positions are LSP positions (lines, UTF-16 columns). Included with `#[path]`.

#![allow(dead_code)]

#[path = "../../examples/fuzz/random.rs"]
mod random;

pub use random::Random;
use serde_json::{json, Value};

/// One block of a program; `number` is its block number.
pub fn block(random: &mut Random, number: usize) -> String {
    let coordinate = |random: &mut Random| {
        let value = random.below(400_000) as f64 / 1000.0 - 200.0;
        format!("{value:.3}")
    };
    match random.below(40) {
        0 => format!("N{number} ; Abschnitt {number} äöü"),
        1 => format!(
            "N{number} G91 G1 X{} Y=AC({}) F800",
            coordinate(random),
            coordinate(random)
        ),
        2 => format!("N{number} G90"),
        // End points lie within ±200 (and incremental moves rarely go far), so a radius of 1000
        // reaches them.
        3 => format!(
            "N{number} G90 G2 X{} Y{} CR={}",
            coordinate(random),
            coordinate(random),
            1000 + random.below(200)
        ),
        4 => format!(
            "N{number} G90 G1 X{} Z=IC({})",
            coordinate(random),
            coordinate(random)
        ),
        5 => format!("N{number} R1=R1+{} R2=R1*2", random.below(10)),
        6 => format!("N{number} G0 Z{}", coordinate(random)),
        // A faulty block now and then, so that there are diagnostics to compare.
        7 if random.one_in(20) => format!("N{number} G1 X Y{}", coordinate(random)),
        8 => format!(
            "N{number} F{} S{} M3",
            100 + random.below(5_000),
            random.below(20_000)
        ),
        _ => format!(
            "N{number} G1 X{} Y{} Z{}",
            coordinate(random),
            coordinate(random),
            coordinate(random)
        ),
    }
}

/// A program of `line_count` lines (header, blocks, `M30`), each line ended by `terminator`.
pub fn program(random: &mut Random, line_count: usize, terminator: &str) -> String {
    let mut lines = vec![
        "; generated program".to_string(),
        "G17 G90 G71 G54 G64".to_string(),
        "T1 D1".to_string(),
        "M6".to_string(),
        "G0 X0 Y0 Z50".to_string(),
    ];
    while lines.len() + 1 < line_count {
        let number = 10 * lines.len();
        lines.push(block(random, number));
    }
    lines.push("M30".to_string());
    lines.truncate(line_count);
    let mut text = lines.join(terminator);
    text.push_str(terminator);
    text
}

/// One change of a `didChange`: an LSP range and its new text.
#[derive(Debug, Clone)]
pub struct Edit {
    pub start: (usize, usize),
    pub end: (usize, usize),
    pub text: String,
}

impl Edit {
    /// The `contentChanges` entry.
    pub fn to_json(&self) -> Value {
        json!({
            "range": {
                "start": {"line": self.start.0, "character": self.start.1},
                "end": {"line": self.end.0, "character": self.end.1},
            },
            "text": self.text,
        })
    }
}

/// Text typed into a line: digits, words, non-ASCII characters (one outside the BMP).
const PIECES: &[&str] = &[
    "1",
    "7",
    ".5",
    "-",
    " X10",
    " Y-2.5",
    " Z=IC(1)",
    " G91",
    " G90",
    " F500",
    " ; ä",
    " 😀",
    " G2 X10 Y5 CR=5",
    " R1=R1+1",
    " X",
    "(",
];

/// The local copy of a document whose lines all end with one kind of terminator: `lines` are the
/// text split at it (the last one is empty when the text ends with a terminator).
pub struct LineDocument {
    pub lines: Vec<String>,
    pub terminator: &'static str,
    /// Edits mostly land near the last one, as when a user types.
    cursor: usize,
}

/// The byte offset in `line` of a UTF-16 column, clamped to the line; inside a surrogate pair it is
/// the start of the character (as the protocol's servers clamp). Written here again on purpose: the
/// copy the server's text is compared with must not share the server's conversions.
pub fn utf16_to_byte(line: &str, character: usize) -> usize {
    let mut units = 0;
    for (byte, ch) in line.char_indices() {
        let next = units + ch.len_utf16();
        if next > character {
            return byte;
        }
        units = next;
    }
    line.len()
}

/// The UTF-16 column of a byte offset in `line`.
pub fn byte_to_utf16(line: &str, byte: usize) -> usize {
    line[..byte].encode_utf16().count()
}

impl LineDocument {
    pub fn new(text: &str, terminator: &'static str) -> LineDocument {
        LineDocument {
            lines: text.split(terminator).map(str::to_string).collect(),
            terminator,
            cursor: 0,
        }
    }

    pub fn text(&self) -> String {
        self.lines.join(self.terminator)
    }

    fn utf16_len(&self, line: usize) -> usize {
        self.lines[line].encode_utf16().count()
    }

    /// Applies an edit as the protocol defines it: positions past the end of a line are its end, a
    /// line past the end is the end of the text.
    pub fn apply(&mut self, edit: &Edit) {
        let position = |lines: &[String], (line, character): (usize, usize)| {
            if line >= lines.len() {
                let last = lines.len() - 1;
                (last, lines[last].len())
            } else {
                (line, utf16_to_byte(&lines[line], character))
            }
        };
        let (start_line, start_byte) = position(&self.lines, edit.start);
        let (end_line, end_byte) = position(&self.lines, edit.end);
        let mut joined = String::with_capacity(edit.text.len() + 200);
        joined.push_str(&self.lines[start_line][..start_byte]);
        joined.push_str(&edit.text);
        joined.push_str(&self.lines[end_line][end_byte..]);
        let pieces: Vec<String> = joined.split(self.terminator).map(str::to_string).collect();
        self.lines.splice(start_line..=end_line, pieces);
    }

    /// A random position near the cursor (one in 50 anywhere), as (line, UTF-16 column) at a
    /// character boundary.
    fn position(&mut self, random: &mut Random) -> (usize, usize) {
        let line_count = self.lines.len();
        let line = if random.one_in(50) {
            random.below(line_count)
        } else {
            (self.cursor + random.below(41))
                .saturating_sub(20)
                .min(line_count - 1)
        };
        self.cursor = line;
        let text = &self.lines[line];
        let boundaries = text.chars().count() + 1;
        let chars = random.below(boundaries);
        let byte = text
            .char_indices()
            .nth(chars)
            .map_or(text.len(), |(byte, _)| byte);
        (line, byte_to_utf16(text, byte))
    }

    /// A random edit of the kinds an editor sends, already applied to this copy.
    pub fn random_edit(&mut self, random: &mut Random) -> Edit {
        let (line, column) = self.position(random);
        let last = self.lines.len() - 1;
        let terminator = self.terminator;
        let edit = match random.below(24) {
            // Typing.
            0..=7 => Edit {
                start: (line, column),
                end: (line, column),
                text: random.word(PIECES).to_string(),
            },
            // A changed digit: every later position may move.
            8..=10 => match self.lines[line].rfind(|ch: char| ch.is_ascii_digit()) {
                Some(byte) => {
                    let column = byte_to_utf16(&self.lines[line], byte);
                    Edit {
                        start: (line, column),
                        end: (line, column + 1),
                        text: random.below(10).to_string(),
                    }
                }
                None => Edit {
                    start: (line, column),
                    end: (line, column),
                    text: "5".to_string(),
                },
            },
            // Deleting a few characters; the end may lie past the line's end (clamped).
            11 | 12 => Edit {
                start: (line, column),
                end: (line, column + 1 + random.below(6)),
                text: String::new(),
            },
            // A new block, or several pasted.
            13 | 14 => {
                let count = if random.one_in(3) {
                    2 + random.below(30)
                } else {
                    1
                };
                let mut text = String::new();
                for index in 0..count {
                    text.push_str(&block(random, 5 + index));
                    text.push_str(terminator);
                }
                Edit {
                    start: (line, 0),
                    end: (line, 0),
                    text,
                }
            }
            // Deleting whole lines.
            15 | 16 if line < last => {
                let count = if random.one_in(4) {
                    2 + random.below(40)
                } else {
                    1
                };
                Edit {
                    start: (line, 0),
                    end: ((line + count).min(last), 0),
                    text: String::new(),
                }
            }
            // Joining a line with the next one.
            17 if line < last => Edit {
                start: (line, self.utf16_len(line)),
                end: (line + 1, random.below(3)),
                text: " ".to_string(),
            },
            // Typing on a line past the end of the document (rarely: the analysis then reads on from
            // the cursor to the end), or at a column past the line's end.
            18 if random.one_in(10) => Edit {
                start: (self.lines.len() + 5, 0),
                end: (self.lines.len() + 5, 0),
                text: format!("N9{} X1", random.below(10)),
            },
            18 => Edit {
                start: (line, column + 1000),
                end: (line, column + 1000),
                text: " ; end".to_string(),
            },
            // A line typed over with a fresh block (keeps the document from filling up with junk).
            _ => Edit {
                start: (line, 0),
                end: (line, self.utf16_len(line)),
                text: block(random, 10 * line),
            },
        };
        self.apply(&edit);
        edit
    }
}

impl LineDocument {
    /// A random edit that keeps the document as sound as it was, for long runs (random typing fills
    /// a document with findings, and every publication grows): a changed digit, a comment at a line's
    /// end, a line typed over with a fresh block, a new block, a deleted line, or a typo taken back
    /// at once (two edits). Already applied to this copy.
    pub fn tidy_edits(&mut self, random: &mut Random) -> Vec<Edit> {
        let (line, column) = self.position(random);
        let length = self.utf16_len(line);
        let edits = match random.below(20) {
            // The first decimal of the last coordinate (never a digit of a G or M function).
            0..=7 => match self.lines[line].rfind('.').filter(|&dot| {
                self.lines[line][dot + 1..].starts_with(|ch: char| ch.is_ascii_digit())
            }) {
                Some(dot) => {
                    let column = byte_to_utf16(&self.lines[line], dot + 1);
                    vec![Edit {
                        start: (line, column),
                        end: (line, column + 1),
                        text: random.below(10).to_string(),
                    }]
                }
                None => Vec::new(),
            },
            8 | 9 if !self.lines[line].contains(';') => vec![Edit {
                start: (line, length),
                end: (line, length),
                text: " ; geprüft".to_string(),
            }],
            10..=12 => vec![Edit {
                start: (line, 0),
                end: (line, length),
                text: block(random, 10 * line),
            }],
            13 | 14 => vec![Edit {
                start: (line, 0),
                end: (line, 0),
                text: format!("{}{}", block(random, 10 * line + 5), self.terminator),
            }],
            15 | 16 if line + 1 < self.lines.len() => vec![Edit {
                start: (line, 0),
                end: (line + 1, 0),
                text: String::new(),
            }],
            _ => {
                let typo = random.word(PIECES);
                let typed_end = column + typo.encode_utf16().count();
                vec![
                    Edit {
                        start: (line, column),
                        end: (line, column),
                        text: typo.to_string(),
                    },
                    Edit {
                        start: (line, column),
                        end: (line, typed_end),
                        text: String::new(),
                    },
                ]
            }
        };
        for edit in &edits {
            self.apply(edit);
        }
        edits
    }
}
