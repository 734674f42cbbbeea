//! Grammar-aware generation and mutation of NC text: blocks built from the language's pieces (addresses,
//! `=AC(..)` modifiers, nested brackets, strings, comments, keywords, control structures, DEFINE, PROC),
//! and mutations of whole programs by lines and by characters, with non-ASCII and control bytes and
//! every kind of line end.

use super::random::Random;

const ADDRESSES: &[&str] = &[
    "X", "Y", "Z", "A", "B", "C", "U", "V", "W", "I", "J", "K", "F", "S", "T", "D", "M", "H", "E",
    "L", "P", "Q", "O", "R",
];

const NAMED_ADDRESSES: &[&str] = &[
    "CR", "AP", "RP", "AR", "I1", "J1", "K1", "CT", "TURN", "SPOS", "DC", "ACP", "ACN", "X1", "Z2",
    "AX[X]", "DIAM", "MEAS", "OFFN", "RND", "CHF", "CHR", "FA[X]",
];

const G_FUNCTIONS: &[&str] = &[
    "G0", "G1", "G2", "G3", "G4", "G9", "G17", "G18", "G19", "G40", "G41", "G42", "G53", "G54",
    "G500", "G55", "G64", "G70", "G71", "G90", "G91", "G94", "G95", "G110", "G111", "G112", "G153",
    "G700", "G710", "G33", "G331", "G74", "G75", "G25", "G26", "G9999", "G01", "G1.5",
];

const INSTRUCTIONS: &[&str] = &[
    "DIAMON",
    "DIAMOF",
    "DIAM90",
    "TRANS",
    "ATRANS",
    "ROT",
    "AROT",
    "SCALE",
    "ASCALE",
    "MIRROR",
    "AMIRROR",
    "TRAORI",
    "TRACYL(20)",
    "TRAFOOF",
    "CIP",
    "CT",
    "SUPA",
    "CFC",
    "SOFT",
    "BRISK",
    "M6",
    "M30",
    "M17",
    "RET",
    "STOPRE",
    "CYCLE800()",
    "CYCLE81(10,0,2,-5)",
    "L100",
    "L9999P3",
    "MCALL",
    "MCALL CYCLE83(1,2)",
    "CALL \"SUB\"",
    "PCALL SUB1",
    "EXTCALL \"PART\"",
    "SAVE",
    "REPEAT START END P=2",
    "RPL=30",
    "MSG()",
    "WAITM(1,1,2)",
    "GETD(X)",
    "SETMS(1)",
];

