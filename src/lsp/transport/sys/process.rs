//! The process settings the server makes through the C library: the allocator's options and the
//! size of the stdio pipes' buffers. `SINUMERIK_LSP_MEASURE_WITHOUT` (`allocator`, `pipe-buffers`)
//! turns them off, for the side-by-side measurement only.

use crate::lsp::transport::measure::measured_without;

/// Blocks from this size on are mapped and unmapped on their own, so freeing them returns the memory.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD_BYTES: libc::c_int = 256 * 1024;

/// The allocator's heaps: one per core of the machines the server is measured on.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const ARENAS: libc::c_int = 2;

/// Asks glibc's allocator to keep resident memory close to what is used. It raises its threshold for
/// serving blocks by `mmap` each time such a block is freed, after which large buffers (a message's
/// body, a text, a publication) come from its heaps and stay resident when freed; and it gives each
/// thread of the blocking pool a heap of its own. A fixed threshold and two heaps keep the peak low
/// and the same from run to run. Called once, before the server starts its threads; settings made
/// through glibc's environment variables (`MALLOC_MMAP_THRESHOLD_`, `MALLOC_ARENA_MAX`) are kept.
pub fn configure_allocator() {
    if measured_without("allocator") {
        return;
    }
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        let unset = |name: &str| std::env::var_os(name).is_none();
        // SAFETY: mallopt only changes the allocator's parameters; it is called before any other
        // thread of the server exists.
        unsafe {
            if unset("MALLOC_MMAP_THRESHOLD_") {
                libc::mallopt(libc::M_MMAP_THRESHOLD, MMAP_THRESHOLD_BYTES);
            }
            if unset("MALLOC_ARENA_MAX") {
                libc::mallopt(libc::M_ARENA_MAX, ARENAS);
            }
        }
    }
}

/// The pipe buffer asked for (`/proc/sys/fs/pipe-max-size` is 1 MiB by default).
#[cfg(target_os = "linux")]
const PIPE_BUFFER_BYTES: libc::c_int = 1 << 20;

/// Enlarges the buffers of stdin and stdout when they are pipes: a message of megabytes (a large
/// `didOpen`, a publication of thousands of diagnostics) then crosses in pieces of 1 MiB instead of
/// 64 KiB, each piece a wake-up of the editor and of the server. Anything else (a terminal, a socket,
/// a file), or a refusal by the kernel, leaves them as they are: the size only changes the speed.
pub fn enlarge_stdio_buffers() {
    if measured_without("pipe-buffers") {
        return;
    }
    #[cfg(target_os = "linux")]
    for fd in [0, 1] {
        // SAFETY: fstat and fcntl only read and set properties of the descriptor, which stays open
        // for the life of the process; the status struct is plain data, zeroed before the call.
        unsafe {
            let mut status: libc::stat = std::mem::zeroed();
            if libc::fstat(fd, &mut status) == 0 && status.st_mode & libc::S_IFMT == libc::S_IFIFO {
                libc::fcntl(fd, libc::F_SETPIPE_SZ, PIPE_BUFFER_BYTES);
            }
        }
    }
}
