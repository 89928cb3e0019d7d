// SPDX-License-Identifier: GPL-3.0-or-later
// Smart Laplacian smoothing of the interior points around the cells a morph inverted.
#include "meshmorph/morph/local_untangle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "meshmorph/core/types.h"

namespace meshmorph::morph
{

namespace
{

//! A move must raise the local quality by this much to count (stops endless tiny moves).
constexpr double min_gain = 1e-9;
constexpr double repair_margin = repair_margin_cosine;
constexpr double left_alone = repair_left_alone;
//! Quality of a cell whose volume is not positive: below any cosine.
constexpr double collapsed = -2.0;

Vector3 row3(const Points& p, Index i)
{
    return p.row(i).transpose();
}

//! Cosine of the angle between a and b, 0 when either vanishes.
double cosine(const Vector3& a, const Vector3& b)
{
    const double m = a.norm() * b.norm();
    return m > 0.0 ? a.dot(b) / m : 0.0;
}

//! Whether a face pyramid of cell c is wrongly oriented, or an internal face of c has a
//! non-orthogonality of 90 degrees or more (checkMesh's face pyramid and orthogonality
//! errors, with OpenFOAM's SMALL).
bool face_invalid_in_cell(const PolyMesh& mesh, const MeshGeometry& g, Index f, Index c)
{
    const Vector3 af = row3(g.face_areas, f);
    const Vector3 cf = row3(g.face_centres, f);
    const double sign = mesh.owner[f] == c ? -1.0 : 1.0;
    if (sign * (1.0 / 3.0) * af.dot(row3(g.cell_centres, c) - cf) < -constants::small)
        return true;
    if (f >= mesh.n_internal_faces())
        return false;
    const Vector3 d = row3(g.cell_centres, mesh.neighbour[f]) - row3(g.cell_centres, mesh.owner[f]);
    return af.dot(d) / (af.norm() * d.norm() + constants::vsmall) <= constants::small;
}

bool cell_invalid(const PolyMesh& mesh, const CompactList& cell_faces, const MeshGeometry& g,
                  Index c)
{
    if (g.cell_volumes[c] < constants::vsmall)
        return true;
    for (Index f : cell_faces[c])
        if (face_invalid_in_cell(mesh, g, f, c))
            return true;
    return false;
}

} // namespace

double repair_quality(const PolyMesh& mesh, const CompactList& cell_faces, const MeshGeometry& g,
                      Index c, double pyramid_weight)
{
    if (g.cell_volumes[c] < constants::vsmall)
        return collapsed;
    double q = 1.0;
    const Vector3 cc = row3(g.cell_centres, c);
    for (Index f : cell_faces[c])
    {
        const Vector3 af = row3(g.face_areas, f);
        const double outward = mesh.owner[f] == c ? 1.0 : -1.0;
        q = std::min(q, pyramid_weight * outward * cosine(af, row3(g.face_centres, f) - cc));
        if (f < mesh.n_internal_faces())
            q = std::min(q, cosine(af, row3(g.cell_centres, mesh.neighbour[f]) -
                                           row3(g.cell_centres, mesh.owner[f])));
    }
    return q;
}

namespace
{

//! A cell the repair must raise: below its target (and not invalid from the start).
bool below_target(const PolyMesh& mesh, const CompactList& cell_faces, const MeshGeometry& g,
                  const std::vector<double>& targets, Index c, double pyramid_weight)
{
    const double target = targets[static_cast<std::size_t>(c)];
    return target > left_alone && repair_quality(mesh, cell_faces, g, c, pyramid_weight) < target;
}

//! Inverse of cell_points: the cells around each point.
CompactList point_cells(Index n_points, const CompactList& cell_points)
{
    CompactList pc;
    std::vector<Index> count(static_cast<std::size_t>(n_points) + 1, 0);
    for (Index p : cell_points.values)
        ++count[static_cast<std::size_t>(p) + 1];
    for (std::size_t i = 1; i < count.size(); ++i)
        count[i] += count[i - 1];
    pc.offsets = count;
    pc.values.resize(cell_points.values.size());
    for (Index c = 0; c < cell_points.size(); ++c)
        for (Index p : cell_points[c])
            pc.values[static_cast<std::size_t>(count[static_cast<std::size_t>(p)]++)] = c;
    return pc;
}

//! Moves points one at a time, keeping the geometry of their faces and cells current.
class Untangler
{
public:
    Untangler(PolyMesh& mesh, const CompactList& cell_faces, MeshGeometry& g,
              const Points& original, const std::vector<double>& targets,
              const std::vector<char>& movable, const RepairGoal& goal)
        : mesh_(mesh), cell_faces_(cell_faces), g_(g), original_(original), targets_(targets),
          movable_(movable), goal_(goal), cell_points_(cell_points(mesh, cell_faces)),
          point_cells_(point_cells(mesh.n_points(), cell_points_)),
          in_region_(static_cast<std::size_t>(cell_faces.size()), 0),
          watched_(static_cast<std::size_t>(cell_faces.size()), 0),
          moved_(static_cast<std::size_t>(mesh.n_points()), 0)
    {
    }

