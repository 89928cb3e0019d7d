// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Keeping freed arrays of a mesh's size in the heap for the next call.
#pragma once

namespace meshmorph
{

//! \brief Has glibc's malloc serve blocks up to 32 MB (its largest allowed threshold) from
//! the heap, and keep up to 256 MB freed at its top, instead of mapping and unmapping them
//! on every call.
//!
//! A variant's check allocates and frees a dozen arrays of the mesh's size (face and cell
//! geometry, metrics). Mapped afresh each time, every page of them faults on first touch:
//! in a Python process, where glibc's own adaptive threshold did not take hold, that was
//! half of `DesignStudy.evaluate` and two thirds of `is_valid` on the 353k-cell motorBike
//! (benchmarks/morph/variant_speed.sh). Peak memory is unchanged; what was freed is
//! kept for reuse until the process ends. A threshold the user set
//! (MALLOC_MMAP_THRESHOLD_ or GLIBC_TUNABLES) is left alone; elsewhere than glibc, nothing.
void keep_freed_blocks_in_heap();

} // namespace meshmorph
