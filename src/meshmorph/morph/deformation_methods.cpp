// SPDX-License-Identifier: GPL-3.0-or-later
// The deformation methods, one row each: what every method-dependent decision of a morph
// (name, fit, exactness, construction, log line, memory) reads.
#include "meshmorph/morph/deformation_methods.h"

#include <algorithm>
#include <iterator>
#include <sstream>
#include <string_view>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/corrected_deformation.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/ffd_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/idw_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"
#include "meshmorph/morph/fit_memory.h"

namespace meshmorph::morph
{

namespace
{

using Made = std::unique_ptr<SpaceDeformation>;

//! The RBF is greedy when asked (`rbf { greedy {...} }`) or above the direct limit.
bool is_greedy(const DeformationSettings& s, Index n_constraints)
{
    return s.greedy || n_constraints > s.direct_limit;
}

double lattice_count(const std::array<int, 3>& n)
{
    return double(n[0]) * double(n[1]) * double(n[2]);
}

std::string constraints_text(Index n_constraints)
{
    return std::to_string(n_constraints) + " constraints";
}

// ---------------------------------------------------------------------------------------
// rbf: the paper's RBF, direct or greedy, plus the IDW correction of its residual

Made make_rbf(const DeformationSettings& s, const Eigen::Ref<const Points>&, Index n_constraints)
{
    // Either way the IDW correction of the residual makes the field exact at every
    // constraint (a direct fit leaves only round-off to correct).
    std::unique_ptr<SpaceDeformation> global;
    if (is_greedy(s, n_constraints))
    {
        GreedySettings g = s.greedy.value_or(GreedySettings{});
        g.rbf = s.rbf;
        global = std::make_unique<GreedyRbfDeformation>(g);
    }
    else
    {
        // A direct fit that ill-conditioning makes inexact is replaced by the greedy RBF
        // (CorrectedDeformation::fit) rather than kept with a warning.
        RbfSettings direct = s.rbf;
        direct.ill_conditioning_is_error = true;
        global = std::make_unique<RbfDeformation>(direct);
    }
    return std::make_unique<CorrectedDeformation>(std::move(global), s.idw, s.limit);
}

void describe_rbf(std::ostream& out, const DeformationSettings& s, Index n_constraints)
{
    out << "rbf (" << to_string(s.rbf.kernel) << ", "
        << (s.rbf.polynomial ? "linear polynomial" : "no polynomial") << ", ";
    const std::string limit = s.limit ? "; limited to the largest prescribed displacement" : "";
    if (!is_greedy(s, n_constraints))
    {
        out << "direct, exact" << limit << ")";
        return;
    }
    const GreedySettings g = s.greedy.value_or(GreedySettings{});
    out << "greedy"
        << (s.greedy ? "" : " (automatic above " + std::to_string(s.direct_limit) + " constraints)")
        << ", tolerance " << g.tolerance << ", max " << g.max_centres
        << " centres; IDW correction of the residual: exact" << limit << ")";
}

FitSize rbf_size(const DeformationSettings& s, Index n_constraints)
{
    const double m = double(n_constraints), word = sizeof(double);
    if (!is_greedy(s, n_constraints)) // the system and its factor
        return {2 * word * m * m, nullptr,
                "a direct RBF fit of " + constraints_text(n_constraints)};
    const Index max_centres = s.greedy.value_or(GreedySettings{}).max_centres;
    const double centres = std::min(m, double(max_centres)); // the centres' system and factor
    return {2 * word * centres * centres, &s.greedy_centres,
            "a greedy RBF of up to " + std::to_string(max_centres) + " centres fitted to " +
                constraints_text(n_constraints)};
}

// ---------------------------------------------------------------------------------------
// idw: inverse-distance weighting (IDWarp's method), no linear solve

Made make_idw(const DeformationSettings& s, const Eigen::Ref<const Points>&, Index)
{
    return std::make_unique<IdwDeformation>(s.idw);
}

void describe_idw(std::ostream& out, const DeformationSettings& s, Index)
{
    out << "idw (exponents " << s.idw.far_exponent << " " << s.idw.near_exponent << ", alpha "
        << s.idw.alpha << ", theta " << s.idw.theta << ", exact)";
}

FitSize idw_size(const DeformationSettings&, Index n_constraints)
{
    return {0, nullptr, "the fit of " + constraints_text(n_constraints)};
}

// ---------------------------------------------------------------------------------------
// dmffd: the paper's direct-manipulation FFD (SVD pseudo-inverse with clamping)

Made make_dmffd(const DeformationSettings& s, const Eigen::Ref<const Points>& points, Index)
{
    DmffdSettings d = s.dmffd;
    if (!d.lattice.box) // enclose the whole mesh, not only the handles (paper Sec. 3.6)
        d.lattice.box = make_lattice(d.lattice, points).box();
    return std::make_unique<DmffdDeformation>(d);
}

void describe_dmffd(std::ostream& out, const DeformationSettings& s, Index)
{
    const auto& n = s.dmffd.lattice.control_points;
    out << "dmffd (lattice " << n[0] << "x" << n[1] << "x" << n[2] << ", clamping "
        << s.dmffd.clamping << ")";
}

FitSize dmffd_size(const DeformationSettings& s, Index n_constraints)
{
    // Phi (m x n), then the SVD's U (m x r) and Vt (r x n), r = min(m, n).
    const double m = double(n_constraints), word = sizeof(double);
    const double n = lattice_count(s.dmffd.lattice.control_points);
    return {word * (m * n + m * std::min(m, n) + std::min(m, n) * n), &s.dmffd_lattice,
            "a lattice of " + format_count(n) + " control points fitted to " +
                constraints_text(n_constraints)};
}

// ---------------------------------------------------------------------------------------
// ffd: the paper's FFD, control points moved as the dictionary says (no fit)

Made make_ffd(const DeformationSettings& s, const Eigen::Ref<const Points>& points, Index)
{
    const FfdLattice lattice = make_lattice(s.ffd, points);
    auto ffd = std::make_unique<FfdDeformation>(lattice, s.ffd.outside);
    Points control = Points::Zero(lattice.size(), 3);
    for (const ControlDisplacement& c : s.ffd_displacements)
        control.row(lattice.index(c.index[0], c.index[1], c.index[2])) = c.displacement.transpose();
    ffd->set_control_displacements(control);
    return ffd;
}

void describe_ffd(std::ostream& out, const DeformationSettings& s, Index)
{
    const auto& n = s.ffd.control_points;
    out << "ffd (lattice " << n[0] << "x" << n[1] << "x" << n[2] << ", "
        << s.ffd_displacements.size() << " control points moved)";
}

FitSize ffd_size(const DeformationSettings& s, Index n_constraints)
{
    return {ffd_lattice_bytes(lattice_count(s.ffd.control_points)), nullptr,
            "the fit of " + constraints_text(n_constraints)};
}

// ---------------------------------------------------------------------------------------
// The table

struct MethodRow
{
    DeformationMethod method;
    std::string_view name;
    bool needs_fit; //!< fitted to the constraints (false: FFD's control points are given)
    bool exact;     //!< interpolates every constraint
    Made (*make)(const DeformationSettings&, const Eigen::Ref<const Points>&, Index);
    void (*describe)(std::ostream&, const DeformationSettings&, Index);
    FitSize (*size)(const DeformationSettings&, Index);
};

const MethodRow methods[] = {
    {DeformationMethod::rbf, "rbf", true, true, make_rbf, describe_rbf, rbf_size},
    {DeformationMethod::dmffd, "dmffd", true, false, make_dmffd, describe_dmffd, dmffd_size},
    {DeformationMethod::ffd, "ffd", false, false, make_ffd, describe_ffd, ffd_size},
    {DeformationMethod::idw, "idw", true, true, make_idw, describe_idw, idw_size},
};

const MethodRow& row(DeformationMethod method)
{
    for (const MethodRow& r : methods)
        if (r.method == method)
            return r;
    throw std::logic_error("deformation method without a row in the method table");
}

} // namespace

std::string to_string(DeformationMethod method)
{
    return std::string(row(method).name);
}

DeformationMethod deformation_method_from_string(const std::string& name)
{
    std::string valid;
    for (const MethodRow& r : methods)
    {
        if (r.name == name)
            return r.method;
        valid += (valid.empty() ? "" : " ") + std::string(r.name);
    }
    throw InvalidInput("unknown method '" + name + "' (valid: " + valid + ")");
}

bool needs_fit(const DeformationSettings& settings)
{
    return row(settings.method).needs_fit;
}

bool is_exact(const DeformationSettings& settings)
{
    return row(settings.method).exact;
}

bool bounded_by_prescriptions(const DeformationSettings& settings)
{
    return settings.method == DeformationMethod::idw ||
           (settings.method == DeformationMethod::rbf && settings.limit);
}

std::unique_ptr<SpaceDeformation> make_deformation(const DeformationSettings& settings,
                                                   const Eigen::Ref<const Points>& points,
                                                   Index n_constraints)
{
    check_fit_memory(fit_size(settings, n_constraints));
    return row(settings.method).make(settings, points, n_constraints);
}

std::string describe(const DeformationSettings& settings, Index n_constraints)
{
    std::ostringstream out;
    row(settings.method).describe(out, settings, n_constraints);
    return out.str();
}

FitSize fit_size(const DeformationSettings& settings, Index n_constraints)
{
    return row(settings.method).size(settings, n_constraints);
}

} // namespace meshmorph::morph
