// SPDX-License-Identifier: GPL-3.0-or-later
// The repair of severely non-orthogonal faces a morph makes (see the header).
#include "meshmorph/morph/non_ortho_repair.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/morph/local_untangle.h"
#include "meshmorph/quality/face_orthogonality.h"

namespace meshmorph::morph
{

namespace
{

double cos_degrees(double degrees)
{
    return std::cos(degrees * std::numbers::pi / 180.0);
}

//! The repair's reach: up to 4 layers of cells around those it repairs, 10 sweeps each (the
//! untangling's 8 and 40 took 0.8 s on the motorBike lifted 13.5% for 19 faces above 70
//! left; this 0.3 s for 16, the same result at 5 and 9%).
const UntangleSettings budget{4, 10};

//! The pyramids' weight: a pyramid binds only when its cosine nears the untangling's margin.
double pyramid_weight(double limit_degrees)
{
    return cos_degrees(limit_degrees - non_ortho_margin_degrees) / repair_margin_cosine;
}

//! The quality below which a cell of unmorphed quality `before` counts as taken beyond the
//! limit: the limit's cosine, or for a cell already beyond it unmorphed, its own angle plus
//! the margin (a snappyHexMesh mesh can have many such cells; a morph moves them all a
//! little, and those it barely moves are not the morph's doing).
double worse_than(double before, double limit_degrees)
{
    const double goal = cos_degrees(limit_degrees);
    if (before >= goal)
        return goal;
    return before <= -1.0
               ? -2.0
               : std::cos(std::acos(before) + non_ortho_margin_degrees * std::numbers::pi / 180.0);
}

//! Interior points that are not points of a cell with a processor or cyclic face: the
//! orthogonality of such a face is measured against a cell this rank (or this side) does
//! not move with it, so the repair leaves those cells' points alone.
std::vector<char> movable_points(const PolyMesh& mesh, const CompactList& cell_faces)
{
    std::vector<char> movable = boundary_point_mask(mesh);
    for (char& m : movable)
        m = m ? 0 : 1;
    for (const Patch& patch : mesh.patches)
    {
        if (!is_processor_patch(patch) && !is_coupled_patch(patch))
            continue;
        for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
            for (const Index g : cell_faces[mesh.owner[f]])
                for (const Index p : mesh.faces[g])
                    movable[std::size_t(p)] = 0;
    }
    return movable;
}

//! The unmorphed geometry of `cells` and of the cells across their internal faces (the
//! arrays sized for the whole mesh, only those entries computed).
MeshGeometry geometry_around(const PolyMesh& original, const CompactList& cell_faces,
                             const std::vector<Index>& cells)
{
    MeshGeometry g;
    g.face_centres.resize(original.n_faces(), 3);
    g.face_areas.resize(original.n_faces(), 3);
    g.cell_centres.resize(cell_faces.size(), 3);
    g.cell_volumes.resize(cell_faces.size());
    std::vector<Index> around;
    for (const Index c : cells)
    {
        around.push_back(c);
        for (const Index f : cell_faces[c])
            if (original.is_internal_face(f))
                around.push_back(original.owner[f] == c ? original.neighbour[f]
                                                        : original.owner[f]);
    }
    std::sort(around.begin(), around.end());
    around.erase(std::unique(around.begin(), around.end()), around.end());
    for (const Index c : around)
    {
        for (const Index f : cell_faces[c])
            face_centre_and_area(original, f, g.face_centres, g.face_areas);
        cell_centre_and_volume(original, cell_faces, c, g);
    }
    return g;
}

//! Per cell, what the repair raises it to: cos(aim), or lower: for a cell beyond the limit
//! its unmorphed quality (repair_left_alone if it was invalid), for any other its quality as
//! the morph left it (the repair makes no cell worse than that, or than the aim).
std::vector<double> repair_targets(const Index n_cells, const NonOrthoCells& cells,
                                   double limit_degrees)
{
    const double goal = cos_degrees(limit_degrees - non_ortho_margin_degrees);
    std::vector<double> targets(std::size_t(n_cells), repair_target_now);
    for (std::size_t i = 0; i < cells.cells.size(); ++i)
        targets[std::size_t(cells.cells[i])] = cells.before[i] <= repair_left_alone
                                                   ? repair_left_alone
                                                   : std::min(goal, cells.before[i]);
    return targets;
}

} // namespace

std::vector<Index> cells_beyond_limit(const PolyMesh& mesh, const MeshGeometry& geometry,
                                      double limit_degrees)
{
    const double goal = cos_degrees(limit_degrees);
    const Eigen::VectorXd ortho = face_orthogonality(mesh, geometry);
    std::vector<Index> cells;
    for (Index f = 0; f < mesh.n_internal_faces(); ++f)
        if (ortho[f] < goal)
        {
            cells.push_back(mesh.owner[f]);
            cells.push_back(mesh.neighbour[f]);
        }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    return cells;
}

std::vector<double> non_ortho_quality(const PolyMesh& mesh, const CompactList& cell_faces,
                                      const MeshGeometry& geometry, const std::vector<Index>& cells,
                                      double limit_degrees)
{
    const double weight = pyramid_weight(limit_degrees);
    std::vector<double> q(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i)
        q[i] = repair_quality(mesh, cell_faces, geometry, cells[i], weight);
    return q;
}

void assess_non_orthogonal_cells(const PolyMesh& original, const CompactList& cell_faces,
                                 double limit_degrees, NonOrthoCells& cells)
{
    const double weight = pyramid_weight(limit_degrees);
    const MeshGeometry g = geometry_around(original, cell_faces, cells.cells);
    cells.before.resize(cells.cells.size());
    for (std::size_t i = 0; i < cells.cells.size(); ++i)
    {
        const Index c = cells.cells[i];
        const bool invalid = repair_quality(original, cell_faces, g, c) <= 0.0;
        cells.before[i] =
            invalid ? repair_left_alone : repair_quality(original, cell_faces, g, c, weight);
        if (!invalid && cells.now[i] < worse_than(cells.before[i], limit_degrees))
            cells.repaired.push_back(c);
    }
}

NonOrthoRepair repair_non_orthogonality(PolyMesh& mesh, const CompactList& cell_faces,
                                        MeshGeometry& geometry, const Points& original_points,
                                        const NonOrthoCells& cells, double limit_degrees)
{
    NonOrthoRepair out;
    const double aim = limit_degrees - non_ortho_margin_degrees;
    const UntangleReport r = untangle_cells(
        mesh, cell_faces, geometry, original_points,
        repair_targets(cell_faces.size(), cells, limit_degrees), movable_points(mesh, cell_faces),
        budget, {pyramid_weight(limit_degrees), cos_degrees(aim)}, &cells.repaired);
    out.points_moved = r.points_moved;
    out.max_move = r.max_move;
    // Of the cells it took on, those still beyond the limit (the repair moves a point only
    // when the worst of its cells rises, so it takes no other cell beyond it).
    const std::vector<double> after =
        non_ortho_quality(mesh, cell_faces, geometry, cells.cells, limit_degrees);
    const double goal = cos_degrees(limit_degrees);
    for (std::size_t i = 0; i < cells.cells.size(); ++i)
        out.cells_after +=
            std::binary_search(cells.repaired.begin(), cells.repaired.end(), cells.cells[i]) &&
                    after[i] < std::min(goal, cells.before[i])
                ? 1
                : 0;
    return out;
}

} // namespace meshmorph::morph
