//! How the server asks the allocator to keep its resident memory close to what it uses. Every
//! publication of a large program's diagnostics writes megabytes of JSON, and analyses run on several
//! threads of the blocking pool. glibc's allocator raises its threshold for serving blocks by `mmap`
//! each time such a block is freed, after which these buffers come from its heaps and stay resident
//! when freed, and it gives each thread a heap of its own: resident memory then grows with every
//! edit. A fixed threshold and two heaps keep it flat (measured with `benches/lsp_latency.rs`).
//! Large transient buffers (the text of a `didOpen`) ask for huge pages, which are filled far faster.

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

/// The size of a huge page on the machines the server runs on (x86-64 and most arm64 kernels).
#[cfg(target_os = "linux")]
const HUGE_PAGE_BYTES: usize = 2 << 20;

/// An empty buffer with room for `capacity` bytes, which the system backs with huge pages where it
/// can (for buffers of several of them). Filling 32 MB of fresh memory, as reading the `didOpen` of a
/// large program does, took 15–19 ms with a page fault for every 4 KiB page on the machine the server
/// is measured on, and under 3 ms with 2 MiB pages. The advice changes nothing but the page size; a
/// system without transparent huge pages ignores it.
pub fn large_buffer(capacity: usize) -> Vec<u8> {
    #[allow(unused_mut)]
    let mut buffer = Vec::with_capacity(capacity);
    #[cfg(target_os = "linux")]
    if capacity >= 2 * HUGE_PAGE_BYTES {
        let start = buffer.as_mut_ptr() as usize;
        let aligned = start.next_multiple_of(HUGE_PAGE_BYTES);
        let end = (start + capacity) & !(HUGE_PAGE_BYTES - 1);
        if end > aligned {
            // SAFETY: advice on whole pages inside the buffer's own allocation, which nothing uses
            // yet; it only asks for larger pages and cannot change any memory.
            unsafe {
                libc::madvise(
                    aligned as *mut libc::c_void,
                    end - aligned,
                    libc::MADV_HUGEPAGE,
                );
            }
        }
    }
    buffer
}
