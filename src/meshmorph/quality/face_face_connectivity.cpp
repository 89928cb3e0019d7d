// SPDX-License-Identifier: GPL-3.0-or-later
// Face-face connectivity, as OpenFOAM counts it: for face f, the number of (vertex position i
// of f, occurrence of g in the point's faces) pairs for every higher face g sharing a point.
#include "meshmorph/quality/face_face_connectivity.h"

#include <algorithm>

#include "meshmorph/quality/foam_vector.h"

namespace meshmorph
{

namespace
{

//! Whether sorted positions in a face of n vertices form one cyclic run. (Positions are in
//! [0, n): cyclic predecessors without integer division.)
bool one_run(const std::vector<Index>& pos, Index n)
{
    std::size_t runs = 0;
    for (std::size_t k = 0; k < pos.size(); ++k)
    {
        const Index prev = pos[k] == 0 ? n - 1 : pos[k] - 1;
        const Index before = k == 0 ? pos.back() : pos[k - 1];
        runs += prev != before;
    }
    return runs <= 1;
}

//! Per-thread scanner: one record per face (a single cache miss per shared face g); count
//! is 0 between faces.
class FaceFaceScanner
{
public:
    FaceFaceScanner(const PolyMesh& mesh, const CompactList& point_faces, FaceFaceConnectivity& out)
        : mesh_(mesh), pf_(point_faces), out_(out),
          shared_(static_cast<std::size_t>(mesh.n_faces()))
    {
    }

    void scan(Index f)
    {
        prefetch(f);
        collect(f);
        for (const Index g : touched_)
            __builtin_prefetch(mesh_.faces.offsets.data() + g);
        for (const Index g : touched_)
        {
            const Shared sg = shared_[g];
            shared_[g].count = 0;
            compare(f, g, sg);
        }
    }

private:
    struct Shared
    {
        Index count = 0, first_pos = 0, last_pos = 0; // first/last position in f
    };

    //! The higher faces of point p: p's faces are stored in ascending order.
    std::span<const Index> higher_faces(Index p, Index f) const
    {
        const Index* begin = pf_.values.data() + pf_.offsets[p];
        const Index* end = pf_.values.data() + pf_.offsets[p + 1];
        // Branch-free count of the faces <= f (lists are short: faster than a binary
        // search's mispredicted branches).
        std::ptrdiff_t n_lower = 0;
        for (const Index* k = begin; k != end; ++k)
            n_lower += *k <= f;
        return std::span<const Index>(begin + n_lower, end);
    }

    //! Memory latency dominates: prefetch the point-face lists of the next face and the
    //! list offsets of the one after (no effect on results).
    void prefetch(Index f) const
    {
        if (f + 2 >= mesh_.n_faces())
            return;
        for (const Index p : mesh_.faces[f + 1])
            __builtin_prefetch(pf_.values.data() + pf_.offsets[p]);
        for (const Index p : mesh_.faces[f + 2])
            __builtin_prefetch(pf_.offsets.data() + p);
    }

    void collect(Index f)
    {
        touched_.clear();
        const std::span<const Index> face = mesh_.faces[f];
        for (Index i = 0; i < static_cast<Index>(face.size()); ++i)
            for (const Index g : higher_faces(face[i], f))
            {
                Shared& sg = shared_[g];
                if (sg.count == 0)
                {
                    touched_.push_back(g);
                    sg.first_pos = i;
                }
                ++sg.count;
                sg.last_pos = i;
            }
    }

    void compare(Index f, Index g, const Shared& sg)
    {
        const Index n_f = mesh_.faces.item_size(f);
        const Index n_g = mesh_.faces.item_size(g);
        if (sg.count == n_g || sg.count == n_f)
        {
            if (n_g != n_f)
                ++out_.duplicates[f];
            else
                ++out_.baffles[f];
        }
        else if (sg.count >= 2 && !shared_points_consecutive(f, g, sg))
            out_.order_errors[f] = 1;
    }

    //! Shared points must form one consecutive run on both faces. Positions in f ascending
    //! (with repeats), as OpenFOAM collects them, then their positions in g.
    bool shared_points_consecutive(Index f, Index g, const Shared& sg)
    {
        const std::span<const Index> face = mesh_.faces[f];
        const std::span<const Index> other = mesh_.faces[g];
        positions_.clear();
        if (sg.count == 2)
            positions_.assign({sg.first_pos, sg.last_pos});
        else
            for (Index i = sg.first_pos; i <= sg.last_pos; ++i)
                for (const Index h : higher_faces(face[i], f))
                    if (h == g)
                        positions_.push_back(i);
        if (!one_run(positions_, static_cast<Index>(face.size())))
            return false;
        for (Index& pos : positions_)
        {
            const Index p = face[pos];
            for (Index j = 0; j < static_cast<Index>(other.size()); ++j)
                if (other[j] == p)
                {
                    pos = j;
                    break;
                }
        }
        std::sort(positions_.begin(), positions_.end());
        return one_run(positions_, static_cast<Index>(other.size()));
    }

    const PolyMesh& mesh_;
    const CompactList& pf_;
    FaceFaceConnectivity& out_;
    std::vector<Shared> shared_;
    std::vector<Index> touched_;
    std::vector<Index> positions_;
};

} // namespace

FaceFaceConnectivity face_face_connectivity(const PolyMesh& mesh, const CompactList& point_faces)
{
    const std::size_t n_faces = static_cast<std::size_t>(mesh.n_faces());
    FaceFaceConnectivity out{std::vector<Index>(n_faces, 0), std::vector<Index>(n_faces, 0),
                             std::vector<char>(n_faces, 0)};
#pragma omp parallel if (mesh.n_faces() > detail::parallel_threshold)
    {
        FaceFaceScanner scanner(mesh, point_faces, out);
#pragma omp for schedule(dynamic, 1024)
        for (Index f = 0; f < mesh.n_faces(); ++f)
            scanner.scan(f);
    }
    return out;
}

} // namespace meshmorph