const KEYWORD_LINES: &[&str] = &[
    "IF R1==1",
    "IF R1>2 GOTOF END1",
    "IF NOT (R1<>R2) AND R3 GOTOB LBL",
    "ELSE",
    "ENDIF",
    "WHILE R1>0",
    "ENDWHILE",
    "FOR R1=0 TO 10",
    "ENDFOR",
    "REPEAT",
    "UNTIL R1==0",
    "LOOP",
    "ENDLOOP",
    "CASE R1 OF 1 GOTOF A 2 GOTOF B DEFAULT GOTOF C",
    "GOTOF END1",
    "GOTOB START",
    "GOTO N100",
    "GOTOC LBL",
    "END1:",
    "START:",
    "LBL: G1 X1",
    "DEF REAL DEPTH=5, WIDTH",
    "DEF INT COUNT[3,4]",
    "DEF AXIS AX1",
    "DEF FRAME F1",
    "DEF STRING[20] NAME=\"A\"",
    "DEFINE RETRACT AS G0 Z100",
    "DEFINE M_OFF AS M5 M9",
    "RETRACT",
    "PROC SUB1 (REAL A, VAR INT B) SAVE DISPLOF",
    "PROC MAIN",
    "EXTERN SUB1 (REAL, VAR INT)",
    "RET",
    "M17",
    "WHEN $AA_IW[X]>10 DO $R1=1",
    "ID=1 WHENEVER $A_IN[1]==1 DO M99",
    "$P_UIFR[1]=CTRANS(X,10,Y,20)",
    "R[R1+1]=R[2]*2",
    "$TC_DP1[1,1]=120",
    "$P_UIFR[1,X,TR]=5",
    "$P_UIFR[2]=CROT(Z,45)",
    "G54 G0 X0 Y0",
    "G55 X1",
    "G500",
    "G58 X10",
    "G59 X-2.5",
    "G53 G0 Z0",
    "SUPA X0",
    "G112 X1 Y1",
    "ATRANS X1 AMIRROR Y0",
    "ASCALE X2",
    "ROT Z45",
    "CALL RETRACT",
    "N10 G90 G0 X10 Y20 Z30",
    "G91 G1 X0.5 Y-0.1 F100",
    "X=IC(5) Y=AC(2) Z=DAC(10)",
    "G2 X10 Y0 I5 J0",
    "G3 X0 Y0 CR=5",
    "G111 X0 Y0",
    "G1 AP=45 RP=10",
    "TRANS X10 Y5",
    "AROT RPL=30",
    "SCALE X2 Y2",
    "MIRROR X0",
    "G18 DIAMON G1 X40 Z-5 F0.2",
    "T=\"DRILL\" D1 M6",
    "MSG(\"Bohren \" << R1)",
    "; comment only",
    "(ISO comment)",
    "/1 N20 X1",
    ":100 X2",
];

const FUNCTIONS: &[&str] = &[
    "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN2", "SQRT", "ABS", "POT", "TRUNC", "ROUND", "LN",
    "EXP", "MINVAL", "MAXVAL", "BOUND", "ISVAR", "NUMBER", "STRLEN", "AXNAME",
];

const OPERATORS: &[&str] = &[
    "+", "-", "*", "/", " DIV ", " MOD ", "==", "<>", "<", ">", "<=", ">=", "=<", "=>", " AND ",
    " OR ", " XOR ", " B_AND ", " B_OR ", " B_XOR ", " << ", "=",
];

const MODIFIERS: &[&str] = &[
    "AC", "IC", "DC", "ACP", "ACN", "DAC", "DIC", "RAC", "RIC", "CAC", "CIC", "CDC", "CACP", "CACN",
];

/// Characters that are not NC text but occur in files: non-ASCII letters, symbols, a replacement
/// character, control bytes, a byte order mark, right-to-left marks, astral characters.
const ODD_CHARACTERS: &[&str] = &[
    "Ä",
    "ö",
    "ß",
    "€",
    "µ",
    "°",
    "日本",
    "\u{FFFD}",
    "\u{FEFF}",
    "\u{200F}",
    "\u{1F600}",
    "\u{0}",
    "\u{1}",
    "\u{7}",
    "\u{8}",
    "\t",
    "\u{b}",
    "\u{c}",
    "\u{1b}",
    "\u{7f}",
    "\u{85}",
    "\u{a0}",
    "\u{2028}",
    "\r",
    "\n",
    "\r\n",
];

/// Short pieces of text a mutation inserts: tokens that change how the rest of a line reads.
const FRAGMENTS: &[&str] = &[
    "=",
    "(",
    ")",
    "[",
    "]",
    "\"",
    "'",
    ";",
    ":",
    ",",
    ".",
    "..",
    "$",
    "_",
    "'H",
    "'B",
    "'H1F'",
    "'B101'",
    "EX",
    "EX-",
    "EX+400",
    "EX999999",
    "=AC(",
    "=IC(",
    "=DAC(",
    "AC",
    "IC(",
    "GOTOF ",
    "IF ",
    "ENDIF",
    "N",
    "G",
    "R1",
    "R",
    "X",
    "-",
    "+",
    "*",
    "/",
    " ",
    "  ",
    "0",
    "9",
    "1.5",
    "1e5",
    "99999999999999999999",
    "0.000000000000000001",
    "4294967296",
    "18446744073709551616",
    "DEFINE ",
    " AS ",
    "PROC ",
    "DEF ",
    "REAL ",
    "SIN(",
    "<<",
    "\\",
    "@",
    "#",
    "%",
    "&",
    "|",
    "!",
    "?",
    "{",
    "}",
    "~",
    "^",
];

