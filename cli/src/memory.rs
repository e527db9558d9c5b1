//! The process's allocator policy: big blocks get pages of their own, and a big scene's
//! load and prepare hand back what they freed, so that the arrays a stage frees go back to
//! the system instead of lingering as holes the next stage may not fit.
//!
//! glibc's allocator serves a block from its heap unless it is at least its mmap threshold,
//! and it raises that threshold to the size of every mapped block freed (up to 32 MiB). A
//! render frees arrays of many megabytes at every stage, so after the first stages nearly
//! everything comes from the heap, and the heap's high-water mark, not the live data, sets
//! the peak: on a 600k-face terrain 430 MB resident for 326 MB live at most. A fixed
//! threshold of 4 MiB gives 360 MB there; blocks under it (almost every allocation) are
//! served as before. At 10M faces the arrays are far above 32 MiB and were mapped anyway
//! (6.30 → 6.26 GB): there the holes are the small blocks load and prepare free, which
//! [`trim`] hands back.

/// Blocks of at least this many bytes are mapped on their own.
pub const BIG_BLOCK: usize = 4 << 20;

/// Sets the allocator's mmap threshold to [`BIG_BLOCK`] (glibc on Linux; elsewhere nothing
/// to do). Call it first thing in `main`, before any thread starts.
pub fn map_big_blocks() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use std::ffi::c_int;
        extern "C" {
            /// glibc's `mallopt(3)`.
            fn mallopt(param: c_int, value: c_int) -> c_int;
        }
        /// `M_MMAP_THRESHOLD` in glibc's `malloc.h`.
        const M_MMAP_THRESHOLD: c_int = -3;
        // SAFETY: mallopt only sets a tuning parameter of the allocator (any value is
        // accepted or refused with 0); called before any other thread exists.
        let done = unsafe { mallopt(M_MMAP_THRESHOLD, BIG_BLOCK as c_int) };
        debug_assert_eq!(done, 1, "glibc accepts a 4 MiB mmap threshold");
    }
}

/// Scenes of at least this many faces have the allocator trimmed after prepare ([`trim`]):
/// loading and preparing a 10M-face terrain leave 1.8 GB of freed pages resident (2.3 GB
/// resident for 0.53 GB live), and trimming them lowers the render's peak by 6% (6.21 →
/// 5.84 GB); on a 100k-face mesh there is nothing to gain and the walk costs about 1%.
pub const TRIM_ABOVE_FACES: usize = 1_000_000;

/// Hands the allocator's free pages back to the system (glibc's `malloc_trim`, which also
/// releases whole free pages inside its heaps); elsewhere nothing to do. Worth calling
/// after a stage that freed much more than it keeps.
pub fn trim() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    {
        use std::ffi::{c_int, c_ulong};
        extern "C" {
            /// glibc's `malloc_trim(3)`.
            fn malloc_trim(pad: c_ulong) -> c_int;
        }
        // SAFETY: malloc_trim only returns free memory to the system; it is thread-safe.
        unsafe { malloc_trim(0) };
    }
}
