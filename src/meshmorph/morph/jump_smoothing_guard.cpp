// SPDX-License-Identifier: GPL-3.0-or-later
// `jumpSmoothing auto`: compare the smoothed and the fitted field on the band's cells.
#include "meshmorph/morph/jump_smoothing_guard.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "meshmorph/mesh/processor_faces.h"
#include "meshmorph/quality/face_orthogonality.h"

namespace meshmorph::morph
{

namespace
{

//! The faces and cells whose geometry depends on the band's points.
struct BandCells
{
    std::vector<Index> faces;    //!< faces with a band point
    std::vector<Index> cells;    //!< their owners and neighbours
    std::vector<Index> measured; //!< internal faces of those cells
    //! -parallel: the processor faces beside such a cell on either side, and whether this
    //! rank holds the pair's statistics (checkMesh counts a processor face once).
    std::vector<Index> coupled;
    std::vector<char> coupled_owner;
};

//! The processor patches of a -parallel run (none in a serial one).
struct Coupling
{
    ProcessorFaces processors;
    bool parallel = false;
};

Coupling coupling(const PolyMesh& mesh, const parallel::Communicator& comm)
{
    Coupling c;
    c.parallel = comm.is_parallel();
    if (!c.parallel)
        return c;
    c.processors.comm = &comm;
    c.processors.patches = processor_patches(mesh, comm.rank());
    return c;
}

//! Per boundary face (face - nInternalFaces), its owner cell's `value` (0 off the patches
//! of `c`), swapped with the rank across: the value of the cell on the other side.
std::vector<double> across(const PolyMesh& mesh, const Coupling& c,
                           const std::function<double(Index)>& value)
{
    const Index n_int = mesh.n_internal_faces();
    std::vector<double> mine(std::size_t(mesh.n_faces() - n_int), 0.0);
    for (const ProcessorPatch& pp : c.processors.patches)
    {
        const Patch& p = mesh.patches[std::size_t(pp.patch)];
        for (Index f = p.start_face; f < p.start_face + p.n_faces; ++f)
            mine[std::size_t(f - n_int)] = value(mesh.owner[std::size_t(f)]);
    }
    return swap_processor_values(mesh, c.processors, mine);
}

//! The processor faces beside a cell of the band on either side (a collective).
void coupled_faces(const PolyMesh& mesh, const Coupling& c, const std::vector<char>& cell_seen,
                   BandCells& out)
{
    const Index n_int = mesh.n_internal_faces();
    const std::vector<double> remote =
        across(mesh, c, [&](Index cell) { return double(cell_seen[std::size_t(cell)]); });
    for (const ProcessorPatch& pp : c.processors.patches)
    {
        const Patch& p = mesh.patches[std::size_t(pp.patch)];
        for (Index f = p.start_face; f < p.start_face + p.n_faces; ++f)
            if (cell_seen[std::size_t(mesh.owner[std::size_t(f)])] != 0 ||
                remote[std::size_t(f - n_int)] != 0.0)
            {
                out.coupled.push_back(f);
                out.coupled_owner.push_back(pp.owner ? 1 : 0);
            }
    }
}

BandCells band_cells(const PolyMesh& mesh, const CompactList& cell_faces,
                     const std::vector<Index>& band, const Coupling& coupled)
{
    std::vector<char> in_band(std::size_t(mesh.n_points()), 0);
    for (const Index p : band)
        in_band[std::size_t(p)] = 1;
    BandCells out;
    std::vector<char> cell_seen(std::size_t(mesh.n_cells), 0);
    const auto add_cell = [&](Index c)
    {
        if (cell_seen[std::size_t(c)] == 0)
        {
            cell_seen[std::size_t(c)] = 1;
            out.cells.push_back(c);
        }
    };
    for (Index f = 0; f < mesh.n_faces(); ++f)
    {
        const std::span<const Index> loop = mesh.faces[f];
        if (std::none_of(loop.begin(), loop.end(),
                         [&](Index p) { return in_band[std::size_t(p)] != 0; }))
            continue;
        out.faces.push_back(f);
        add_cell(mesh.owner[std::size_t(f)]);
        if (mesh.is_internal_face(f))
            add_cell(mesh.neighbour[std::size_t(f)]);
    }
    std::sort(out.cells.begin(), out.cells.end());
    std::vector<char> face_seen(std::size_t(mesh.n_faces()), 0);
    for (const Index c : out.cells)
        for (const Index f : cell_faces[c])
            if (mesh.is_internal_face(f) && face_seen[std::size_t(f)] == 0)
            {
                face_seen[std::size_t(f)] = 1;
                out.measured.push_back(f);
            }
    std::sort(out.measured.begin(), out.measured.end());
    if (coupled.parallel)
        coupled_faces(mesh, coupled, cell_seen, out);
    return out;
}

//! The non-orthogonality of the processor faces of b, checkMesh's way: against the centre
//! of the cell across (a collective).
void coupled_quality(const PolyMesh& mesh, const MeshGeometry& g, const BandCells& b,
                     const Coupling& c, BandQuality& q)
{
    const Index n_int = mesh.n_internal_faces();
    std::array<std::vector<double>, 3> centre;
    for (int k = 0; k < 3; ++k)
        centre[std::size_t(k)] =
            across(mesh, c, [&](Index cell) { return g.cell_centres(cell, k); });
    for (std::size_t i = 0; i < b.coupled.size(); ++i)
    {
        const Index f = b.coupled[i];
        const std::size_t at = std::size_t(f - n_int);
        const Vector3 d = Vector3(centre[0][at], centre[1][at], centre[2][at]) -
                          g.cell_centres.row(mesh.owner[std::size_t(f)]).transpose();
        const Vector3 s = g.face_areas.row(f).transpose();
        const double angle =
            non_orthogonality_degrees(d.dot(s) / (d.norm() * s.norm() + constants::rootvsmall));
        q.max_non_ortho = std::max(q.max_non_ortho, angle);
        if (angle > 70.0 && b.coupled_owner[i] != 0)
            ++q.faces_above_70;
    }
}

BandQuality band_quality(const PolyMesh& mesh, const MeshGeometry& g, const BandCells& b,
                         const Coupling& coupled, const parallel::Communicator& comm)
{
    BandQuality q;
    for (const Index c : b.cells)
        if (!(g.cell_volumes[c] > 0.0))
            ++q.invalid_cells;
    for (const Index f : b.measured)
    {
        const double angle = non_orthogonality_degrees(internal_face_orthogonality(mesh, g, f));
        q.max_non_ortho = std::max(q.max_non_ortho, angle);
        if (angle > 70.0)
            ++q.faces_above_70;
    }
    if (coupled.parallel)
        coupled_quality(mesh, g, b, coupled, q);
    q.invalid_cells = Index(comm.sum(std::int64_t(q.invalid_cells)));
    q.faces_above_70 = Index(comm.sum(std::int64_t(q.faces_above_70)));
    q.max_non_ortho = comm.max(q.max_non_ortho);
    return q;
}

//! Put the band's points at accepted + `field` (one row per band point, as the step adds
//! them) and update the geometry of the faces and cells they touch.
void move_band(PolyMesh& mesh, const CompactList& cell_faces, MeshGeometry& g,
               const Points& accepted, const std::vector<Index>& band, const Points& field,
               const BandCells& b)
{
    for (std::size_t i = 0; i < band.size(); ++i)
        mesh.points.row(band[i]) = accepted.row(band[i]) + field.row(Eigen::Index(i));
    for (const Index f : b.faces)
        face_centre_and_area(mesh, f, g.face_centres, g.face_areas);
    for (const Index c : b.cells)
        cell_centre_and_volume(mesh, cell_faces, c, g);
}

bool better(const BandQuality& smoothed, const BandQuality& fitted)
{
    if (smoothed.invalid_cells != fitted.invalid_cells)
        return smoothed.invalid_cells < fitted.invalid_cells;
    return smoothed.max_non_ortho < fitted.max_non_ortho - margin_degrees;
}

} // namespace

JumpSmoothingChoice choose_jump_smoothing(PolyMesh& trial, const CompactList& cell_faces,
                                          MeshGeometry& geometry, const Points& accepted,
                                          const JumpSmoothing& s, Points& displacement,
                                          const parallel::Communicator& comm)
{
    JumpSmoothingChoice out;
    // Every rank alike: the decision to compare is a collective's.
    if (comm.sum(std::int64_t(s.band.size())) == 0)
        return out;
    out.compared = true;
    const Coupling coupled = coupling(trial, comm);
    const BandCells b = band_cells(trial, cell_faces, s.band, coupled);
    Points smoothed(Eigen::Index(s.band.size()), 3);
    for (std::size_t i = 0; i < s.band.size(); ++i)
        smoothed.row(Eigen::Index(i)) = displacement.row(s.band[i]);
    out.smoothed = band_quality(trial, geometry, b, coupled, comm);
    move_band(trial, cell_faces, geometry, accepted, s.band, s.fitted, b);
    out.fitted = band_quality(trial, geometry, b, coupled, comm);
    out.kept = better(out.smoothed, out.fitted);
    if (out.kept)
        move_band(trial, cell_faces, geometry, accepted, s.band, smoothed, b);
    else
        for (std::size_t i = 0; i < s.band.size(); ++i)
            displacement.row(s.band[i]) = s.fitted.row(Eigen::Index(i));
    return out;
}

} // namespace meshmorph::morph