    void add_cells(const std::vector<Index>& cells)
    {
        for (Index c : cells)
            add_cell(c);
    }

    //! Add every cell that shares a point with the region.
    void grow_layer()
    {
        const std::vector<Index> frontier = region_;
        for (Index c : frontier)
            for (Index p : cell_points_[c])
                for (Index n : point_cells_[p])
                    add_cell(n);
    }

    //! The watched cells checkMesh counts as invalid (but for those invalid from the start).
    Index count_invalid() const
    {
        return count_watched(
            [&](Index c)
            {
                return targets_[static_cast<std::size_t>(c)] > left_alone &&
                       cell_invalid(mesh_, cell_faces_, g_, c);
            });
    }

    //! The watched cells still below their repair target.
    Index count_below_target() const
    {
        return count_watched([&](Index c) { return below_target(c); });
    }

    //! One pass over the region's movable points. \return whether any point moved.
    bool sweep()
    {
        bool any = false;
        for (Index p : region_points())
            any = relax(p) || any;
        return any;
    }

    Index points_moved() const { return static_cast<Index>(start_.size()); }

    double max_move() const
    {
        double m = 0.0;
        for (const auto& [p, x] : start_)
            m = std::max(m, (row3(mesh_.points, p) - x).norm());
        return m;
    }

private:
    bool below_target(Index c) const
    {
        resolve_target(c);
        return morph::below_target(mesh_, cell_faces_, g_, targets_, c, goal_.pyramid_weight);
    }

    //! A target given as NaN (repair_target_now) becomes the cell's quality now, capped at
    //! good_enough: called before any point of the cell moves (relax() resolves a point's
    //! cells first), so "now" is as the morph left it.
    void resolve_target(Index c) const
    {
        double& t = targets_[static_cast<std::size_t>(c)];
        if (std::isnan(t))
            t = std::min(goal_.good_enough,
                         repair_quality(mesh_, cell_faces_, g_, c, goal_.pyramid_weight));
    }

    //! How many watched cells satisfy `pred`: the region's and every cell a moved point
    //! touches (a move raises the worst cell around its point, and may lower another one).
    template <class Pred> Index count_watched(Pred pred) const
    {
        Index n = 0;
        for (Index c : watched_cells_)
            n += pred(c) ? 1 : 0;
        return n;
    }

    void watch(Index c)
    {
        if (watched_[static_cast<std::size_t>(c)])
            return;
        watched_[static_cast<std::size_t>(c)] = 1;
        watched_cells_.push_back(c);
    }

    void add_cell(Index c)
    {
        if (in_region_[static_cast<std::size_t>(c)])
            return;
        resolve_target(c);
        in_region_[static_cast<std::size_t>(c)] = 1;
        region_.push_back(c);
        watch(c);
    }

    std::vector<Index> region_points() const
    {
        std::vector<Index> pts;
        for (Index c : region_)
            for (Index p : cell_points_[c])
                if (movable_[static_cast<std::size_t>(p)])
                    pts.push_back(p);
        std::sort(pts.begin(), pts.end());
        pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
        return pts;
    }

    //! The faces of p's cells that contain p.
    std::vector<Index> faces_of(Index p) const
    {
        std::vector<Index> faces;
        for (Index c : point_cells_[p])
            for (Index f : cell_faces_[c])
            {
                const std::span<const Index> face = mesh_.faces[f];
                if (std::find(face.begin(), face.end(), p) != face.end())
                    faces.push_back(f);
            }
        std::sort(faces.begin(), faces.end());
        faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
        return faces;
    }

