// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Precomputed handle basis (paper Sec. 3.1): B (k x m) with X = B H for k fixed
//! evaluation points and any displacements H (m x 3) of m fixed handles; B = M Phi^-1 (RBF)
//! or M Phi^+ (DM-FFD), B = M (FFD, handles = control points). Saved in a small binary file.
//! Used by the paper benchmark's Sec. 3.1 (benchmarks/paper/performance.cpp: compute, apply,
//! save and load against refit and fit for a new design).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

#include "meshmorph/core/types.h"

namespace meshmorph
{

class RbfDeformation;
class DmffdDeformation;
class FfdDeformation;
class GreedyRbfDeformation;

//! Which deformation produced a basis (stored in the file header).
enum class BasisMethod : std::uint32_t
{
    rbf = 1,
    ffd = 2,
    dmffd = 3,
    greedy_rbf = 4
};

//! k x m handle basis.
//!
//! File format (version 1, native little-endian): 8-byte magic "MMBASIS\0", uint32 version,
//! uint32 method, int64 k, int64 m, then k * m doubles in column-major order, nothing after.
class HandleBasis
{
public:
    HandleBasis() = default;
    //! \throw InvalidInput if B has non-finite entries.
    HandleBasis(Eigen::MatrixXd B, BasisMethod method);

    //! B = M Phi^-1 of a fitted RBF at points (k x 3). \throw InvalidInput if not fitted.
    static HandleBasis compute(const RbfDeformation& rbf, const Eigen::Ref<const Points>& points);
    //! B = M Phi^+ of a fitted DM-FFD at points (k x 3).
    static HandleBasis compute(const DmffdDeformation& dmffd,
                               const Eigen::Ref<const Points>& points);
    //! B of a greedy RBF (columns of non-centre constraints are zero).
    static HandleBasis compute(const GreedyRbfDeformation& greedy,
                               const Eigen::Ref<const Points>& points);
    //! B = M of an FFD (handles = its control points) at points (k x 3).
    static HandleBasis compute(const FfdDeformation& ffd, const Eigen::Ref<const Points>& points);

    Index rows() const { return Index(B_.rows()); } //!< k evaluation points
    Index cols() const { return Index(B_.cols()); } //!< m handles
    BasisMethod method() const { return method_; }
    const Eigen::MatrixXd& matrix() const { return B_; }

    //! \brief X = B H in one dgemm. \param H m x 3. \return k x 3. \throw InvalidInput on size.
    Points apply(const Eigen::Ref<const Points>& H) const;
    //! As apply(H) into a pre-sized out (k x 3).
    void apply(const Eigen::Ref<const Points>& H, Eigen::Ref<Points> out) const;

    //! Write the binary format. \throw IoError on a stream failure.
    void write(std::ostream& out) const;
    //! Read the binary format; name is used in messages.
    //! \throw ParseError (bad magic, version, method, sizes, truncation, trailing data).
    static HandleBasis read(std::istream& in, const std::string& name);
    //! \throw IoError when the file cannot be written.
    void save(const std::string& path) const;
    //! \throw IoError when the file cannot be opened, ParseError on bad content.
    static HandleBasis load(const std::string& path);

private:
    Eigen::MatrixXd B_;
    BasisMethod method_ = BasisMethod::rbf;
};

} // namespace meshmorph
