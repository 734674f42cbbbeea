//! Tests of the command line's program library on real folders.

use super::*;
use std::fs;

/// A fresh folder per test, removed afterwards.
struct Folder {
    path: PathBuf,
}

impl Folder {
    fn new(test_name: &str) -> Folder {
        let path = std::env::temp_dir().join(format!(
            "sinumerik-lsp-library-{}-{test_name}",
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap();
        Folder { path }
    }

    fn write(&self, relative_path: &str, contents: &[u8]) -> PathBuf {
        let path = self.path.join(relative_path);
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, contents).unwrap();
        path
    }

    fn join(&self, relative_path: &str) -> PathBuf {
        self.path.join(relative_path)
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.path);
    }
}

/// The text the library finds for `name`, or `None`.
fn text_of(library: &dyn ProgramLibrary, name: &str) -> Option<String> {
    library.find(name).map(|program| program.text.to_string())
}

#[test]
fn the_own_folder_comes_first_then_the_parents_up_to_the_configuration_s_folder() {
    let folder = Folder::new("parents");
    let program = folder.write("a/b/MAIN.MPF", b"M30\n");
    folder.write("a/b/OWN.SPF", b"; own\n");
    folder.write("a/OWN.SPF", b"; parent\n");
    folder.write("a/PARENT.SPF", b"; parent\n");
    folder.write("PARENT.SPF", b"; top\n");
    folder.write("TOP.SPF", b"; top\n");

    let library = library_for(&program, Some(&folder.join("a")), &[]);
    assert_eq!(text_of(&*library, "OWN").as_deref(), Some("; own\n"));
    assert_eq!(text_of(&*library, "PARENT").as_deref(), Some("; parent\n"));
    // The configuration's folder is the last one searched.
    assert_eq!(text_of(&*library, "TOP"), None);

    let library = library_for(&program, Some(&folder.path), &[]);
    assert_eq!(text_of(&*library, "TOP").as_deref(), Some("; top\n"));
    assert_eq!(text_of(&*library, "PARENT").as_deref(), Some("; parent\n"));
    let found = library.find("OWN").unwrap();
    assert_eq!(found.name, "OWN");
    assert_eq!(
        &*found.path,
        folder.join("a/b/OWN.SPF").display().to_string()
    );
}

#[test]
fn without_a_configuration_file_only_the_own_folder_is_searched() {
    let folder = Folder::new("own-only");
    let program = folder.write("a/MAIN.MPF", b"M30\n");
    folder.write("a/OWN.SPF", b"; own\n");
    folder.write("PARENT.SPF", b"; parent\n");
    let library = library_for(&program, None, &[]);
    assert_eq!(text_of(&*library, "OWN").as_deref(), Some("; own\n"));
    assert_eq!(text_of(&*library, "PARENT"), None);

    // A configuration file elsewhere (given with `--config`) does not make other folders parents.
    let library = library_for(&program, Some(&folder.join("b")), &[]);
    assert_eq!(text_of(&*library, "OWN").as_deref(), Some("; own\n"));
    assert_eq!(text_of(&*library, "PARENT"), None);
}

#[test]
fn cycle_folders_come_after_the_program_s_folders_in_the_order_given_with_their_subfolders() {
    let folder = Folder::new("cycles");
    let program = folder.write("work/MAIN.MPF", b"M30\n");
    folder.write("work/SHARED.SPF", b"; work\n");
    folder.write("first/SHARED.SPF", b"; first\n");
    folder.write("first/deep/er/DEEP.SPF", b"; deep\n");
    folder.write("first/BOTH.SPF", b"; first\n");
    folder.write("second/BOTH.SPF", b"; second\n");
    folder.write("second/ONLY.SPF", b"; second\n");
    let cycles = [folder.join("first"), folder.join("second")];

    let library = library_for(&program, None, &cycles);
    assert_eq!(text_of(&*library, "SHARED").as_deref(), Some("; work\n"));
    assert_eq!(text_of(&*library, "BOTH").as_deref(), Some("; first\n"));
    assert_eq!(text_of(&*library, "ONLY").as_deref(), Some("; second\n"));
    let deep = library.find("DEEP").unwrap();
    assert_eq!(deep.text.as_ref(), "; deep\n");
    assert_eq!(
        &*deep.path,
        folder.join("first/deep/er/DEEP.SPF").display().to_string()
    );

    let reversed = [folder.join("second"), folder.join("first")];
    let library = library_for(&program, None, &reversed);
    assert_eq!(text_of(&*library, "BOTH").as_deref(), Some("; second\n"));
}