    //! The points joined to p by an edge of one of its faces.
    std::vector<Index> edge_neighbours(Index p, const std::vector<Index>& faces) const
    {
        std::vector<Index> nbrs;
        for (Index f : faces)
        {
            const std::span<const Index> face = mesh_.faces[f];
            const std::size_t n = face.size();
            const std::size_t i =
                static_cast<std::size_t>(std::find(face.begin(), face.end(), p) - face.begin());
            nbrs.push_back(face[(i + 1) % n]);
            nbrs.push_back(face[(i + n - 1) % n]);
        }
        std::sort(nbrs.begin(), nbrs.end());
        nbrs.erase(std::unique(nbrs.begin(), nbrs.end()), nbrs.end());
        return nbrs;
    }

    double quality_around(Index p) const
    {
        double q = 1.0;
        for (Index c : point_cells_[p])
            q = std::min(q, repair_quality(mesh_, cell_faces_, g_, c, goal_.pyramid_weight));
        return q;
    }

    //! Put p at x and update the geometry of its faces and cells.
    void place(Index p, const Vector3& x, const std::vector<Index>& faces)
    {
        mesh_.points.row(p) = x.transpose();
        for (Index f : faces)
            face_centre_and_area(mesh_, f, g_.face_centres, g_.face_areas);
        for (Index c : point_cells_[p])
            cell_centre_and_volume(mesh_, cell_faces_, c, g_);
    }

    //! Where p may go: the mean of its edge neighbours, the mean of its cells' centres,
    //! and its original position moved by its neighbours' mean displacement.
    std::array<Vector3, 3> targets(Index p, const std::vector<Index>& nbrs) const
    {
        Vector3 mean = Vector3::Zero(), shift = Vector3::Zero(), centres = Vector3::Zero();
        for (Index n : nbrs)
        {
            mean += row3(mesh_.points, n);
            shift += row3(mesh_.points, n) - row3(original_, n);
        }
        for (Index c : point_cells_[p])
            centres += row3(g_.cell_centres, c);
        const double k = static_cast<double>(std::max<std::size_t>(nbrs.size(), 1));
        const double m = static_cast<double>(std::max<Index>(point_cells_.item_size(p), 1));
        return {mean / k, centres / m, row3(original_, p) + shift / k};
    }

    //! The quality around p if it were at y (p is put back at x).
    double quality_at(Index p, const Vector3& y, const std::vector<Index>& faces)
    {
        place(p, y, faces);
        return quality_around(p);
    }

    //! The direction in which the quality around p rises fastest (a forward difference of
    //! its worst term, which the smallest cosine is where it is differentiable); zero when
    //! flat. \param h the difference step.
    Vector3 ascent(Index p, const Vector3& x, double now, double h, const std::vector<Index>& faces)
    {
        Vector3 grad;
        for (int k = 0; k < 3; ++k)
            grad[k] = (quality_at(p, x + h * Vector3::Unit(k), faces) - now) / h;
        const double n = grad.norm();
        return n > 0.0 ? Vector3(grad / n) : Vector3(Vector3::Zero());
    }

    //! Where p may go: its targets at full, half and quarter distance, and steps of 1/2 to
    //! 1/50 of its mean edge length up the quality's ascent direction.
    std::vector<Vector3> candidates(Index p, const Vector3& x, double now,
                                    const std::vector<Index>& faces)
    {
        const std::vector<Index> nbrs = edge_neighbours(p, faces);
        std::vector<Vector3> out;
        for (const Vector3& target : targets(p, nbrs))
            for (double t : {1.0, 0.5, 0.25})
                out.push_back(x + t * (target - x));
        double length = 0.0;
        for (Index n : nbrs)
            length += (row3(mesh_.points, n) - x).norm();
        length /= static_cast<double>(std::max<std::size_t>(nbrs.size(), 1));
        const Vector3 d = ascent(p, x, now, 1e-4 * length, faces);
        if (d.squaredNorm() > 0.0)
            for (double s : {0.5, 0.25, 0.1, 0.05, 0.02})
                out.push_back(x + s * length * d);
        return out;
    }

    //! Try p's candidates; keep the best if it raises the quality around p.
    //! \return whether p moved.
    bool relax(Index p)
    {
        const double now = quality_around(p);
        if (now >= goal_.good_enough)
            return false;
        for (Index c : point_cells_[p])
            resolve_target(c);
        const std::vector<Index> faces = faces_of(p);
        const Vector3 x = row3(mesh_.points, p);
        Vector3 best_x = x;
        double best = now;
        for (const Vector3& y : candidates(p, x, now, faces))
        {
            const double q = quality_at(p, y, faces);
            if (q > best)
            {
                best = q;
                best_x = y;
            }
        }
        const bool moves = best > now + min_gain;
        place(p, moves ? best_x : x, faces);
        if (moves && !moved_[static_cast<std::size_t>(p)])
        {
            moved_[static_cast<std::size_t>(p)] = 1;
            start_.emplace_back(p, x);
            for (Index c : point_cells_[p])
                watch(c);
        }
        return moves;
    }

