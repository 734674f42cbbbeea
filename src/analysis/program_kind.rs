//! Whether a program runs on its own or is called: `ProgramKind` by file name or extension, and the
//! `PROC` header that makes any program a subprogram.

/// Whether a program runs on its own (a main program, `.MPF`) or is called (a subprogram, `.SPF`): a
/// subprogram inherits the caller's modal state, feed included.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramKind {
    Main,
    Subprogram,
}

impl ProgramKind {
    /// The kind by file extension: only `mpf` is known to be a main program. Anything else (`spf`,
    /// contour files such as `drs`, text files) may be called with the caller's modal state, so it is
    /// treated as a subprogram: findings that need the reset state are not reported there.
    pub fn from_extension(extension: Option<&str>) -> ProgramKind {
        match extension {
            Some(extension) if extension.eq_ignore_ascii_case("mpf") => ProgramKind::Main,
            _ => ProgramKind::Subprogram,
        }
    }

    /// The kind by file name or path: the control's own names say it (`_N_PART1_MPF` is a main
    /// program, `_N_PART1_SPF` a subprogram, with or without an extension after them, as archives
    /// and transfers add one); any other name goes by its extension as in
    /// [`ProgramKind::from_extension`]. A path's folders are ignored, whether written with `/` or `\`.
    pub fn from_file_name(name: &str) -> ProgramKind {
        let base = name.rsplit(['/', '\\']).next().unwrap_or(name);
        let (stem, extension) = match base.rfind('.') {
            Some(dot) if dot > 0 => (&base[..dot], Some(&base[dot + 1..])),
            _ => (base, None),
        };
        // Compared as bytes: a name may hold any characters, and slicing a `str` inside one panics.
        let stem = stem.as_bytes();
        let is_control_name = |suffix: &[u8]| {
            stem.len() > 3 + suffix.len()
                && stem[..3].eq_ignore_ascii_case(b"_N_")
                && stem[stem.len() - suffix.len()..].eq_ignore_ascii_case(suffix)
        };
        if is_control_name(b"_MPF") {
            ProgramKind::Main
        } else if is_control_name(b"_SPF") {
            ProgramKind::Subprogram
        } else {
            ProgramKind::from_extension(extension)
        }
    }
}

/// Whether a line of the program starts with `PROC`: such a program is a subprogram whatever its
/// file is called.
pub fn has_proc_header(text: &str) -> bool {
    crate::syntax::lines_containing(text, b"PROC").any(is_proc_header)
}

/// Whether a line starts with `PROC`, the header of a subprogram.
#[inline]
pub fn is_proc_header(line: &str) -> bool {
    line.trim_start()
        .get(..4)
        .is_some_and(|word| word.eq_ignore_ascii_case("PROC"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kind_comes_from_the_control_s_file_names_and_from_extensions() {
        for (name, kind) in [
            ("_N_PART1_MPF", ProgramKind::Main),
            ("_n_part1_mpf", ProgramKind::Main),
            ("_N_PART1_SPF", ProgramKind::Subprogram),
            ("_N_PART1_MPF.txt", ProgramKind::Main),
            ("_N_PART1_MPF.SPF", ProgramKind::Main),
            ("_N_PART1_SPF.MPF", ProgramKind::Subprogram),
            ("/nc/_N_WKS_DIR/_N_A_WPD/_N_MAIN_MPF", ProgramKind::Main),
            ("C:\\nc\\_N_MAIN_MPF", ProgramKind::Main),
            ("PART1.MPF", ProgramKind::Main),
            ("part1.mpf", ProgramKind::Main),
            ("a/b/PART1.SPF", ProgramKind::Subprogram),
            ("CONTOUR.DRS", ProgramKind::Subprogram),
            ("MPF", ProgramKind::Subprogram),
            // The name between `_N_` and the type must not be empty.
            ("_N_MPF", ProgramKind::Subprogram),
            ("_N__MPF", ProgramKind::Subprogram),
            ("_N_X_MPF", ProgramKind::Main),
            ("_N_ÄÖ_MPF", ProgramKind::Main),
            ("ÄÖÜ", ProgramKind::Subprogram),
            ("PART1_MPF", ProgramKind::Subprogram),
            ("", ProgramKind::Subprogram),
        ] {
            assert_eq!(ProgramKind::from_file_name(name), kind, "{name}");
        }
    }
}