/// One random block.
pub fn block(random: &mut Random) -> String {
    let mut line = String::new();
    if random.one_in(3) {
        return random.word(KEYWORD_LINES).to_string();
    }
    if random.one_in(20) {
        line.push('/');
        if random.one_in(2) {
            line.push_str(&random.below(12).to_string());
        }
        line.push(' ');
    }
    if random.one_in(3) {
        line.push('N');
        line.push_str(&number(random, false));
        line.push(' ');
    }
    if random.one_in(15) {
        line.push_str(random.word(&["L1:", "END1:", "A_B:", "M:", "LONG_LABEL_NAME_X:"]));
        line.push(' ');
    }
    let words = random.length(5, 40);
    for _ in 0..words {
        match random.below(12) {
            0..=3 => {
                line.push_str(random.word(ADDRESSES));
                line.push_str(&value(random, 0));
            }
            4 => {
                line.push_str(random.word(NAMED_ADDRESSES));
                line.push('=');
                line.push_str(&expression(random, 0));
            }
            5 | 6 => line.push_str(random.word(G_FUNCTIONS)),
            7 => line.push_str(random.word(INSTRUCTIONS)),
            8 => {
                line.push_str(&format!("R{}=", random.below(120)));
                line.push_str(&expression(random, 0));
            }
            9 => line.push_str(&format!("\"{}\"", text(random))),
            10 => line.push_str(random.word(ODD_CHARACTERS)),
            _ => line.push_str(random.word(KEYWORD_LINES)),
        }
        if !random.one_in(6) {
            line.push(' ');
        }
    }
    if random.one_in(4) {
        line.push(';');
        line.push_str(&text(random));
    }
    line
}

/// The value of an address: a constant run together (`X10`), or `=` with an expression or a modifier.
fn value(random: &mut Random, depth: usize) -> String {
    match random.below(8) {
        0..=3 => number(random, true),
        4 => format!("={}", expression(random, depth)),
        5 | 6 => format!(
            "={}({})",
            random.word(MODIFIERS),
            expression(random, depth + 1)
        ),
        // A modifier without parentheses or without its closing one: mistakes the checker explains.
        _ => format!(
            "={}{}",
            random.word(MODIFIERS),
            random.word(&["", "(", "17", "(1", "()", "(,)"])
        ),
    }
}

/// A number of any shape the lexer might see, including forms that are too long or malformed.
pub fn number(random: &mut Random, signed: bool) -> String {
    let mut out = String::new();
    if signed && random.one_in(3) {
        out.push(if random.one_in(4) { '+' } else { '-' });
    }
    let digits = |random: &mut Random, count: usize| -> String {
        (0..count)
            .map(|_| char::from(b'0' + random.below(10) as u8))
            .collect()
    };
    match random.below(10) {
        0..=4 => out.push_str(&random.below(1000).to_string()),
        5 => out.push_str(&format!("{}.{}", random.below(500), digits(random, 3))),
        6 => {
            let count = 1 + random.below(6);
            out.push_str(&format!(".{}", digits(random, count)))
        }
        7 => {
            let count = 1 + random.below(4);
            let mantissa = digits(random, count);
            let exponent = random.word(&["", "-", "+"]).to_string();
            out.push_str(&format!(
                "{mantissa}EX{exponent}{}",
                random.word(&["3", "308", "309", "400", "-400", "99999999999", "0"])
            ));
        }
        8 => {
            let count = random.pick(&[17, 18, 19, 20, 25, 309, 400, 2000]);
            out.push_str(&digits(random, *count));
        }
        _ => out.push_str(random.word(&[
            "0",
            "00",
            "0.",
            ".0",
            "1.2.3",
            "1..",
            "4294967295",
            "4294967296",
            "9007199254740993",
        ])),
    }
    out
}

