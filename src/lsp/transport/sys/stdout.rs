//! The process's stdout as the writer uses it: written straight to the descriptor (without Rust's
//! line buffering), and, when it is a pipe, the pieces that lie in frozen pages of their own
//! (`frozen.rs`) handed to the pipe with `vmsplice` instead of copied into it. A copy into a pipe
//! writes every byte into pages the kernel allocates for it; a publication of 31,000 findings is
//! 7.8 MB, about 1,900 such pages per keystroke, and on the virtual machines the server is measured
//! on, runs of those allocations are served by pages the host has taken back, which made runs of
//! keystrokes take 20-25 ms instead of 4-5 ms (`docs/performance.md`). Handed over, the pages are
//! the publisher's own, already present.

use super::frozen::FrozenBytes;
use crate::lsp::transport::measure::measured_without;
use std::io::{IoSlice, Write};

/// A piece of a message being written.
#[derive(Clone, Copy)]
pub struct OutputPiece<'a> {
    bytes: &'a [u8],
    /// The bytes lie in frozen pages of their own, which may be handed to a pipe.
    own_pages: bool,
}

impl<'a> OutputPiece<'a> {
    /// Bytes in ordinary memory: they are copied into the output.
    pub fn copied(bytes: &'a [u8]) -> OutputPiece<'a> {
        OutputPiece {
            bytes,
            own_pages: false,
        }
    }

    /// The first `length` bytes of frozen bytes.
    pub fn frozen(bytes: &'a FrozenBytes, length: usize) -> OutputPiece<'a> {
        let slice = bytes.as_slice();
        OutputPiece {
            bytes: &slice[..length.min(slice.len())],
            own_pages: bytes.has_own_pages(),
        }
    }
}

/// The process's standard output, which stays open for the life of the process.
pub struct StdoutOutput {
    #[cfg(unix)]
    file: std::mem::ManuallyDrop<std::fs::File>,
    #[cfg(not(unix))]
    file: std::io::Stdout,
    splice_pages: bool,
}

impl StdoutOutput {
    pub fn new() -> StdoutOutput {
        #[cfg(unix)]
        {
            use std::os::fd::FromRawFd;
            // SAFETY: descriptor 1 is open for the life of the process; `ManuallyDrop` keeps the
            // file from ever closing it.
            let file = unsafe { std::fs::File::from_raw_fd(1) };
            StdoutOutput::on(std::mem::ManuallyDrop::new(file))
        }
        #[cfg(not(unix))]
        StdoutOutput {
            file: std::io::stdout(),
            splice_pages: false,
        }
    }

    #[cfg(unix)]
    fn on(file: std::mem::ManuallyDrop<std::fs::File>) -> StdoutOutput {
        use std::os::fd::AsRawFd;
        let splice_pages =
            cfg!(target_os = "linux") && is_pipe(file.as_raw_fd()) && !measured_without("vmsplice");
        StdoutOutput { file, splice_pages }
    }

    /// Writes the pieces in order, each run of frozen pieces with one `vmsplice` as far as it goes
    /// and each run of the others with one `writev`.
    pub fn write_message(&mut self, pieces: &[OutputPiece<'_>]) -> std::io::Result<()> {
        let mut rest = pieces;
        while let Some(first) = rest.first() {
            let by_pages = first.own_pages && self.splice_pages;
            let run = rest
                .iter()
                .take_while(|piece| (piece.own_pages && self.splice_pages) == by_pages)
                .count();
            let mut slices: Vec<IoSlice<'_>> = rest[..run]
                .iter()
                .filter(|piece| !piece.bytes.is_empty())
                .map(|piece| IoSlice::new(piece.bytes))
                .collect();
            rest = &rest[run..];
            let mut remaining = &mut slices[..];
            while !remaining.is_empty() {
                let batch = remaining.len().min(MOST_SLICES);
                let written = if by_pages && self.splice_pages {
                    match self.splice(&remaining[..batch]) {
                        // No byte went out: the descriptor or the system cannot splice.
                        Err(error) if splice_unsupported(&error) => {
                            self.splice_pages = false;
                            continue;
                        }
                        result => result,
                    }
                } else {
                    self.file.write_vectored(&remaining[..batch])
                };
                match written {
                    Ok(0) => return Err(std::io::ErrorKind::WriteZero.into()),
                    Ok(written) => IoSlice::advance_slices(&mut remaining, written),
                    Err(error) if error.kind() == std::io::ErrorKind::Interrupted => {}
                    Err(error) if error.kind() == std::io::ErrorKind::WouldBlock => {
                        self.wait_until_writable()
                    }
                    Err(error) => return Err(error),
                }
            }
        }
        Ok(())
    }

    /// Hands the pages of `slices` to the pipe; returns how many bytes went in.
    #[cfg(target_os = "linux")]
    fn splice(&self, slices: &[IoSlice<'_>]) -> std::io::Result<usize> {
        use std::os::fd::AsRawFd;
        // SAFETY: `IoSlice` is ABI compatible with `iovec` on Unix, and `write_message` passes only
        // slices of `FrozenBytes` with pages of their own (`OutputPiece::frozen`), which are never
        // written again and are unmapped, never reused, when dropped.
        let spliced = unsafe {
            libc::vmsplice(
                self.file.as_raw_fd(),
                slices.as_ptr().cast::<libc::iovec>(),
                slices.len(),
                0,
            )
        };
        if spliced < 0 {
            Err(std::io::Error::last_os_error())
        } else {
            Ok(spliced as usize)
        }
    }

    #[cfg(not(target_os = "linux"))]
    fn splice(&self, _slices: &[IoSlice<'_>]) -> std::io::Result<usize> {
        Err(std::io::ErrorKind::Unsupported.into())
    }

    /// Waits until the output takes more; used when the editor made the pipe non-blocking.
    fn wait_until_writable(&self) {
        #[cfg(unix)]
        {
            use std::os::fd::AsRawFd;
            let mut poll = libc::pollfd {
                fd: self.file.as_raw_fd(),
                events: libc::POLLOUT,
                revents: 0,
            };
            // SAFETY: one valid pollfd; the result only decides when the write is tried again.
            unsafe {
                libc::poll(&mut poll, 1, -1);
            }
        }
    }
}

/// Slices per system call: the most `writev` and `vmsplice` take (`IOV_MAX` on Linux).
const MOST_SLICES: usize = 1024;

#[cfg(unix)]
fn is_pipe(fd: std::os::fd::RawFd) -> bool {
    // SAFETY: fstat only reads the properties of the descriptor into the zeroed struct.
    unsafe {
        let mut status: libc::stat = std::mem::zeroed();
        libc::fstat(fd, &mut status) == 0 && status.st_mode & libc::S_IFMT == libc::S_IFIFO
    }
}

/// Errors after which the output copies instead: the descriptor or the system cannot splice.
fn splice_unsupported(error: &std::io::Error) -> bool {
    error.kind() == std::io::ErrorKind::Unsupported
        || matches!(
            error.raw_os_error(),
            Some(libc::EINVAL | libc::EBADF | libc::ENOSYS | libc::EPERM)
        )
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;
    use crate::lsp::transport::sys::frozen::tests::pattern;
    use std::io::Read;
    use std::os::fd::FromRawFd;

    fn pipe() -> (std::fs::File, std::fs::File) {
        let mut fds = [0; 2];
        // SAFETY: pipe writes two new descriptors into the array; each is owned by one File below.
        unsafe {
            assert_eq!(libc::pipe(fds.as_mut_ptr()), 0);
            libc::fcntl(fds[1], libc::F_SETPIPE_SZ, 1 << 20);
            (
                std::fs::File::from_raw_fd(fds[0]),
                std::fs::File::from_raw_fd(fds[1]),
            )
        }
    }

    /// The pages handed to the pipe stay as they were after the bytes are dropped and their memory
    /// is mapped again and overwritten, and the reader gets every piece in order, however small
    /// the pipe's buffer against the message.
    #[test]
    fn pieces_read_back_in_order_after_their_pages_were_dropped_and_reused() {
        let (mut reader, writer) = pipe();
        let mut output = StdoutOutput::on(std::mem::ManuallyDrop::new(writer));
        assert!(output.splice_pages, "a pipe is spliced into");
        let frozen: Vec<FrozenBytes> = (0..3)
            .map(|seed| FrozenBytes::new(pattern(20_000 + seed as usize * 4099, seed)))
            .collect();
        assert!(frozen.iter().all(FrozenBytes::has_own_pages));
        let mut expected = b"head".to_vec();
        expected.extend_from_slice(&frozen[0].as_slice()[..19_999]);
        expected.extend_from_slice(frozen[1].as_slice());
        expected.push(b',');
        expected.extend_from_slice(frozen[2].as_slice());
        expected.extend_from_slice(b"tail");
        let pieces = [
            OutputPiece::copied(b"head"),
            OutputPiece::frozen(&frozen[0], 19_999),
            OutputPiece::frozen(&frozen[1], usize::MAX),
            OutputPiece::copied(b","),
            OutputPiece::frozen(&frozen[2], usize::MAX),
            OutputPiece::copied(b"tail"),
        ];
        output.write_message(&pieces).unwrap();
        drop(frozen);
        // The same sizes mapped again and overwritten: the pipe must still give the old bytes.
        let reused: Vec<FrozenBytes> = (0..3)
            .map(|seed| FrozenBytes::new(vec![0xEE; 20_000 + seed * 4099]))
            .collect();
        let mut read = vec![0; expected.len()];
        reader.read_exact(&mut read).unwrap();
        assert!(
            read == expected,
            "the pipe gave other bytes than were written"
        );
        drop(reused);
        // The file is the pipe's writing end, owned here: closing it ends the reader's input.
        let writer = std::mem::ManuallyDrop::into_inner(output.file);
        drop(writer);
    }

    /// A message larger than the pipe's buffer goes out whole while the reader reads it.
    #[test]
    fn a_message_larger_than_the_pipe_goes_out_whole() {
        let (mut reader, writer) = pipe();
        let frozen: Vec<FrozenBytes> = (0..40)
            .map(|seed| FrozenBytes::new(pattern(64 * 1024 + seed as usize, seed)))
            .collect();
        let expected: Vec<u8> = frozen
            .iter()
            .flat_map(|bytes| bytes.as_slice().iter().copied())
            .collect();
        let reading = std::thread::spawn(move || {
            let mut all = Vec::new();
            reader.read_to_end(&mut all).unwrap();
            all
        });
        let mut output = StdoutOutput::on(std::mem::ManuallyDrop::new(writer));
        let pieces: Vec<OutputPiece<'_>> = frozen
            .iter()
            .map(|bytes| OutputPiece::frozen(bytes, usize::MAX))
            .collect();
        output.write_message(&pieces).unwrap();
        drop(std::mem::ManuallyDrop::into_inner(output.file));
        assert!(reading.join().unwrap() == expected);
    }
}
