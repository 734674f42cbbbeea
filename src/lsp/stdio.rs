//! The process's standard input and output as the server uses them. Every publication of a large
//! program's diagnostics is megabytes of JSON, and a pipe moves them in pieces of its buffer's size
//! (64 KiB by default on Linux), each piece a wake-up of the editor and of the server: the buffers
//! are enlarged to 1 MiB, the most an unprivileged process may ask for by default, which made a
//! 7.8 MB message arrive in about a third of the time (a socket's send buffer is enlarged too, see
//! [`enlarge_stdio_buffers`]). The output is written by a thread of its own
//! straight to the file descriptor, without the copy into tokio's buffers, and the large pieces of a
//! message, which lie in pages of their own (`frozen_bytes.rs`), are handed to the pipe as pages
//! (`vmsplice`) instead of being copied: that took the same message's transfer from about 3 ms to
//! about 1.4 ms on the 2-core machine the server is measured on.

use std::io::Write;

/// The pipe buffer asked for (`/proc/sys/fs/pipe-max-size` is 1 MiB by default).
#[cfg(target_os = "linux")]
const PIPE_BUFFER_BYTES: libc::c_int = 1 << 20;

/// The send buffer asked for when stdout is a socket (the kernel doubles it, up to
/// `/proc/sys/net/core/wmem_max`).
#[cfg(target_os = "linux")]
const SOCKET_SEND_BUFFER_BYTES: libc::c_int = 2 << 20;

/// Enlarges the buffers of stdin and stdout: those of pipes, and the send buffer of stdout when it is
/// a Unix socket, as libuv (VS Code's Node.js, Neovim) makes a child's stdio. With the default
/// 208 KiB a 9.1 MB publication crossed a socket pair in about 2 ms, but one in a hundred took 10-60
/// ms on the 2-core machine the server is measured on; with 4 MiB none took over 5 ms. Anything else
/// (a terminal, a file), or a refusal by the kernel, leaves them as they are: the size only changes
/// the speed.
pub fn enlarge_stdio_buffers() {
    #[cfg(target_os = "linux")]
    {
        enlarge_buffer(0, false);
        enlarge_buffer(1, true);
    }
}

/// Enlarges the buffer of `fd` if it is a pipe, or its send buffer if it is a socket the server
/// writes to (`output`).
#[cfg(target_os = "linux")]
fn enlarge_buffer(fd: std::os::fd::RawFd, output: bool) {
    // SAFETY: fstat, fcntl and setsockopt only read and set properties of the descriptor (the
    // option's value is a valid c_int), which the caller keeps open.
    unsafe {
        let mut status: libc::stat = std::mem::zeroed();
        if libc::fstat(fd, &mut status) != 0 {
            return;
        }
        match status.st_mode & libc::S_IFMT {
            libc::S_IFIFO => {
                libc::fcntl(fd, libc::F_SETPIPE_SZ, PIPE_BUFFER_BYTES);
            }
            libc::S_IFSOCK if output => {
                libc::setsockopt(
                    fd,
                    libc::SOL_SOCKET,
                    libc::SO_SNDBUF,
                    (&SOCKET_SEND_BUFFER_BYTES as *const libc::c_int).cast(),
                    std::mem::size_of::<libc::c_int>() as libc::socklen_t,
                );
            }
            _ => {}
        }
    }
}

/// A piece of a message being written. `own_pages` says that the bytes lie in pages of their own that
/// are never written or reused (`frozen_bytes.rs`), which may then be handed to a pipe.
#[derive(Clone, Copy)]
pub struct Piece<'a> {
    pub bytes: &'a [u8],
    pub own_pages: bool,
}

