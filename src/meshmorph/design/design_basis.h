// SPDX-License-Identifier: GPL-3.0-or-later
//! \file The stored set-up of a design study (`morphMesh -variables`): for every design
//! variable j its unit prescription P_j at the constrained points and its volume field F_j
//! at every mesh point, so that a variant is x = x0 + sum_j a_j F_j and a gradient
//! dJ/da_j = sum_i g_i . F_j(i) (the transpose product) without any fit.
//!
//! File `constant[/<region>]/designBasis` (version 2), written atomically:
//! - line 1: `meshMorph designBasis 2`
//! - line 2: a one-line JSON header (DesignBasisHeader: fingerprints of the points, the
//!   topology and the morphDict, the instance the points were read from, variable names and
//!   bounds, method, point count, the invalid cells of the mesh before, the storage)
//! - binary, little-endian, per variable a block: 4 doubles of fit statistics (max
//!   constraint error, relative constraint error, centres, fit seconds), int64 c_j, the
//!   point labels (int64, c_j), P_j (c_j x 3 doubles, row-major), then with storage `fields`
//!   F_j (nPoints x 3 doubles, row-major); nothing after the last block.
//!   - `fields`: the labels are every point variable j constrains (variables constrain
//!     different points: a handle is constrained only in its own variable's set).
//!   - `shared` (shared_design_fit.h): the labels are the points P_j moves (not zero), and
//!     there is no field: the variables share one fit, chosen again when the file is read.
//! The blocks are read one at a time, so applying a variant or a gradient needs memory for
//! one field, not for all. Version 1 is version 2 with storage `fields` and is still read.
#pragma once

#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/types.h"

namespace meshmorph::design
{

//! What a set-up was computed from and for.
struct DesignBasisHeader
{
    static constexpr int current_version = 2;
    int version = current_version;
    std::string points_fingerprint, topology_fingerprint, dict_fingerprint;
    std::string instance; //!< the time the points were read from ("constant" or a time)
    std::string method;
    Index n_points = 0;
    std::vector<std::string> names;
    std::vector<std::optional<std::pair<double, double>>> bounds;
    Index negative_volume_cells_before = 0;
    Index wrong_pyramids_before = 0;
    bool shared = false; //!< storage `shared` (else `fields`)
    //! shared: the variable whose constraints the others share (the first that moves).
    Index shared_template = -1;
    //! The rows of a block's field: nPoints (fields) or 0 (shared).
    Index field_rows() const { return shared ? 0 : n_points; }
};

//! The statistics of one variable's fit, stored with its fields.
struct VariableFit
{
    double max_constraint_error = 0.0;
    double relative_constraint_error = 0.0;
    double centres = 0.0;
    double seconds = 0.0;
};

//! One variable's block.
struct VariableBlock
{
    VariableFit fit;
    std::vector<Index> constrained; //!< the points variable j prescribes (sorted)
    Points prescribed;              //!< constrained.size() x 3, P_j
    Points field;                   //!< header.field_rows() x 3, F_j
};

//! Writes a set-up block by block into a temporary file; commit() renames it over the
//! target, so that an interrupted set-up leaves the old file (or none).
class DesignBasisWriter
{
public:
    //! \throw IoError naming the target.
    DesignBasisWriter(const std::filesystem::path& target, const DesignBasisHeader& header);
    ~DesignBasisWriter(); //!< removes the temporary unless committed
    DesignBasisWriter(const DesignBasisWriter&) = delete;
    DesignBasisWriter& operator=(const DesignBasisWriter&) = delete;

    //! \pre called once per variable, in order, with the header's point count.
    void append(const VariableBlock& block);
    //! \throw IoError (the target is then unchanged) or InvalidInput if blocks are missing.
    void commit();

private:
    std::filesystem::path target_, temp_;
    std::ofstream out_;
    const DesignBasisHeader& header_;
    std::size_t written_ = 0;
    bool committed_ = false;
};

//! Reads a set-up: the header at once, the blocks one at a time.
class DesignBasisReader
{
public:
    //! \throw IoError if the file cannot be opened; ParseError naming the file for a foreign
    //! file, another version, a bad header or a size that does not match the header.
    explicit DesignBasisReader(const std::filesystem::path& path);

    const DesignBasisHeader& header() const { return header_; }
    const std::filesystem::path& path() const { return path_; }
    //! The next variable's block into `block` (buffers reused). \throw ParseError if truncated.
    void next(VariableBlock& block);
    //! Past the next variable's block without reading its values.
    void skip();
    //! Back to the first block.
    void rewind();

private:
    void check_blocks(const std::function<ParseError(const std::string&)>& bad);

    std::filesystem::path path_;
    std::ifstream in_;
    DesignBasisHeader header_;
    std::streamoff blocks_start_ = 0;
};

//! `<mesh case>/constant[/<region>]/designBasis`.
std::filesystem::path design_basis_path(const std::filesystem::path& mesh_case,
                                        const std::string& region);

} // namespace meshmorph::design