/// An expression with brackets, calls, operators and variables, nested up to a random depth.
pub fn expression(random: &mut Random, depth: usize) -> String {
    if depth > 6 || random.one_in(3) {
        return match random.below(6) {
            0..=2 => number(random, false),
            3 => format!("R{}", random.below(200)),
            4 => random
                .pick(&[
                    "DEPTH",
                    "$PI",
                    "$AA_IW[X]",
                    "TRUE",
                    "FALSE",
                    "UNKNOWN",
                    "_M1",
                ])
                .to_string(),
            _ => format!("R[{}]", expression(random, depth + 1)),
        };
    }
    match random.below(6) {
        0 => format!("({})", expression(random, depth + 1)),
        1 => format!(
            "{}({})",
            random.word(FUNCTIONS),
            expression(random, depth + 1)
        ),
        2 => format!("-{}", expression(random, depth + 1)),
        3 => format!("NOT {}", expression(random, depth + 1)),
        4 => {
            // Unbalanced or very deep brackets: the depth limit and the error recovery.
            let count = random.pick(&[1, 2, 50, 200]);
            let open = random.word(&["(", "[", "SIN("]).repeat(*count);
            let close = if random.one_in(2) {
                ")".repeat(*count)
            } else {
                String::new()
            };
            format!("{open}1{close}")
        }
        _ => format!(
            "{}{}{}",
            expression(random, depth + 1),
            random.word(OPERATORS),
            expression(random, depth + 1)
        ),
    }
}

/// Text for strings and comments, sometimes with characters that are not ASCII.
fn text(random: &mut Random) -> String {
    let length = random.length(12, 200);
    (0..length)
        .map(|_| match random.below(10) {
            0 => random.word(ODD_CHARACTERS).to_string(),
            1 => "\"".to_string(),
            _ => char::from(b' ' + random.below(95) as u8).to_string(),
        })
        .collect()
}

/// A whole program of generated blocks.
pub fn program(random: &mut Random, max_lines: usize) -> Vec<String> {
    let count = 1 + random.length(max_lines / 8, max_lines);
    (0..count).map(|_| block(random)).collect()
}

/// Joins lines with one kind of line end (sometimes a mixture), with or without a last line end.
pub fn join(random: &mut Random, lines: &[String]) -> String {
    let style = random.below(8);
    let mut out = String::with_capacity(lines.iter().map(|line| line.len() + 2).sum());
    for (index, line) in lines.iter().enumerate() {
        out.push_str(line);
        if index + 1 == lines.len() && random.one_in(3) {
            break;
        }
        out.push_str(match style {
            0 => "\r\n",
            1 => "\r",
            2 => random.word(&["\n", "\r\n", "\r", "\n\r"]),
            _ => "\n",
        });
    }
    out
}

/// Changes a program by whole lines: deletes, duplicates, swaps, inserts generated blocks or lines of
/// `donor` (another program).
pub fn mutate_lines(random: &mut Random, lines: &mut Vec<String>, donor: &[String]) {
    let rounds = 1 + random.length(3, 30);
    for _ in 0..rounds {
        let at = random.below(lines.len() + 1);
        match random.below(7) {
            0 if at < lines.len() => {
                let count = random.below(lines.len() - at).min(random.length(3, 200)) + 1;
                lines.drain(at..at + count);
            }
            1 if at < lines.len() => {
                let copy = lines[at].clone();
                lines.insert(at, copy);
            }
            2 if lines.len() >= 2 => {
                let other = random.below(lines.len());
                let first = at.min(lines.len() - 1);
                lines.swap(first, other);
            }
            3 if !donor.is_empty() => {
                let start = random.below(donor.len());
                let count = random.length(3, 100).min(donor.len() - start);
                lines.splice(at..at, donor[start..start + count].iter().cloned());
            }
            4 | 5 if at < lines.len() => {
                let changed = mutate_line(random, &lines[at]);
                lines[at] = changed;
            }
            _ => lines.insert(at, block(random)),
        }
    }
}