impl<'a> Piece<'a> {
    /// A piece in ordinary memory: it is copied into the output.
    pub fn copied(bytes: &'a [u8]) -> Piece<'a> {
        Piece {
            bytes,
            own_pages: false,
        }
    }
}

/// Where the output thread writes whole messages.
pub trait MessageOutput: Send {
    fn write_message(&mut self, pieces: &[Piece<'_>]) -> std::io::Result<()>;
}

/// The standard output, written straight to its descriptor, without Rust's line buffering.
pub fn stdout_output() -> Box<dyn MessageOutput> {
    #[cfg(unix)]
    {
        Box::new(DescriptorOutput::new(1))
    }
    #[cfg(not(unix))]
    {
        Box::new(Copying(std::io::stdout()))
    }
}

/// Any writer, every piece copied into it.
#[cfg(not(unix))]
struct Copying<W>(W);

#[cfg(not(unix))]
impl<W: Write + Send> MessageOutput for Copying<W> {
    fn write_message(&mut self, pieces: &[Piece<'_>]) -> std::io::Result<()> {
        let parts: Vec<&[u8]> = pieces.iter().map(|piece| piece.bytes).collect();
        write_all_parts(&mut self.0, &parts)?;
        self.0.flush()
    }
}

/// An open descriptor the output owns for the life of the process (it is never closed). Pieces in
/// pages of their own are handed to the pipe with `vmsplice` when the descriptor is a pipe: the
/// kernel then refers to the pages instead of copying them, which made a 7.8 MB publication arrive
/// in about a third of the time. Everything else is copied with `writev`.
#[cfg(unix)]
pub struct DescriptorOutput {
    file: std::mem::ManuallyDrop<std::fs::File>,
    splice_pages: bool,
}

#[cfg(unix)]
impl DescriptorOutput {
    /// The output to `fd`, which must stay open for the life of the value.
    pub fn new(fd: std::os::fd::RawFd) -> DescriptorOutput {
        use std::os::fd::FromRawFd;
        // SAFETY: the caller keeps `fd` open; `ManuallyDrop` keeps the file from closing it.
        let file = unsafe { std::fs::File::from_raw_fd(fd) };
        DescriptorOutput {
            file: std::mem::ManuallyDrop::new(file),
            splice_pages: cfg!(target_os = "linux") && is_pipe(fd),
        }
    }

    fn fd(&self) -> std::os::fd::RawFd {
        use std::os::fd::AsRawFd;
        self.file.as_raw_fd()
    }
}

#[cfg(unix)]
impl MessageOutput for DescriptorOutput {
    fn write_message(&mut self, pieces: &[Piece<'_>]) -> std::io::Result<()> {
        let fd = self.fd();
        let mut rest = pieces;
        while let Some(first) = rest.first() {
            // Runs of pieces that go the same way: one system call for each run, as far as it goes.
            let by_pages = first.own_pages;
            let run = rest
                .iter()
                .take_while(|piece| piece.own_pages == by_pages)
                .count();
            let parts: Vec<&[u8]> = rest[..run].iter().map(|piece| piece.bytes).collect();
            rest = &rest[run..];
            let splice_pages = &mut self.splice_pages;
            let file = &mut *self.file;
            write_all_with(
                &parts,
                |slices| {
                    if by_pages && *splice_pages {
                        match splice_into_pipe(fd, slices) {
                            Err(error) if splice_unsupported(&error) => *splice_pages = false,
                            result => return result,
                        }
                    }
                    file.write_vectored(slices)
                },
                || {
                    wait_until_writable(fd);
                    Ok(())
                },
            )?;
        }
        Ok(())
    }
}

#[cfg(unix)]
fn is_pipe(fd: std::os::fd::RawFd) -> bool {
    // SAFETY: fstat only reads the properties of the descriptor into the zeroed struct.
    unsafe {
        let mut status: libc::stat = std::mem::zeroed();
        libc::fstat(fd, &mut status) == 0 && status.st_mode & libc::S_IFMT == libc::S_IFIFO
    }
}

/// Hands the pages of `slices` to the pipe `fd`; returns how many bytes went in.
#[cfg(target_os = "linux")]
fn splice_into_pipe(
    fd: std::os::fd::RawFd,
    slices: &[std::io::IoSlice<'_>],
) -> std::io::Result<usize> {
    // SAFETY: `IoSlice` is ABI compatible with `iovec` on Unix, and the callers only pass slices of
    // `FrozenBytes` with pages of their own, which are never written again and never reused.
    let spliced =
        unsafe { libc::vmsplice(fd, slices.as_ptr().cast::<libc::iovec>(), slices.len(), 0) };
    if spliced < 0 {
        Err(std::io::Error::last_os_error())
    } else {
        Ok(spliced as usize)
    }
}

#[cfg(all(unix, not(target_os = "linux")))]
fn splice_into_pipe(
    _fd: std::os::fd::RawFd,
    _slices: &[std::io::IoSlice<'_>],
) -> std::io::Result<usize> {
    Err(std::io::Error::from_raw_os_error(libc::ENOSYS))
}

/// Errors after which the output copies instead: the descriptor or the system cannot splice. No
/// byte went out in the call that failed.
#[cfg(unix)]
fn splice_unsupported(error: &std::io::Error) -> bool {
    matches!(
        error.raw_os_error(),
        Some(libc::EINVAL | libc::EBADF | libc::ENOSYS | libc::EPERM)
    )
}

/// Waits until `fd` takes more output; used when the editor made the pipe non-blocking.
#[cfg(unix)]
fn wait_until_writable(fd: std::os::fd::RawFd) {
    let mut poll = libc::pollfd {
        fd,
        events: libc::POLLOUT,
        revents: 0,
    };
    // SAFETY: one valid pollfd; the result only decides when the write is tried again.
    unsafe {
        libc::poll(&mut poll, 1, -1);
    }
}

/// Slices per system call: the most `writev` and `vmsplice` take (`IOV_MAX` on Linux).
const MOST_SLICES: usize = 1024;

/// Writes all of `parts` with `write`, which takes a batch of slices and returns how many bytes it
/// wrote; `wait` is called when the output would block.
fn write_all_with(
    parts: &[&[u8]],
    mut write: impl FnMut(&[std::io::IoSlice<'_>]) -> std::io::Result<usize>,
    mut wait: impl FnMut() -> std::io::Result<()>,
) -> std::io::Result<()> {
    let mut slices: Vec<std::io::IoSlice<'_>> = parts
        .iter()
        .filter(|part| !part.is_empty())
        .map(|part| std::io::IoSlice::new(part))
        .collect();
    let mut remaining = &mut slices[..];
    while !remaining.is_empty() {
        let batch = remaining.len().min(MOST_SLICES);
        match write(&remaining[..batch]) {
            Ok(0) => return Err(std::io::ErrorKind::WriteZero.into()),
            Ok(written) => std::io::IoSlice::advance_slices(&mut remaining, written),
            Err(error) if error.kind() == std::io::ErrorKind::Interrupted => {}
            Err(error) if error.kind() == std::io::ErrorKind::WouldBlock => wait()?,
            Err(error) => return Err(error),
        }
    }
    Ok(())
}

/// Writes all of `parts` with as few system calls as the output allows.
#[cfg(any(test, not(unix)))]
pub fn write_all_parts(output: &mut dyn Write, parts: &[&[u8]]) -> std::io::Result<()> {
    write_all_with(
        parts,
        |slices| output.write_vectored(slices),
        || Err(std::io::ErrorKind::WouldBlock.into()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer that takes at most `limit` bytes a call, as a full pipe does.
    struct Trickle {
        written: Vec<u8>,
        limit: usize,
    }

    impl Write for Trickle {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            let length = bytes.len().min(self.limit);
            self.written.extend_from_slice(&bytes[..length]);
            Ok(length)
        }

        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn every_part_is_written_in_order_however_little_each_call_takes() {
        for limit in [1, 3, 7, 1000] {
            let mut output = Trickle {
                written: Vec::new(),
                limit,
            };
            write_all_parts(&mut output, &[b"head", b"", b"middle part", b"tail"]).unwrap();
            assert_eq!(output.written, b"headmiddle parttail", "limit {limit}");
        }
    }
}

#[cfg(all(test, target_os = "linux"))]
mod pipe_tests {
    use super::*;
    use crate::lsp::frozen_bytes::FrozenBytes;
    use std::io::Read;
    use std::os::fd::FromRawFd;

    fn pipe(buffer_bytes: libc::c_int) -> (std::fs::File, std::fs::File) {
        let mut fds = [0; 2];
        // SAFETY: pipe writes two new descriptors into the array; each is owned by one File below.
        unsafe {
            assert_eq!(libc::pipe(fds.as_mut_ptr()), 0);
            libc::fcntl(fds[1], libc::F_SETPIPE_SZ, buffer_bytes);
            (
                std::fs::File::from_raw_fd(fds[0]),
                std::fs::File::from_raw_fd(fds[1]),
            )
        }
    }

    fn pattern(length: usize, seed: u8) -> Vec<u8> {
        (0..length)
            .map(|index| (index % 253) as u8 ^ seed)
            .collect()
    }

    /// The pages handed to the pipe stay as they were after the bytes are dropped and their memory
    /// is mapped again and overwritten, and the reader gets every piece in order.
    #[test]
    fn pieces_read_back_in_order_after_their_pages_were_dropped_and_reused() {
        use std::os::fd::AsRawFd;
        let (mut reader, writer) = pipe(1 << 20);
        let mut output = DescriptorOutput::new(writer.as_raw_fd());
        assert!(output.splice_pages, "a pipe is spliced into");
        let frozen: Vec<FrozenBytes> = (0..3)
            .map(|seed| FrozenBytes::new(pattern(20_000 + seed as usize * 4099, seed)))
            .collect();
        assert!(frozen.iter().all(FrozenBytes::has_own_pages));
        let pieces = [
            Piece::copied(b"head"),
            Piece {
                bytes: &frozen[0],
                own_pages: true,
            },
            Piece {
                bytes: &frozen[1][1..],
                own_pages: true,
            },
            Piece::copied(b","),
            Piece {
                bytes: &frozen[2],
                own_pages: true,
            },
            Piece::copied(b"tail"),
        ];
        let mut expected = Vec::new();
        for piece in &pieces {
            expected.extend_from_slice(piece.bytes);
        }
        // Everything fits the pipe: the write returns before anything is read.
        output.write_message(&pieces).unwrap();
        drop(frozen);
        let overwritten: Vec<FrozenBytes> = (0..6)
            .map(|_| FrozenBytes::new(vec![0xEE; 40_000]))
            .collect();
        let mut received = vec![0; expected.len()];
        reader.read_exact(&mut received).unwrap();
        assert!(received == expected, "the bytes in the pipe changed");
        assert!(overwritten.iter().all(|bytes| bytes[0] == 0xEE));
    }

    /// A message larger than the pipe goes out whole while the reader takes it in small reads.
    #[test]
    fn a_message_larger_than_the_pipe_arrives_whole() {
        use std::os::fd::AsRawFd;
        let (mut reader, writer) = pipe(4096);
        let frozen: Vec<FrozenBytes> = (0..40)
            .map(|seed| FrozenBytes::new(pattern(17_000 + seed as usize, seed as u8)))
            .collect();
        let mut expected = b"head".to_vec();
        for bytes in &frozen {
            expected.extend_from_slice(bytes);
        }
        let reading = std::thread::spawn(move || {
            let mut received = Vec::new();
            let mut buffer = [0; 1000];
            loop {
                match reader.read(&mut buffer) {
                    Ok(0) | Err(_) => return received,
                    Ok(count) => received.extend_from_slice(&buffer[..count]),
                }
            }
        });
        let mut output = DescriptorOutput::new(writer.as_raw_fd());
        let mut pieces = vec![Piece::copied(b"head")];
        pieces.extend(frozen.iter().map(|bytes| Piece {
            bytes,
            own_pages: true,
        }));
        output.write_message(&pieces).unwrap();
        // The reader sees the end once the only descriptor of the writing end is closed.
        drop(writer);
        let received = reading.join().unwrap();
        assert_eq!(received.len(), expected.len());
        assert!(received == expected);
    }

    /// A descriptor that is not a pipe is written by copying.
    #[test]
    fn a_file_is_written_by_copying() {
        use std::os::fd::AsRawFd;
        let path = std::env::temp_dir().join(format!("sinumerik-lsp-stdio-{}", std::process::id()));
        let file = std::fs::File::create(&path).unwrap();
        let mut output = DescriptorOutput::new(file.as_raw_fd());
        assert!(!output.splice_pages);
        let frozen = FrozenBytes::new(pattern(30_000, 7));
        output
            .write_message(&[
                Piece::copied(b"head"),
                Piece {
                    bytes: &frozen,
                    own_pages: true,
                },
            ])
            .unwrap();
        drop(file);
        let written = std::fs::read(&path).unwrap();
        let _ = std::fs::remove_file(&path);
        assert_eq!(&written[..4], b"head");
        assert!(written[4..] == frozen[..]);
    }
}

#[cfg(all(test, target_os = "linux"))]
mod buffer_tests {
    use super::*;
    use std::os::fd::AsRawFd;

    fn send_buffer(fd: std::os::fd::RawFd) -> libc::c_int {
        let mut value: libc::c_int = 0;
        let mut length = std::mem::size_of::<libc::c_int>() as libc::socklen_t;
        // SAFETY: getsockopt writes one c_int into `value`, whose size `length` gives.
        unsafe {
            libc::getsockopt(
                fd,
                libc::SOL_SOCKET,
                libc::SO_SNDBUF,
                (&mut value as *mut libc::c_int).cast(),
                &mut length,
            );
        }
        value
    }

    #[test]
    fn the_send_buffer_of_an_output_socket_grows_as_far_as_the_system_allows() {
        let (output, _reader) = std::os::unix::net::UnixStream::pair().unwrap();
        let before = send_buffer(output.as_raw_fd());
        enlarge_buffer(output.as_raw_fd(), true);
        let after = send_buffer(output.as_raw_fd());
        let most: libc::c_int = std::fs::read_to_string("/proc/sys/net/core/wmem_max")
            .ok()
            .and_then(|text| text.trim().parse().ok())
            .unwrap_or(0);
        // The kernel doubles what it is asked for, up to twice the system's maximum.
        let expected = (2 * SOCKET_SEND_BUFFER_BYTES).min(2 * most).max(before);
        assert_eq!(after, expected, "before {before}, maximum {most}");
    }

    #[test]
    fn an_input_socket_is_left_as_it_is() {
        let (input, _writer) = std::os::unix::net::UnixStream::pair().unwrap();
        let before = send_buffer(input.as_raw_fd());
        enlarge_buffer(input.as_raw_fd(), false);
        assert_eq!(send_buffer(input.as_raw_fd()), before);
    }
}
