// SPDX-License-Identifier: GPL-3.0-or-later
// Handle basis: computation from the fitted deformations, X = B H by dgemm, binary I/O.
#include "meshmorph/deform/handle_basis.h"

#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/ffd_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/lapack.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{
namespace
{
constexpr char magic[8] = {'M', 'M', 'B', 'A', 'S', 'I', 'S', '\0'};
constexpr std::uint32_t version = 1;
} // namespace

HandleBasis::HandleBasis(Eigen::MatrixXd B, BasisMethod method) : B_(std::move(B)), method_(method)
{
    if (!B_.allFinite())
        throw InvalidInput("handle basis has non-finite entries");
}

HandleBasis HandleBasis::compute(const RbfDeformation& rbf, const Eigen::Ref<const Points>& points)
{
    return HandleBasis(rbf.handle_basis(points), BasisMethod::rbf);
}

HandleBasis HandleBasis::compute(const DmffdDeformation& dmffd,
                                 const Eigen::Ref<const Points>& points)
{
    return HandleBasis(dmffd.handle_basis(points), BasisMethod::dmffd);
}

HandleBasis HandleBasis::compute(const GreedyRbfDeformation& greedy,
                                 const Eigen::Ref<const Points>& points)
{
    return HandleBasis(greedy.handle_basis(points), BasisMethod::greedy_rbf);
}

HandleBasis HandleBasis::compute(const FfdDeformation& ffd, const Eigen::Ref<const Points>& points)
{
    detail::require_finite(points, "FFD handle basis: point");
    return HandleBasis(ffd.basis_matrix(points), BasisMethod::ffd);
}

Points HandleBasis::apply(const Eigen::Ref<const Points>& H) const
{
    Points out(B_.rows(), 3);
    apply(H, out);
    return out;
}

void HandleBasis::apply(const Eigen::Ref<const Points>& H, Eigen::Ref<Points> out) const
{
    if (H.rows() != B_.cols())
        throw InvalidInput("handle basis: " + std::to_string(H.rows()) +
                           " handle displacements for a basis of " + std::to_string(B_.cols()) +
                           " handles");
    if (out.rows() != B_.rows())
        throw InvalidInput("handle basis: output has " + std::to_string(out.rows()) +
                           " rows, expected " + std::to_string(B_.rows()));
    if (B_.rows() == 0)
        return;
    if (B_.cols() == 0)
    {
        out.setZero();
        return;
    }
    // Row-major k x 3 is column-major 3 x k: out^T = H^T B^T in one dgemm.
    const Points Hc = H; // contiguous
    Points tmp;
    const bool direct = out.outerStride() == 3;
    if (!direct)
        tmp.resize(B_.rows(), 3);
    double* dst = direct ? out.data() : tmp.data();
    const int k = detail::lapack_int(B_.rows()), m = detail::lapack_int(B_.cols()), three = 3;
    const double one = 1.0, zero = 0.0;
    dgemm_("N", "T", &three, &k, &m, &one, Hc.data(), &three, B_.data(), &k, &zero, dst, &three);
    if (!direct)
        out = tmp;
}

void HandleBasis::write(std::ostream& out) const
{
    const std::uint32_t method = static_cast<std::uint32_t>(method_);
    const std::int64_t k = B_.rows(), m = B_.cols();
    out.write(magic, sizeof(magic));
    out.write(reinterpret_cast<const char*>(&version), sizeof(version));
    out.write(reinterpret_cast<const char*>(&method), sizeof(method));
    out.write(reinterpret_cast<const char*>(&k), sizeof(k));
    out.write(reinterpret_cast<const char*>(&m), sizeof(m));
    out.write(reinterpret_cast<const char*>(B_.data()),
              static_cast<std::streamsize>(sizeof(double) * std::size_t(k) * std::size_t(m)));
    if (!out)
        throw IoError("handle basis: write failed");
}

HandleBasis HandleBasis::read(std::istream& in, const std::string& name)
{
    char head[8];
    in.read(head, sizeof(head));
    if (in.gcount() != sizeof(head) || std::memcmp(head, magic, sizeof(magic)) != 0)
        throw ParseError(name, 0, "not a meshMorph handle basis file (bad magic)");
    std::uint32_t ver = 0, method = 0;
    std::int64_t k = -1, m = -1;
    in.read(reinterpret_cast<char*>(&ver), sizeof(ver));
    in.read(reinterpret_cast<char*>(&method), sizeof(method));
    in.read(reinterpret_cast<char*>(&k), sizeof(k));
    in.read(reinterpret_cast<char*>(&m), sizeof(m));
    if (!in)
        throw ParseError(name, 0, "truncated handle basis header");
    if (ver != version)
        throw ParseError(name, 0,
                         "unsupported handle basis version " + std::to_string(ver) + " (expected " +
                             std::to_string(version) + ")");
    if (method < 1 || method > 4)
        throw ParseError(name, 0, "unknown handle basis method " + std::to_string(method));
    constexpr std::int64_t limit = std::int64_t(1) << 40;
    if (k < 0 || m < 0 || k > limit || m > limit || (m > 0 && k > limit / m))
        throw ParseError(
            name, 0, "invalid handle basis size " + std::to_string(k) + " x " + std::to_string(m));
    // Check the size before allocating, when the stream can tell.
    const std::streampos here = in.tellg();
    const std::uint64_t want = std::uint64_t(k) * std::uint64_t(m) * sizeof(double);
    if (here != std::streampos(-1))
    {
        in.seekg(0, std::ios::end);
        const std::streampos end = in.tellg();
        in.seekg(here);
        const std::uint64_t have = std::uint64_t(end - here);
        if (have < want)
            throw ParseError(name, 0,
                             "truncated handle basis: " + std::to_string(k) + " x " +
                                 std::to_string(m) + " needs " + std::to_string(want) +
                                 " bytes of data, file has " + std::to_string(have));
        if (have > want)
            throw ParseError(name, 0,
                             "handle basis has " + std::to_string(have - want) +
                                 " unexpected trailing bytes");
    }
    Eigen::MatrixXd B(k, m);
    in.read(reinterpret_cast<char*>(B.data()), static_cast<std::streamsize>(want));
    if (std::uint64_t(in.gcount()) != want)
        throw ParseError(name, 0, "truncated handle basis data");
    if (!B.allFinite())
        throw ParseError(name, 0, "handle basis contains non-finite values");
    return HandleBasis(std::move(B), static_cast<BasisMethod>(method));
}

void HandleBasis::save(const std::string& path) const
{
    std::ofstream out(path, std::ios::binary);
    if (!out)
        throw IoError("cannot open " + path + " for writing");
    write(out);
    out.close();
    if (!out)
        throw IoError("failed writing " + path);
}

HandleBasis HandleBasis::load(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw IoError("cannot open " + path);
    return read(in, path);
}

} // namespace meshmorph
