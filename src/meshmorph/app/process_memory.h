// SPDX-License-Identifier: GPL-3.0-or-later
//! \file How the applications ask the C library for memory.
//!
//! A morph touches every byte it allocates once or twice, and on a virtual machine each
//! first touch of a 4 KB page is a fault costing microseconds: the full motorBike morph
//! faulted 112k pages, 0.6-0.8 s of its 3.3 s. Transparent huge pages (2 MB) cut the faults
//! to 13k, and keeping freed blocks in the heap (instead of returning them to the kernel
//! and faulting fresh pages in for the next array of the same size) to 2.6k.
#pragma once

namespace meshmorph::app
{

//! \brief Called first in an application's main() with its argv.
//!
//! - Runs the program again, once, with glibc's tunable `glibc.malloc.hugetlb=1` added to
//!   GLIBC_TUNABLES, so that malloc marks its heap for transparent huge pages (madvise
//!   mode, Debian's default). A tunable is read only when a process starts, hence the
//!   re-execution (same process id, arguments and environment). Not done when
//!   GLIBC_TUNABLES already sets it, when MESHMORPH_HUGE_PAGES=0, when the kernel has
//!   transparent huge pages off, under valgrind or a sanitizer, or with glibc before 2.35;
//!   if the re-execution fails the program simply goes on.
//! - Keeps freed blocks of up to 32 MB in the heap (mallopt M_MMAP_THRESHOLD,
//!   M_TRIM_THRESHOLD) unless GLIBC_TUNABLES sets those thresholds.
//!
//! Results do not depend on any of this; only time does.
void configure_process_memory(char** argv);

} // namespace meshmorph::app