/// Changes one line by characters: inserts fragments, odd characters or digits, deletes or repeats a
/// piece, changes a number (what an edit of a coordinate does), swaps the case.
pub fn mutate_line(random: &mut Random, line: &str) -> String {
    let mut out = line.to_string();
    let rounds = 1 + random.length(2, 12);
    for _ in 0..rounds {
        let at = char_boundary_at(&out, random.below(out.len() + 1));
        match random.below(8) {
            0 | 1 => out.insert_str(at, random.word(FRAGMENTS)),
            2 => out.insert_str(at, random.word(ODD_CHARACTERS)),
            3 => {
                let end = char_boundary_at(&out, at + random.length(3, 40));
                out.replace_range(at..end, "");
            }
            4 => {
                let end = char_boundary_at(&out, at + random.length(6, 60));
                let piece = out[at..end].repeat(1 + random.length(2, 300));
                out.insert_str(at, &piece);
            }
            5 | 6 => change_a_number(random, &mut out),
            _ => {
                let end = char_boundary_at(&out, at + random.length(4, 20));
                let piece = &out[at..end];
                let swapped: String = piece
                    .chars()
                    .map(|character| {
                        if character.is_ascii_uppercase() {
                            character.to_ascii_lowercase()
                        } else {
                            character.to_ascii_uppercase()
                        }
                    })
                    .collect();
                out.replace_range(at..end, &swapped);
            }
        }
    }
    out
}

/// Replaces one run of digits in `line` by another number, or appends one when there is none.
fn change_a_number(random: &mut Random, line: &mut String) {
    let runs: Vec<(usize, usize)> = digit_runs(line);
    let replacement = number(random, false);
    match runs.get(random.below(runs.len().max(1))) {
        Some(&(start, end)) => line.replace_range(start..end, &replacement),
        None => line.push_str(&replacement),
    }
}

fn digit_runs(line: &str) -> Vec<(usize, usize)> {
    let bytes = line.as_bytes();
    let mut runs = Vec::new();
    let mut index = 0;
    while index < bytes.len() {
        if bytes[index].is_ascii_digit() {
            let start = index;
            while index < bytes.len() && (bytes[index].is_ascii_digit() || bytes[index] == b'.') {
                index += 1;
            }
            runs.push((start, index));
        } else {
            index += 1;
        }
    }
    runs
}

/// The nearest character boundary at or before `index` (clamped to the text).
pub fn char_boundary_at(text: &str, index: usize) -> usize {
    let mut index = index.min(text.len());
    while !text.is_char_boundary(index) {
        index -= 1;
    }
    index
}

/// Raw bytes damage: decodes a program after flipping, inserting or deleting bytes, as the CLI decodes
/// files (UTF-8, else Windows-1252).
pub fn mutate_bytes(random: &mut Random, text: &str) -> String {
    let mut bytes = text.as_bytes().to_vec();
    let rounds = 1 + random.length(4, 64);
    for _ in 0..rounds {
        let at = random.below(bytes.len() + 1);
        match random.below(4) {
            0 if at < bytes.len() => bytes[at] = random.next() as u8,
            1 if at < bytes.len() => {
                bytes.remove(at);
            }
            2 => bytes.insert(at, random.next() as u8),
            _ => bytes.insert(
                at,
                *random.pick(&[0u8, 0x80, 0xC3, 0xE2, 0xF0, 0xFF, b'\r']),
            ),
        }
    }
    sinumerik_lsp::io::source_file::decode_source(&bytes).text
}
