//! Paths as the CI formats want them: forward slashes, relative to the working folder where the path
//! was relative, and as URI references (percent-encoded) for SARIF.

use std::path::Path;

/// The path with forward slashes and without a leading `./`: GitLab matches a report's paths
/// against the repository's files, which it names that way.
pub(super) fn slash_path(path_text: &str) -> String {
    // A backslash separates folders only on Windows; elsewhere it is part of a file name.
    let slashed = if cfg!(windows) {
        path_text.replace('\\', "/")
    } else {
        path_text.to_string()
    };
    let mut rest = slashed.as_str();
    while let Some(stripped) = rest.strip_prefix("./") {
        rest = stripped.trim_start_matches('/');
    }
    rest.to_string()
}

/// Whether the path (as written) is absolute, so that it becomes a `file:` URI rather than a
/// reference relative to `%SRCROOT%`.
pub(super) fn is_absolute(path_text: &str) -> bool {
    Path::new(path_text).is_absolute()
}

/// A URI reference for the path: `file:///abs/path` for an absolute one, `rel/path` for a relative
/// one; every byte outside the unreserved characters and `/` percent-encoded (RFC 3986), so that
/// spaces, `#`, `%` and non-ASCII names survive.
pub(super) fn path_uri(path_text: &str) -> String {
    let slashed = slash_path(path_text);
    let encoded = percent_encode(&slashed);
    if !is_absolute(path_text) {
        return encoded;
    }
    // `C:/dir` becomes `file:///C:/dir`, `/dir` becomes `file:///dir`.
    if encoded.starts_with('/') {
        format!("file://{encoded}")
    } else {
        format!("file:///{}", encoded.replacen("%3A", ":", 1))
    }
}

/// The URI of a folder, ending in `/` as SARIF requires of a base URI.
pub(super) fn folder_uri(folder: &Path) -> Option<String> {
    let text = folder.to_str()?;
    if !folder.is_absolute() {
        return None;
    }
    let mut uri = path_uri(text);
    if !uri.ends_with('/') {
        uri.push('/');
    }
    Some(uri)
}

fn percent_encode(text: &str) -> String {
    let mut encoded = String::with_capacity(text.len());
    for byte in text.bytes() {
        if byte.is_ascii_alphanumeric() || matches!(byte, b'-' | b'.' | b'_' | b'~' | b'/') {
            encoded.push(char::from(byte));
        } else {
            encoded.push_str(&format!("%{byte:02X}"));
        }
    }
    encoded
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_paths_lose_their_leading_dot_slash() {
        assert_eq!(slash_path("./progs/A.MPF"), "progs/A.MPF");
        assert_eq!(slash_path(".//progs/A.MPF"), "progs/A.MPF");
        assert_eq!(slash_path("progs/A.MPF"), "progs/A.MPF");
        assert_eq!(slash_path("../A.MPF"), "../A.MPF");
    }

    #[test]
    fn uris_are_percent_encoded() {
        assert_eq!(path_uri("progs/A B#1.MPF"), "progs/A%20B%231.MPF");
        assert_eq!(path_uri("Teil_Ä.MPF"), "Teil_%C3%84.MPF");
        assert_eq!(path_uri("100%.mpf"), "100%25.mpf");
        if cfg!(unix) {
            assert_eq!(path_uri("/tmp/x y/A.MPF"), "file:///tmp/x%20y/A.MPF");
            assert_eq!(path_uri("a\\b.mpf"), "a%5Cb.mpf");
            assert_eq!(
                folder_uri(Path::new("/work/repo")).as_deref(),
                Some("file:///work/repo/")
            );
        }
        assert_eq!(folder_uri(Path::new("relative")), None);
    }
}
