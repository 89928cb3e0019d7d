// SPDX-License-Identifier: GPL-3.0-or-later
#include "meshmorph/design/lattice_box_cut.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "meshmorph/core/log.h"

namespace meshmorph::design
{

namespace
{

//! Per axis, how many of `points` lie inside the box's slab along it and how many outside.
struct AxisSides
{
    std::array<std::int64_t, 3> inside{0, 0, 0}, outside{0, 0, 0};
};

AxisSides sides_of(const PolyMesh& mesh, const FfdBox& box, const std::vector<Index>& points)
{
    // Box coordinates u = axes^-1 (x - origin); the box is u in [0, 1]^3. A point on a face
    // (to round-off) counts as inside: it moves with the face's value, not a step.
    const Eigen::Matrix3d to_box = box.axes.inverse();
    constexpr double on_face = 1e-9;
    AxisSides s;
    for (const Index i : points)
    {
        const Vector3 u = to_box * (mesh.points.row(i).transpose() - box.origin);
        for (int a = 0; a < 3; ++a)
            (u[a] < -on_face || u[a] > 1.0 + on_face ? s.outside : s.inside)[std::size_t(a)] += 1;
    }
    return s;
}

//! The largest motion at a box face, as a fraction of one control point's, with c outer
//! layers held: (P0 + 4 P1 + P2) / 6 with the first c of them zero.
std::string step_at_face(int held)
{
    switch (held)
    {
    case 0:
        return "the full motion of its outer control points";
    case 1:
        return "up to 5/6 of a control point's motion";
    default:
        return "up to 1/6 of a control point's motion";
    }
}

//! The first variable of lattice `l` (its patches are the lattice's), or -1 if none is left
//! free by `confine`.
Index first_variable_of(const DesignVariables& variables, std::size_t l)
{
    for (std::size_t j = 0; j < variables.variables.size(); ++j)
    {
        const DesignVariable& v = variables.variables[j];
        if (v.kind == DesignVariable::Kind::lattice_point && v.lattice == l)
            return Index(j);
    }
    return -1;
}

} // namespace

void warn_lattice_box_cuts(const PolyMesh& mesh, const DesignVariables& variables,
                           const VariableConstraints& constraints,
                           const parallel::Communicator& comm)
{
    static const char* const axis_names[] = {"x", "y", "z"};
    for (std::size_t l = 0; l < variables.lattices.size(); ++l)
    {
        const DesignLattice& lattice = variables.lattices[l];
        const Index j = first_variable_of(variables, l);
        if (j < 0)
            continue;
        const AxisSides s = sides_of(mesh, lattice.lattice.box(), constraints.points_moved_by(j));
        for (std::size_t a = 0; a < 3; ++a)
        {
            const int held = lattice.confine[a];
            // An axis written with one control point is constant along it: no face there.
            if (lattice.counts[a] == 1 || held >= 3)
                continue;
            const std::int64_t inside = comm.sum(s.inside[a]);
            const std::int64_t outside = comm.sum(s.outside[a]);
            if (inside == 0 || outside == 0)
                continue;
            log::warning() << "designVariables " << lattice.name << " (line " << lattice.line
                           << "): its box cuts the patches it moves across " << axis_names[a]
                           << " (" << outside << " of their points lie outside it), and confine "
                           << "holds " << held << " layer(s) of control points at each "
                           << axis_names[a] << " side: at the box's " << axis_names[a]
                           << " faces the walls move by " << step_at_face(held)
                           << ", just outside by nothing, a step the cells there take as shear. "
                           << "confine 3 along " << axis_names[a]
                           << " makes the motion fade to zero at the box (with its slope and "
                              "curvature); or enlarge the box around the patches";
        }
    }
}

} // namespace meshmorph::design
