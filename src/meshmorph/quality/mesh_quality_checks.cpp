// SPDX-License-Identifier: GPL-3.0-or-later
// checkMesh -meshQuality: one table row per meshQualityDict criterion (when it is enabled,
// which faces it flags); the flags are merged in table order.
#include "meshmorph/quality/mesh_quality_checks.h"

#include <cmath>
#include <vector>

#include "meshmorph/mesh/foam_vector.h"
#include "meshmorph/quality/cell_determinant.h"
#include "meshmorph/quality/face_concavity.h"
#include "meshmorph/quality/face_flatness.h"
#include "meshmorph/quality/face_orthogonality.h"
#include "meshmorph/quality/face_pyramids.h"
#include "meshmorph/quality/face_tets.h"
#include "meshmorph/quality/face_twist.h"
#include "meshmorph/quality/face_weights.h"

namespace meshmorph
{

namespace
{

constexpr double small = constants::small;

struct Input
{
    const PolyMesh& mesh;
    const CompactList& cell_faces;
    const MeshGeometry& g;
    const MeshQualitySettings& q;
    const Eigen::VectorXd& skewness;
    const CoupledFaces& coupled;

    //! Internal, or coupled to a cell across (polyMeshGeometry measures both alike).
    bool two_sided(Index f) const
    {
        return coupled.internal_or_coupled[static_cast<std::size_t>(f)];
    }
};

using Flags = std::vector<char>;

//! Flags f where test(f) holds, for f in [0, n) (the rest stay 0).
template <typename Test> Flags faces_where(const PolyMesh& mesh, Index n, Test&& test)
{
    Flags flags(static_cast<std::size_t>(mesh.n_faces()), 0);
    for (Index f = 0; f < n; ++f)
        flags[f] = test(f);
    return flags;
}

Flags non_ortho(const Input& in)
{
    const double threshold = std::cos(detail::deg_to_rad(in.q.max_non_ortho));
    const Eigen::VectorXd ortho = face_orthogonality(in.mesh, in.g, in.coupled, constants::vsmall);
    return faces_where(in.mesh, in.mesh.n_faces(),
                       [&](Index f) { return in.two_sided(f) && ortho[f] < threshold; });
}

Flags pyramid_volume(const Input& in)
{
    const FacePyramidVolumes v = face_pyramid_volumes(in.mesh, in.g);
    const Index n_int = in.mesh.n_internal_faces();
    return faces_where(in.mesh, in.mesh.n_faces(),
                       [&](Index f) {
                           return v.owner[f] < in.q.min_vol ||
                                  (f < n_int && v.neighbour[f] < in.q.min_vol);
                       });
}

Flags area(const Input& in)
{
    const Eigen::VectorXd mag_area = face_area_magnitudes(in.g);
    return faces_where(in.mesh, in.mesh.n_faces(),
                       [&](Index f) { return mag_area[f] < in.q.min_area; });
}

Flags skewness(const Input& in)
{
    return faces_where(in.mesh, in.mesh.n_faces(),
                       [&](Index f)
                       {
                           return in.skewness[f] > (in.two_sided(f) ? in.q.max_internal_skewness
                                                                    : in.q.max_boundary_skewness);
                       });
}

Flags face_weight(const Input& in)
{
    const Eigen::VectorXd weights = face_weights(in.mesh, in.g, in.coupled);
    return faces_where(in.mesh, in.mesh.n_faces(),
                       [&](Index f)
                       { return in.two_sided(f) && weights[f] < in.q.min_face_weight; });
}

Flags volume_ratio(const Input& in)
{
    // Of the volumes' magnitudes, on both sides.
    CoupledFaces magnitudes = in.coupled;
    magnitudes.neighbour_cell_volumes = magnitudes.neighbour_cell_volumes.cwiseAbs();
    const Eigen::VectorXd ratio =
        face_volume_ratio(in.mesh, in.g.cell_volumes.cwiseAbs(), magnitudes);
    return faces_where(in.mesh, in.mesh.n_faces(),
                       [&](Index f) { return in.two_sided(f) && ratio[f] < in.q.min_vol_ratio; });
}

Flags flatness(const Input& in)
{
    const Eigen::VectorXd fan = face_fan_areas(in.mesh, in.g);
    const Eigen::VectorXd mag_area = face_area_magnitudes(in.g);
    // OpenFOAM's ratio is fan area / |Af| >= 1 (a quirk, reproduced: spec §5).
    return faces_where(in.mesh, in.mesh.n_faces(),
                       [&](Index f) {
                           return in.mesh.faces.item_size(f) > 3 &&
                                  fan[f] / mag_area[f] < in.q.min_face_flatness;
                       });
}

Flags determinant(const Input& in)
{
    const Eigen::VectorXd det = cell_area_determinant(in.cell_faces, in.g);
    Flags flags(static_cast<std::size_t>(in.mesh.n_faces()), 0);
    for (Index cell = 0; cell < in.mesh.n_cells; ++cell)
        if (det[cell] < in.q.min_determinant)
            for (Index f : in.cell_faces[cell])
                flags[f] = 1;
    return flags;
}

Flags tet_quality(const Input& in)
{
    return faces_with_tet_quality_below(in.mesh, in.g, in.q.min_tet_quality, &in.coupled);
}

Flags concavity(const Input& in)
{
    return faces_concave_beyond(in.mesh, in.g, std::sin(detail::deg_to_rad(in.q.max_concave)));
}

Flags twist(const Input& in)
{
    return faces_with_twist_below(in.mesh, in.g, in.q.min_twist, &in.coupled);
}

Flags triangle_twist(const Input& in)
{
    return faces_with_triangle_twist_below(in.mesh, in.g, in.q.min_triangle_twist);
}

using Settings = MeshQualitySettings;

struct Criterion
{
    const char* key;
    bool (*enabled)(const Settings&); // as OpenFOAM enables it (spec §5)
    Flags (*faces)(const Input&);
};

// OpenFOAM's order (motionSmoother::checkMesh).
const Criterion criteria[] = {
    {"maxNonOrtho", [](const Settings& q) { return q.max_non_ortho < 180.0 - small; }, non_ortho},
    {"minVol", [](const Settings& q) { return q.min_vol > -1e15; }, pyramid_volume},
    {"minTetQuality", [](const Settings& q) { return q.min_tet_quality > -1e15; }, tet_quality},
    {"maxConcave", [](const Settings& q) { return q.max_concave < 180.0 - small; }, concavity},
    {"minArea", [](const Settings& q) { return q.min_area > -small; }, area},
    {"maxInternalSkewness",
     [](const Settings& q) { return q.max_internal_skewness > 0 || q.max_boundary_skewness > 0; },
     skewness},
    {"minFaceWeight",
     [](const Settings& q) { return q.min_face_weight >= 0 && q.min_face_weight < 1; },
     face_weight},
    {"minVolRatio", [](const Settings& q) { return q.min_vol_ratio >= 0; }, volume_ratio},
    {"minTwist", [](const Settings& q) { return q.min_twist > -1; }, twist},
    {"minTriangleTwist", [](const Settings& q) { return q.min_triangle_twist > -1; },
     triangle_twist},
    {"minFaceFlatness", [](const Settings& q) { return q.min_face_flatness > -small; }, flatness},
    {"minDeterminant", [](const Settings& q) { return q.min_determinant > -1; }, determinant},
};

} // namespace

CheckResult check_mesh_quality(const PolyMesh& mesh, const CompactList& cell_faces,
                               const MeshGeometry& g, const MeshQualitySettings& q,
                               const Eigen::VectorXd& skewness, const CoupledFaces& coupled)
{
    const Input in{mesh, cell_faces, g, q, skewness, coupled};
    std::vector<char> in_error(static_cast<std::size_t>(mesh.n_faces()), 0);
    Statistic::Counts failures;
    for (const Criterion& c : criteria)
    {
        if (!c.enabled(q))
            continue;
        const Flags flags = c.faces(in);
        Index added = 0;
        for (std::size_t f = 0; f < flags.size(); ++f)
            if (flags[f] && !in_error[f])
            {
                in_error[f] = 1;
                ++added;
            }
        failures.emplace_back(c.key, added);
    }
    std::vector<Index> faces = flagged(in_error);
    CheckResult r(CheckId::mesh_quality);
    r.add("meshQualityFailures", std::move(failures));
    r.add("meshQualityFaces", size_of(faces));
    if (!faces.empty())
        r.failure = "meshQuality";
    r.add_set("meshQualityFaces", MeshSet::Kind::face, std::move(faces), "faces in error");
    return r;
}

} // namespace meshmorph