#[test]
fn names_match_pc_and_control_file_names_in_any_case_subprograms_first() {
    let folder = Folder::new("forms");
    let program = folder.write("MAIN.MPF", b"M30\n");
    folder.write("PART2.MPF", b"; main\n");
    folder.write("part2.spf", b"; sub\n");
    folder.write("_N_PART3_SPF", b"; control\n");
    folder.write("_n_part4_mpf.txt", b"; control main\n");
    folder.write("_N_PART5_MPF", b"; control main\n");
    folder.write("_N_PART5_SPF", b"; control sub\n");
    // Sorted by name, `_` comes before the lower-case letters: the rank decides, not the order.
    folder.write("part6.Spf", b"; pc\n");
    folder.write("_N_PART6_SPF", b"; control\n");
    folder.write("PART7.SPF.bak", b"; backup\n");
    folder.write("PART8.txt", b"; text\n");
    folder.write("PART9.DEF", b"DEFINE PART9 AS G0\n");

    let library = library_for(&program, None, &[]);
    assert_eq!(text_of(&*library, "PART2").as_deref(), Some("; sub\n"));
    assert_eq!(text_of(&*library, "part2").as_deref(), Some("; sub\n"));
    assert_eq!(text_of(&*library, "PART3").as_deref(), Some("; control\n"));
    assert_eq!(
        text_of(&*library, "Part4").as_deref(),
        Some("; control main\n")
    );
    assert_eq!(
        text_of(&*library, "PART5").as_deref(),
        Some("; control sub\n")
    );
    assert_eq!(text_of(&*library, "PART6").as_deref(), Some("; pc\n"));
    for name in ["PART7", "PART8", "PART9", "MISSING"] {
        assert_eq!(text_of(&*library, name), None, "{name}");
    }
    assert_eq!(library.find("part2").unwrap().name, "PART2");
    assert_eq!(
        &*library.find("PART4").unwrap().path,
        folder.join("_n_part4_mpf.txt").display().to_string()
    );
}

#[test]
fn leading_zeros_of_l_numbers_are_significant() {
    let folder = Folder::new("l-numbers");
    let program = folder.write("MAIN.MPF", b"M30\n");
    folder.write("L123.SPF", b"; 123\n");
    folder.write("_N_L0123_SPF", b"; 0123\n");
    let library = library_for(&program, None, &[]);
    assert_eq!(text_of(&*library, "L123").as_deref(), Some("; 123\n"));
    assert_eq!(text_of(&*library, "L0123").as_deref(), Some("; 0123\n"));
    assert_eq!(text_of(&*library, "L00123"), None);
    assert_eq!(text_of(&*library, "L12"), None);
}

#[test]
fn each_file_is_read_once_and_misses_are_remembered() {
    let folder = Folder::new("cache");
    let program = folder.write("MAIN.MPF", b"M30\n");
    let callee = folder.write("PART2.SPF", b"; first\n");
    let files = ProgramFiles::unchecked(&[]);
    let library = files.library_for(&program, None);
    assert_eq!(text_of(&*library, "PART2").as_deref(), Some("; first\n"));
    assert_eq!(text_of(&*library, "LATER"), None);

    fs::write(&callee, b"; second\n").unwrap();
    folder.write("LATER.SPF", b"; later\n");
    assert_eq!(text_of(&*library, "PART2").as_deref(), Some("; first\n"));
    assert_eq!(text_of(&*library, "LATER"), None);
    // Another program of the same run shares the folder's listing and the file's text.
    let other = files.library_for(&folder.join("OTHER.MPF"), None);
    assert_eq!(text_of(&*other, "PART2").as_deref(), Some("; first\n"));
    assert_eq!(text_of(&*other, "LATER"), None);

    // A new run reads the folder again.
    let fresh = library_for(&program, None, &[]);
    assert_eq!(text_of(&*fresh, "PART2").as_deref(), Some("; second\n"));
    assert_eq!(text_of(&*fresh, "LATER").as_deref(), Some("; later\n"));
}

#[test]
fn threads_asking_at_once_get_the_same_program() {
    let folder = Folder::new("threads");
    let program = folder.write("MAIN.MPF", b"M30\n");
    folder.write("PART2.SPF", b"; sub\n");
    let library = library_for(&program, None, &[]);
    let found: Vec<Arc<LibraryProgram>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..4)
            .map(|_| scope.spawn(|| library.find("PART2").unwrap()))
            .collect();
        handles
            .into_iter()
            .map(|handle| handle.join().unwrap())
            .collect()
    });
    assert!(found.iter().all(|program| Arc::ptr_eq(program, &found[0])));
}

