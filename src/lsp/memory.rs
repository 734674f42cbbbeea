//! How the server asks the allocator to keep its resident memory close to what it uses. Every
//! publication of a large program's diagnostics writes megabytes of JSON, and analyses run on several
//! threads of the blocking pool. glibc's allocator raises its threshold for serving blocks by `mmap`
//! each time such a block is freed, after which these buffers come from its heaps and stay resident
//! when freed, and it gives each thread a heap of its own: resident memory then grows with every
//! edit. A fixed threshold and two heaps keep it flat (measured with `benches/lsp_latency.rs`). The
//! pieces of a large message arriving have their pages mapped at once.

/// Blocks from this size on are mapped and unmapped on their own, so freeing them returns the memory.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const MMAP_THRESHOLD_BYTES: libc::c_int = 256 * 1024;

/// The allocator's heaps: one per core of the machines the server is measured on.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
const ARENAS: libc::c_int = 2;

/// Sets the allocator's options; called once, before the server starts its threads. Settings made by
/// the user through glibc's environment variables (`MALLOC_MMAP_THRESHOLD_`, `MALLOC_ARENA_MAX`)
/// are kept.
pub fn configure_allocator() {
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

/// An empty buffer with room for `capacity` bytes whose pages the system maps at once, where it can.
/// A large message arrives in pieces of half a megabyte, each freshly mapped by the allocator:
/// mapping a piece's 128 pages in one call took about 60% of the time of 128 page faults on the
/// machine the server is measured on (33 MB: 9 ms against 15 ms). A system that does not know the
/// advice leaves the pages to be mapped as they are written.
pub fn populated_buffer(capacity: usize) -> Vec<u8> {
    #[allow(unused_mut)]
    let mut buffer = Vec::with_capacity(capacity);
    #[cfg(target_os = "linux")]
    {
        const PAGE_BYTES: usize = 4096;
        let start = buffer.as_mut_ptr() as usize;
        let aligned = start.next_multiple_of(PAGE_BYTES);
        let end = (start + capacity) & !(PAGE_BYTES - 1);
        if end > aligned {
            // SAFETY: advice on whole pages inside the buffer's own allocation, whose bytes are
            // not initialized yet; populating maps pages without changing any byte the program
            // could read.
            unsafe {
                libc::madvise(
                    aligned as *mut libc::c_void,
                    end - aligned,
                    libc::MADV_POPULATE_WRITE,
                );
            }
        }
    }
    buffer
}
