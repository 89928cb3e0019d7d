// SPDX-License-Identifier: GPL-3.0-or-later
//! \file How the applications ask the C library for memory.
//!
//! A morph touches every byte it allocates once or twice, and on a virtual machine each
//! first touch of a 4 KB page is a fault costing microseconds: the full motorBike morph
//! once faulted 112k pages, 0.6-0.8 s of its 3.3 s. Keeping freed blocks in the heap
//! (instead of returning them to the kernel and faulting fresh pages in for the next array
//! of the same size) took most of that off.
//!
//! Transparent huge pages (2 MB) cut the faults further, but they are opt-in: with the
//! kernel's defrag setting `madvise` (Debian's default) a fault in a region marked for huge
//! pages compacts memory on the spot when free memory is fragmented, which it is whenever
//! another program ran before (a solver, moveMesh, a mesher). Measured on the motorBike
//! morph (5% lift, 2 cores), each run right after a moveMesh of the same mesh: 1.28-1.37 s
//! with huge pages (0.39-0.49 s system time), 1.16-1.22 s without (0.15-0.17 s); back to back
//! with nothing in between: 1.17-1.19 s with, 1.18-1.22 s without. An optimiser's loop is
//! the first case.
#pragma once

namespace meshmorph::app
{

//! \brief Called first in an application's main() with its argv.
//!
//! - With MESHMORPH_HUGE_PAGES=1 only: runs the program again, once, with glibc's tunable
//!   `glibc.malloc.hugetlb=1` added to GLIBC_TUNABLES, so that malloc marks its heap for
//!   transparent huge pages (madvise mode, Debian's default). A tunable is read only when a
//!   process starts, hence the re-execution (same process id, arguments and environment).
//!   Not done when GLIBC_TUNABLES already sets it, when the kernel has transparent huge
//!   pages off, under valgrind or a sanitizer, or with glibc before 2.35; if the
//!   re-execution fails the program simply goes on.
//! - Keeps freed blocks of up to 32 MB in the heap (mallopt M_MMAP_THRESHOLD,
//!   M_TRIM_THRESHOLD) unless GLIBC_TUNABLES sets those thresholds.
//!
//! Results do not depend on any of this; only time does.
void configure_process_memory(char** argv);

} // namespace meshmorph::app
