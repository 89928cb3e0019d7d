// SPDX-License-Identifier: GPL-3.0-or-later
// `jumpSmoothing auto`: compare the smoothed and the fitted field on the band's cells.
#include "meshmorph/morph/jump_smoothing_guard.h"

#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "meshmorph/mesh/coupled_patches.h"
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
    //! -parallel: the processor faces beside such a cell on either side.
    std::vector<Index> coupled;
};

//! -parallel: what lies across the processor faces for the current points (a collective);
//! nothing in a serial run.
std::optional<ProcessorFaces> exchanged(const PolyMesh& mesh, const MeshGeometry& g,
                                        const parallel::Communicator& comm)
{
    if (!comm.is_parallel())
        return std::nullopt;
    return exchange_processor_faces(mesh, g, comm);
}

//! The processor faces with a band cell on this side or across (a collective).
std::vector<Index> processor_faces_beside(const PolyMesh& mesh, const ProcessorFaces& across,
                                          const std::vector<char>& cell_seen)
{
    const Index n_int = mesh.n_internal_faces();
    std::vector<double> mine(std::size_t(mesh.n_faces() - n_int), 0.0);
    for (Index f = n_int; f < mesh.n_faces(); ++f)
        if (across.on_processor_patch[std::size_t(f - n_int)] != 0)
            mine[std::size_t(f - n_int)] = cell_seen[std::size_t(mesh.owner[std::size_t(f)])];
    const std::vector<double> theirs = swap_processor_values(mesh, across, mine);
    std::vector<Index> out;
    for (Index f = n_int; f < mesh.n_faces(); ++f)
        if (mine[std::size_t(f - n_int)] != 0.0 || theirs[std::size_t(f - n_int)] != 0.0)
            out.push_back(f);
    return out;
}

BandCells band_cells(const PolyMesh& mesh, const CompactList& cell_faces,
                     const std::vector<Index>& band, const ProcessorFaces* across)
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
    if (across != nullptr)
        out.coupled = processor_faces_beside(mesh, *across, cell_seen);
    return out;
}

//! The non-orthogonality of an angle cosine into q.
void add_angle(double cosine, bool counted, BandQuality& q)
{
    const double angle = non_orthogonality_degrees(cosine);
    q.max_non_ortho = std::max(q.max_non_ortho, angle);
    if (angle > 70.0 && counted)
        ++q.faces_above_70;
}

//! The band's cells' figures; processor faces measured against the cell across, as
//! checkMesh -parallel does (counted once, on the owner side). A collective.
BandQuality band_quality(const PolyMesh& mesh, const MeshGeometry& g, const BandCells& b,
                         const ProcessorFaces* across, const parallel::Communicator& comm)
{
    BandQuality q;
    for (const Index c : b.cells)
        if (!(g.cell_volumes[c] > 0.0))
            ++q.invalid_cells;
    for (const Index f : b.measured)
        add_angle(internal_face_orthogonality(mesh, g, f), true, q);
    if (across != nullptr)
    {
        const CoupledFaces coupled = coupled_faces(mesh, g, {}, across);
        for (const Index f : b.coupled)
            add_angle(coupled_face_orthogonality(mesh, g, coupled, f),
                      coupled.master[std::size_t(f)] != 0, q);
    }
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
    std::optional<ProcessorFaces> across = exchanged(trial, geometry, comm);
    const BandCells b = band_cells(trial, cell_faces, s.band, across ? &*across : nullptr);
    Points smoothed(Eigen::Index(s.band.size()), 3);
    for (std::size_t i = 0; i < s.band.size(); ++i)
        smoothed.row(Eigen::Index(i)) = displacement.row(s.band[i]);
    out.smoothed = band_quality(trial, geometry, b, across ? &*across : nullptr, comm);
    move_band(trial, cell_faces, geometry, accepted, s.band, s.fitted, b);
    across = exchanged(trial, geometry, comm);
    out.fitted = band_quality(trial, geometry, b, across ? &*across : nullptr, comm);
    out.kept = better(out.smoothed, out.fitted);
    if (out.kept)
        move_band(trial, cell_faces, geometry, accepted, s.band, smoothed, b);
    else
        for (std::size_t i = 0; i < s.band.size(); ++i)
            displacement.row(s.band[i]) = s.fitted.row(Eigen::Index(i));
    return out;
}

} // namespace meshmorph::morph
