// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Fingerprints that tie a design set-up to what it was computed from: the points, the
//! topology (faces, owner, neighbour, patches), the morphDict as parsed, and the
//! pointDisplacement field its variables read. A set-up whose
//! fingerprints differ from the case's is stale and refused, never silently reused.
//!
//! 64-bit FNV-1a over the raw bytes (8-byte words at a time), printed as 16 hex digits: a change
//! detector, not a cryptographic hash (a case is not an adversary).
#pragma once

#include <string>
#include <string_view>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph::io
{
class FoamDictionary;
}

namespace meshmorph::design
{

//! The fingerprint of `bytes`, 16 lower-case hex digits.
std::string fingerprint(std::string_view bytes);

//! Of the point coordinates' bits (any change of any coordinate changes it).
std::string points_fingerprint(const Points& points);

//! Of the faces, owner, neighbour and the patches' names, starts and sizes.
std::string topology_fingerprint(const PolyMesh& mesh);

//! Of a parsed dictionary: every keyword and value token after `#include` and `$var`
//! substitution, so an edited included file counts as an edit, a comment does not. The
//! top-level `untangle`, `maxUntangleCells` and `newCheckFailures`, which only judge
//! variants, do not count.
std::string dictionary_fingerprint(const io::FoamDictionary& dict);

} // namespace meshmorph::design