#[test]
fn windows_1252_files_are_decoded() {
    let folder = Folder::new("windows-1252");
    let program = folder.write("MAIN.MPF", b"M30\n");
    folder.write("PART2.SPF", b"; \xC4nderung \x80\r\nM17\r\n");
    let library = library_for(&program, None, &[]);
    assert_eq!(
        text_of(&*library, "PART2").as_deref(),
        Some("; Änderung €\r\nM17\r\n")
    );
}

#[test]
fn macro_files_are_the_definition_files_with_macros_in_reading_order() {
    let folder = Folder::new("macros");
    let program = folder.write("work/MAIN.MPF", b"M30\n");
    folder.write("work/GUD.DEF", b"DEF NCK REAL LENGTH\n");
    folder.write("work/tools.def", b"DEFINE TOOLS AS T1 D1\n");
    folder.write("work/_N_UMAC_DEF", b"DEFINE USER AS G0\n");
    folder.write("work/_N_SMAC_DEF", b"N10 DEFINE SYSTEM AS G1\n");
    folder.write("work/_N_MMAC_DEF", b"DEFINE MAKER AS G0\n");
    folder.write("work/_N_XMAC_DEF", b"; nothing defined here\n");
    folder.write("work/_N_GUD_DEF", b"DEF CHAN INT COUNT\n");
    folder.write("work/SUB.SPF", b"DEFINE LOCAL AS G0\n");
    folder.write("PARENT.DEF", b"define parent as g0\n");
    folder.write("cycles/sub/_N_CMAC_DEF", b"DEFINE CYCLES AS G0\n");
    let cycles = [folder.join("cycles")];

    let library = library_for(&program, Some(&folder.path), &cycles);
    let names: Vec<String> = library
        .macro_files()
        .iter()
        .map(|file| file.name.clone())
        .collect();
    assert_eq!(names, ["SMAC", "MMAC", "UMAC", "TOOLS", "PARENT", "CMAC"]);
    let files = library.macro_files();
    assert_eq!(
        &*files[3].path,
        folder.join("work/tools.def").display().to_string()
    );
    assert_eq!(files[3].text.as_ref(), "DEFINE TOOLS AS T1 D1\n");

    // A folder that is both a parent and a cycle folder gives its files once.
    let library = library_for(
        &program,
        Some(&folder.path),
        std::slice::from_ref(&folder.path),
    );
    let paths: Vec<String> = library
        .macro_files()
        .iter()
        .map(|file| file.path.to_string())
        .collect();
    let parent = folder.join("PARENT.DEF").display().to_string();
    assert_eq!(paths.iter().filter(|path| **path == parent).count(), 1);
}

#[test]
fn parents_are_shown_as_parts_of_the_program_s_path_then_absolute() {
    let current = absolute_folder(Path::new(""));
    let folders = own_and_parent_folders(Path::new("a/b/MAIN.MPF"), Some(&current));
    let shown: Vec<&Path> = folders
        .iter()
        .map(|folder| folder.shown.as_path())
        .collect();
    assert_eq!(shown, [Path::new("a/b"), Path::new("a"), Path::new("")]);
    assert_eq!(folders[0].read, current.join("a/b"));
    assert_eq!(folders[2].read, current);

    // Above the current folder the path has no names left to take off.
    let above = current.parent().unwrap().to_path_buf();
    let folders = own_and_parent_folders(Path::new("a/../MAIN.MPF"), Some(&above));
    let shown: Vec<&Path> = folders
        .iter()
        .map(|folder| folder.shown.as_path())
        .collect();
    assert_eq!(shown, [Path::new("a/.."), above.as_path()]);
    assert_eq!(folders[0].read, current);
}

#[test]
fn cycle_folders_must_exist() {
    let folder = Folder::new("cycle-errors");
    let file = folder.write("NOT_A_FOLDER.SPF", b"M17\n");
    assert!(ProgramFiles::new(std::slice::from_ref(&folder.path)).is_ok());
    let missing = folder.join("missing");
    let error = ProgramFiles::new(&[folder.path.clone(), missing.clone()]).unwrap_err();
    assert!(
        error.starts_with(&format!(
            "{}: the folder given with --cycles cannot be read: ",
            missing.display()
        )),
        "{error}"
    );
    let error = ProgramFiles::new(std::slice::from_ref(&file)).unwrap_err();
    assert_eq!(
        error,
        format!("{}: given with --cycles, but not a folder", file.display())
    );
}
