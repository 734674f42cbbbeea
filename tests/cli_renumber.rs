//! End-to-end tests of `sinumerik-lsp renumber`: start, step and the three numbering modes, jumps to
//! block numbers following their block, `--check`, and refusals that leave files untouched.

#[path = "support/scratch.rs"]
mod scratch;

use scratch::{run_in, Scratch};

const PROGRAM: &str = "N5 G0 X0 ; N5 in a comment stays\nNAME:\nN7 MSG(\"N7\")\nN7 IF R1>0 GOTOB N7\n/N9 GOTOF N5\nN5 M30\n";

#[test]
fn renumber_keeps_numbered_blocks_and_moves_jumps_with_their_block() {
    let scratch = Scratch::new("renumber-keep");
    scratch.write("p.mpf", PROGRAM.as_bytes());
    let (code, stdout, stderr) = run_in(
        &scratch,
        &["renumber", "--start", "100", "--step", "5", "p.mpf"],
    );
    assert_eq!(code, 0, "{stdout}{stderr}");
    // GOTOB N7 reaches the N7 above it (now N105), GOTOF N5 the N5 below it (now N120).
    assert_eq!(
        String::from_utf8(scratch.read("p.mpf")).unwrap(),
        "N100 G0 X0 ; N5 in a comment stays\nNAME:\nN105 MSG(\"N7\")\nN110 IF R1>0 GOTOB N105\n/N115 GOTOF N120\nN120 M30\n"
    );
}

#[test]
fn renumber_all_numbers_every_block_and_drop_keeps_only_jump_targets() {
    let scratch = Scratch::new("renumber-modes");
    scratch.write("all.mpf", PROGRAM.as_bytes());
    scratch.write("drop.mpf", PROGRAM.as_bytes());
    assert_eq!(run_in(&scratch, &["renumber", "--all", "all.mpf"]).0, 0);
    assert_eq!(
        String::from_utf8(scratch.read("all.mpf")).unwrap(),
        "N10 G0 X0 ; N5 in a comment stays\nN20 NAME:\nN30 MSG(\"N7\")\nN40 IF R1>0 GOTOB N30\n/N50 GOTOF N60\nN60 M30\n"
    );
    assert_eq!(run_in(&scratch, &["renumber", "--drop", "drop.mpf"]).0, 0);
    assert_eq!(
        String::from_utf8(scratch.read("drop.mpf")).unwrap(),
        "G0 X0 ; N5 in a comment stays\nNAME:\nN10 MSG(\"N7\")\nIF R1>0 GOTOB N10\n/GOTOF N20\nN20 M30\n"
    );
}

#[test]
fn renumber_check_writes_nothing_and_exits_1() {
    let scratch = Scratch::new("renumber-check");
    scratch.write("p.mpf", PROGRAM.as_bytes());
    let (code, stdout, _) = run_in(&scratch, &["renumber", "--check", "p.mpf"]);
    assert_eq!(code, 1, "{stdout}");
    assert!(stdout.contains("would be renumbered: p.mpf"), "{stdout}");
    assert_eq!(scratch.read("p.mpf"), PROGRAM.as_bytes());
    scratch.write("done.mpf", b"N10 G0 X0\nN20 M30\n");
    assert_eq!(run_in(&scratch, &["renumber", "--check", "done.mpf"]).0, 0);
}

#[test]
fn renumber_refuses_to_give_a_missing_jump_target_a_block() {
    let scratch = Scratch::new("renumber-refuse");
    let program = b"N1 GOTOF N20\nN2 G0 X1\n";
    scratch.write("p.mpf", program);
    let (code, _, stderr) = run_in(&scratch, &["renumber", "p.mpf"]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("N20"), "{stderr}");
    assert_eq!(scratch.read("p.mpf"), program);
}
