//! What a document's URI says: the file it names, if any, and the kind of program it holds.

use crate::analysis::ProgramKind;
use std::path::{Path, PathBuf};
use tower_lsp_server::ls_types::Uri;

/// The file of a `file:` URI.
pub fn file_path(uri: &Uri) -> Option<PathBuf> {
    let is_file = uri.scheme().as_str().eq_ignore_ascii_case("file");
    if !is_file {
        return None;
    }
    uri.to_file_path().map(|path| path.into_owned())
}

/// The kind of a document by its file name (`_N_PART1_MPF` and `PART1.MPF` are main programs), or by
/// the last segment of its URI when it is not a file.
pub fn program_kind(uri: &Uri, path: Option<&Path>) -> ProgramKind {
    match path {
        Some(path) => ProgramKind::from_file_name(&path.to_string_lossy()),
        None => ProgramKind::from_file_name(uri.path().as_str()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::str::FromStr;

    #[test]
    fn a_document_s_kind_comes_from_its_file_name() {
        let kind = |uri: &str| {
            let uri = Uri::from_str(uri).unwrap();
            program_kind(&uri, file_path(&uri).as_deref())
        };
        assert_eq!(kind("file:///nc/_N_MAIN_MPF"), ProgramKind::Main);
        assert_eq!(kind("file:///nc/_N_MAIN_SPF"), ProgramKind::Subprogram);
        assert_eq!(kind("file:///nc/main.mpf"), ProgramKind::Main);
        assert_eq!(kind("untitled:_N_MAIN_MPF"), ProgramKind::Main);
        assert_eq!(kind("untitled:Untitled-1"), ProgramKind::Subprogram);
    }
}
