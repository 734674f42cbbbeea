//! End-to-end tests of `sinumerik-lsp fmt`: files are rewritten in place in their own encoding,
//! `--check` writes nothing and exits 1 when a file would change, and files that cannot be written
//! back byte for byte are refused.

#[path = "support/scratch.rs"]
mod scratch;

use scratch::{run_in, Scratch};

#[test]
fn fmt_rewrites_in_place_and_check_reports_without_writing() {
    let scratch = Scratch::new("fmt-basic");
    let original = b"n10 g0x10y5   ; keep: g0x10\r\nN20 g1 z-5 f100\r\nmsg( \"a;b  c\" )\r\n";
    scratch.write("part.mpf", original);
    scratch.write("clean.mpf", b"N10 G0 X10\n");

    let (code, stdout, _) = run_in(&scratch, &["fmt", "--check", "."]);
    assert_eq!(code, 1, "{stdout}");
    assert!(
        stdout.contains("would be reformatted: ./part.mpf"),
        "{stdout}"
    );
    assert!(!stdout.contains("clean.mpf"), "{stdout}");
    assert_eq!(scratch.read("part.mpf"), original, "--check must not write");

    let (code, stdout, stderr) = run_in(&scratch, &["fmt", "part.mpf"]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert_eq!(
        String::from_utf8(scratch.read("part.mpf")).unwrap(),
        "N10 G0 X10 Y5 ; keep: g0x10\r\nN20 G1 Z-5 F100\r\nMSG(\"a;b  c\")\r\n"
    );
    let (code, stdout, _) = run_in(&scratch, &["fmt", "--check", "part.mpf"]);
    assert_eq!(code, 0, "formatted files pass the check: {stdout}");
    assert!(
        stdout.contains("0 files would be reformatted, 1 file unchanged"),
        "{stdout}"
    );
}

#[test]
fn fmt_keeps_eight_bit_and_bom_encodings_byte_for_byte() {
    let scratch = Scratch::new("fmt-encodings");
    // Windows-1252 umlaut and GBK bytes in comments, a UTF-8 file with a byte-order mark.
    scratch.write("latin.mpf", b"g0 x1 ; \xC4nderung \x80\n");
    scratch.write("gbk.spf", b"g1 x2 f100 ; \xB5\xB6\xBE\xDF\n");
    scratch.write("bom.mpf", b"\xEF\xBB\xBFg0 x1 ; \xC3\xA4\n");
    let (code, stdout, stderr) = run_in(&scratch, &["fmt", "."]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert_eq!(scratch.read("latin.mpf"), b"G0 X1 ; \xC4nderung \x80\n");
    assert_eq!(scratch.read("gbk.spf"), b"G1 X2 F100 ; \xB5\xB6\xBE\xDF\n");
    assert_eq!(scratch.read("bom.mpf"), b"\xEF\xBB\xBFG0 X1 ; \xC3\xA4\n");
}

#[test]
fn fmt_refuses_invalid_utf8_after_a_byte_order_mark() {
    let scratch = Scratch::new("fmt-lossy");
    let bytes = b"\xEF\xBB\xBFg0 x1 ; \xC4\n";
    scratch.write("broken.mpf", bytes);
    let (code, _, stderr) = run_in(&scratch, &["fmt", "broken.mpf"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("byte-order mark"), "{stderr}");
    assert_eq!(
        scratch.read("broken.mpf"),
        bytes,
        "a refused file is not touched"
    );
}

#[test]
fn fmt_usage_and_missing_files_exit_2() {
    let scratch = Scratch::new("fmt-usage");
    assert_eq!(run_in(&scratch, &["fmt"]).0, 2);
    let (code, _, stderr) = run_in(&scratch, &["fmt", "missing.mpf"]);
    assert_eq!(code, 2);
    assert!(stderr.contains("missing.mpf"), "{stderr}");
}