    PolyMesh& mesh_;
    const CompactList& cell_faces_;
    MeshGeometry& g_;
    const Points& original_;
    mutable std::vector<double> targets_; //!< a copy: NaN entries resolved on first use
    const std::vector<char>& movable_;
    const RepairGoal goal_;
    CompactList cell_points_, point_cells_;
    std::vector<char> in_region_;
    std::vector<Index> region_;
    std::vector<char> watched_;
    std::vector<Index> watched_cells_; //!< the region's cells and those of moved points
    std::vector<char> moved_;
    std::vector<std::pair<Index, Vector3>> start_; //!< where each moved point was
};

//! f(c) for every cell c, on every thread.
template <class T, class F> std::vector<T> per_cell(Index n, F f)
{
    std::vector<T> values(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
    for (Index c = 0; c < n; ++c)
        values[static_cast<std::size_t>(c)] = static_cast<T>(f(c));
    return values;
}

//! The cells below their repair target now (none that were invalid in the original mesh).
std::vector<Index> cells_below_target(const PolyMesh& mesh, const CompactList& cell_faces,
                                      const MeshGeometry& g, const std::vector<double>& targets,
                                      double pyramid_weight)
{
    std::vector<Index> cells;
    for (Index c = 0; c < cell_faces.size(); ++c)
        if (below_target(mesh, cell_faces, g, targets, c, pyramid_weight))
            cells.push_back(c);
    return cells;
}

} // namespace

Index count_cells_below_target(const PolyMesh& mesh, const CompactList& cell_faces,
                               const MeshGeometry& geometry, const std::vector<double>& targets,
                               double pyramid_weight)
{
    Index count = 0;
#pragma omp parallel for schedule(static) reduction(+ : count)
    for (Index c = 0; c < cell_faces.size(); ++c)
        count += below_target(mesh, cell_faces, geometry, targets, c, pyramid_weight) ? 1 : 0;
    return count;
}

std::vector<char> invalid_cell_flags(const PolyMesh& mesh, const CompactList& cell_faces,
                                     const MeshGeometry& g)
{
    return per_cell<char>(cell_faces.size(),
                          [&](Index c) { return cell_invalid(mesh, cell_faces, g, c) ? 1 : 0; });
}

std::vector<double> repair_targets(const PolyMesh& original, const CompactList& cell_faces,
                                   const MeshGeometry& g)
{
    return per_cell<double>(cell_faces.size(),
                            [&](Index c)
                            {
                                return cell_invalid(original, cell_faces, g, c)
                                           ? left_alone
                                           : std::min(repair_margin,
                                                      repair_quality(original, cell_faces, g, c));
                            });
}

UntangleReport untangle_cells(PolyMesh& mesh, const CompactList& cell_faces, MeshGeometry& geometry,
                              const Points& original_points, const std::vector<double>& targets,
                              const std::vector<char>& movable, const UntangleSettings& settings,
                              const RepairGoal& goal, const std::vector<Index>* start)
{
    UntangleReport report;
    const std::vector<Index> poor =
        start != nullptr
            ? *start
            : cells_below_target(mesh, cell_faces, geometry, targets, goal.pyramid_weight);
    if (poor.empty())
        return report;
    Untangler untangler(mesh, cell_faces, geometry, original_points, targets, movable, goal);
    untangler.add_cells(poor);
    report.invalid_before = untangler.count_invalid();
    Index remaining = static_cast<Index>(poor.size());
    for (int layers = 1; layers <= settings.max_layers && remaining > 0; layers *= 2)
    {
        while (report.layers < layers)
        {
            untangler.grow_layer();
            ++report.layers;
        }
        for (int s = 0; s < settings.sweeps && remaining > 0; ++s)
        {
            if (!untangler.sweep())
                break;
            remaining = untangler.count_below_target();
        }
    }
    report.invalid_after = untangler.count_invalid();
    report.below_target_after = remaining;
    report.points_moved = untangler.points_moved();
    report.max_move = untangler.max_move();
    return report;
}

} // namespace meshmorph::morph
