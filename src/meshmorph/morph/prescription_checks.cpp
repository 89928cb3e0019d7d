// SPDX-License-Identifier: GPL-3.0-or-later
// Prescriptions that cannot be done, refused with the entry that asked for them.
#include "meshmorph/morph/prescription_checks.h"

#include <cmath>
#include <sstream>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/morph/conflict_resolution.h"

namespace meshmorph::morph
{

namespace
{

//! Who asked for a claim, for messages: the boundary entry (or, for an implicit one, the
//! patch) or the handle, and the dictionary line.
struct Asker
{
    std::string what;
    std::size_t line = 0;
    MotionType type = MotionType::fixed;
};

Asker boundary_asker(const PolyMesh& mesh, const MorphSetup& setup, const Claim& c)
{
    const std::string patch = mesh.patches[static_cast<std::size_t>(c.source)].name;
    if (c.order < 0 || c.order >= static_cast<Index>(setup.boundary.size()))
        return {"patch '" + patch + "'", 0, MotionType::fixed};
    const BoundaryEntry& e = setup.boundary[static_cast<std::size_t>(c.order)];
    const std::string key =
        e.key == patch ? "'" + e.key + "'" : "'" + e.key + "' (patch '" + patch + "')";
    return {"boundary entry " + key + " (type " + to_string(e.motion.type) + ")", e.line,
            e.motion.type};
}

Asker handle_asker(const MorphSetup& setup, const Claim& c)
{
    const HandleEntry& h = setup.handles[static_cast<std::size_t>(c.source)];
    return {"handle '" + h.name + "'", h.line, MotionType::translate};
}

std::string vector_text(const Vector3& v)
{
    std::ostringstream o;
    o.precision(6);
    o << '(' << v.x() << ' ' << v.y() << ' ' << v.z() << ')';
    return o.str();
}

[[noreturn]] void refuse(const MorphSetup& setup, const Asker& a, const std::string& why)
{
    throw ParseError(setup.dict_path, a.line, a.what + ": " + why);
}

void check_size(const MorphSetup& setup, const Asker& a, const Claim& c, double diagonal)
{
    const double limit = max_displacement_in_mesh_sizes * diagonal;
    if (!c.value.allFinite())
        refuse(setup, a,
               "the displacement it gives point " + std::to_string(c.point) + " is not finite " +
                   vector_text(c.value) + " (NaN or an overflow): check its values");
    if (c.value.stableNorm() > limit)
    {
        std::ostringstream o;
        o.precision(3);
        o << "the displacement it gives point " << c.point << ", " << vector_text(c.value)
          << ", is " << c.value.stableNorm() / diagonal
          << " times the mesh's size (its bounding box's diagonal, " << diagonal << "); at most "
          << max_displacement_in_mesh_sizes
          << " times can be computed and written: check its values and units";
        refuse(setup, a, o.str());
    }
}

//! The largest normal and in-plane parts of one asker's claims (indexed by claim.source:
//! the patch, or the handle).
struct PlaneParts
{
    double normal = 0.0, in_plane = 0.0;
    const Claim* worst = nullptr; //!< the claim with the largest normal part
};

void check_2d(const MorphSetup& setup, const Asker& a, const PlaneParts& parts,
              const EmptyPlanes& planes, double tolerance)
{
    const bool dropped = parts.normal > tolerance;
    // A surface's normal part is the target's shape; it is refused only when it is all.
    if (!dropped || (a.type == MotionType::surface && parts.in_plane > tolerance))
        return;
    const Vector3 d = parts.worst->value;
    std::string hint = "remove its component along the normal";
    if (a.type == MotionType::rotate)
        hint = "rotate about an axis parallel to the normal";
    else if (a.type == MotionType::scale)
        hint = "give its factor 1 along the normal";
    else if (a.type == MotionType::surface)
        hint = "use a target surface that crosses the planes";
    refuse(setup, a,
           "this is a 2D case (empty patches, normal " + vector_text(planes.normal) +
               ") and its motion has a part normal to the planes (" + vector_text(d) +
               " at point " + std::to_string(parts.worst->point) +
               "), which a 2D case cannot follow and morphMesh would have to drop: " + hint);
}

void check_claims(const MorphSetup& setup, const std::vector<Claim>& claims,
                  const std::optional<EmptyPlanes>& planes, double diagonal, double tolerance,
                  std::size_t n_askers, const std::function<Asker(const Claim&)>& asker_of)
{
    std::vector<PlaneParts> parts(n_askers);
    for (const Claim& c : claims)
    {
        if (c.kind != Claim::Kind::value)
            continue;
        if (!c.value.allFinite() ||
            c.value.stableNorm() > max_displacement_in_mesh_sizes * diagonal)
            check_size(setup, asker_of(c), c, diagonal);
        if (!planes)
            continue;
        PlaneParts& p = parts[static_cast<std::size_t>(c.source)];
        const double normal = std::abs(c.value.dot(planes->normal));
        p.in_plane = std::max(p.in_plane, planes->in_plane(c.value).norm());
        if (p.worst == nullptr || normal > p.normal)
        {
            p.normal = normal;
            p.worst = &c;
        }
    }
    if (planes)
        for (const PlaneParts& p : parts)
            if (p.worst != nullptr)
                check_2d(setup, asker_of(*p.worst), p, *planes, tolerance);
}

//! Of the largest claimed motion: what round-off of the closed-form motions leaves.
constexpr double round_off_fraction = 1e-9;

//! In an axisymmetric case, a value claimed for a point of a wedge plane that leaves the
//! plane is refused: the case cannot follow it, and the point would be held by the
//! conflict rule instead. \param claims sorted by point.
void check_wedge_planes(const PolyMesh& mesh, const MorphSetup& setup,
                        const std::vector<Claim>& claims, double tolerance)
{
    for (std::size_t begin = 0, end = 0; begin < claims.size(); begin = end)
    {
        end = begin;
        while (end < claims.size() && claims[end].point == claims[begin].point)
            ++end;
        for (std::size_t w = begin; w < end; ++w)
        {
            const Claim& wedge = claims[w];
            if (wedge.kind != Claim::Kind::slip ||
                mesh.patches[std::size_t(wedge.source)].type != "wedge")
                continue;
            for (std::size_t v = begin; v < end; ++v)
            {
                const Claim& c = claims[v];
                if (c.kind != Claim::Kind::value)
                    continue;
                const double off = std::abs(c.value.dot(wedge.value));
                if (off <= in_plane_fraction * c.value.norm() + tolerance)
                    continue;
                std::ostringstream o;
                o.precision(3);
                o << "this is an axisymmetric case (wedge patch '"
                  << mesh.patches[std::size_t(wedge.source)].name
                  << "') and its motion leaves the wedge plane at point " << c.point << " ("
                  << vector_text(c.value) << ", " << off / c.value.norm()
                  << " of it normal to the plane), which the case cannot follow: use a motion "
                     "symmetric about the axis (a translation along it, a rotation about it, a "
                     "scale about a point on it)";
                refuse(setup, boundary_asker(mesh, setup, c), o.str());
            }
        }
    }
}

//! The largest finite displacement claimed (0 if none).
double largest_claim(const std::vector<Claim>& claims)
{
    double largest = 0.0;
    for (const Claim& c : claims)
        if (c.kind == Claim::Kind::value && c.value.allFinite())
            largest = std::max(largest, c.value.stableNorm());
    return largest;
}

} // namespace

void check_prescriptions(const PolyMesh& mesh, const MorphSetup& setup,
                         const std::vector<Claim>& claims, const std::vector<Claim>& handle_claims,
                         const std::optional<EmptyPlanes>& planes, double diagonal,
                         double tolerance)
{
    // Normal parts below 1e-9 of the largest motion are round-off of the closed forms (a
    // point on a wedge's axis scaled about another point of it moves 1e-13 where the wall
    // moves 1e-4, in a direction only round-off decides).
    const double negligible =
        tolerance +
        round_off_fraction * std::max(largest_claim(claims), largest_claim(handle_claims));
    check_claims(setup, claims, planes, diagonal, negligible, mesh.patches.size(),
                 [&](const Claim& c) { return boundary_asker(mesh, setup, c); });
    check_claims(setup, handle_claims, planes, diagonal, negligible, setup.handles.size(),
                 [&](const Claim& c) { return handle_asker(setup, c); });
    check_wedge_planes(mesh, setup, claims, negligible);
}

} // namespace meshmorph::morph
