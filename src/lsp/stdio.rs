//! The process's standard input and output as the server uses them. Every publication of a large
//! program's diagnostics is megabytes of JSON, and a pipe moves them in pieces of its buffer's size
//! (64 KiB by default on Linux), each piece a wake-up of the editor and of the server: the buffers
//! are enlarged to 1 MiB, the most an unprivileged process may ask for by default, which made a
//! 7.8 MB message arrive in about a third of the time. The output is written by a thread of its own
//! straight to the file descriptor, without the copy into tokio's buffers.

use std::io::Write;

/// The pipe buffer asked for (`/proc/sys/fs/pipe-max-size` is 1 MiB by default).
#[cfg(target_os = "linux")]
const PIPE_BUFFER_BYTES: libc::c_int = 1 << 20;

/// Enlarges the buffers of stdin and stdout where they are pipes. Anything else (a terminal, a file,
/// a socket), or a refusal by the kernel, leaves them as they are: the size only changes the speed.
pub fn enlarge_pipe_buffers() {
    #[cfg(target_os = "linux")]
    for fd in [0, 1] {
        // SAFETY: fstat and fcntl only read and set properties of the descriptor; 0 and 1 stay open
        // for the whole life of the process.
        unsafe {
            let mut status: libc::stat = std::mem::zeroed();
            if libc::fstat(fd, &mut status) == 0 && status.st_mode & libc::S_IFMT == libc::S_IFIFO {
                libc::fcntl(fd, libc::F_SETPIPE_SZ, PIPE_BUFFER_BYTES);
            }
        }
    }
}

/// The standard output without Rust's line buffering: the server writes whole messages.
pub fn raw_stdout() -> Box<dyn Write + Send> {
    #[cfg(unix)]
    {
        use std::os::fd::FromRawFd;
        // SAFETY: descriptor 1 is open for the life of the process; `ManuallyDrop` keeps the file
        // from closing it.
        let file = unsafe { std::fs::File::from_raw_fd(1) };
        Box::new(Unclosed(std::mem::ManuallyDrop::new(file)))
    }
    #[cfg(not(unix))]
    {
        Box::new(std::io::stdout())
    }
}

#[cfg(unix)]
struct Unclosed(std::mem::ManuallyDrop<std::fs::File>);

#[cfg(unix)]
impl Write for Unclosed {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.0.write(bytes)
    }

    fn write_vectored(&mut self, parts: &[std::io::IoSlice<'_>]) -> std::io::Result<usize> {
        self.0.write_vectored(parts)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.0.flush()
    }
}

/// Writes all of `parts` with as few system calls as the output allows.
pub fn write_all_parts(output: &mut dyn Write, parts: &[&[u8]]) -> std::io::Result<()> {
    let mut slices: Vec<std::io::IoSlice<'_>> = parts
        .iter()
        .filter(|part| !part.is_empty())
        .map(|part| std::io::IoSlice::new(part))
        .collect();
    let mut remaining = &mut slices[..];
    while !remaining.is_empty() {
        match output.write_vectored(remaining) {
            Ok(0) => return Err(std::io::ErrorKind::WriteZero.into()),
            Ok(written) => std::io::IoSlice::advance_slices(&mut remaining, written),
            Err(error) if error.kind() == std::io::ErrorKind::Interrupted => {}
            Err(error) => return Err(error),
        }
    }
    Ok(())
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
