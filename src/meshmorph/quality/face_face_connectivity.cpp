// SPDX-License-Identifier: GPL-3.0-or-later
// Face-face connectivity, as OpenFOAM counts it: for face f, the number of (vertex position i
// of f, occurrence of g in the point's faces) pairs for every higher face g sharing a point.
#include "meshmorph/quality/face_face_connectivity.h"

#include <algorithm>

#include "meshmorph/mesh/foam_vector.h"

namespace meshmorph
{

namespace
{

//! What face f shares with a higher face g: one record per face g (a single cache miss),
//! count == 0 between faces.
struct Shared
{
    Index count = 0, first_pos = 0, last_pos = 0; // first/last position in f
};

//! Point -> faces lists (each ascending) as raw arrays.
struct PointFaceLists
{
    const Index* offsets;
    const Index* values;

    //! The faces of point p above face f. Branch-free count of the faces <= f (lists are
    //! short: faster than a binary search's mispredicted branches).
    std::span<const Index> higher(Index p, Index f) const
    {
        const Index* begin = values + offsets[p];
        const Index* end = values + offsets[p + 1];
        std::ptrdiff_t n_lower = 0;
        for (const Index* k = begin; k != end; ++k)
            n_lower += *k <= f;
        return std::span<const Index>(begin + n_lower, end);
    }
};

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

//! Whether the points f shares with g form one consecutive run on both faces. Positions in
//! f ascending (with repeats), as OpenFOAM collects them, then their positions in g.
bool consecutive_on_both(std::span<const Index> face, std::span<const Index> other, Index f,
                         Index g, const Shared& sg, const PointFaceLists& pf,
                         std::vector<Index>& positions)
{
    positions.clear();
    if (sg.count == 2)
        positions.assign({sg.first_pos, sg.last_pos});
    else
        for (Index i = sg.first_pos; i <= sg.last_pos; ++i)
            for (const Index h : pf.higher(face[i], f))
                if (h == g)
                    positions.push_back(i);
    if (!one_run(positions, static_cast<Index>(face.size())))
        return false;
    for (Index& pos : positions)
    {
        const Index p = face[pos];
        for (Index j = 0; j < static_cast<Index>(other.size()); ++j)
            if (other[j] == p)
            {
                pos = j;
                break;
            }
    }
    std::sort(positions.begin(), positions.end());
    return one_run(positions, static_cast<Index>(other.size()));
}

//! Per-thread scratch space.
struct Scratch
{
    std::vector<Shared> shared;
    std::vector<Index> touched;
    std::vector<Index> positions;
    std::vector<Index> partners; //!< the higher faces of flagged pairs (merged at the end)
};

//! Record in s.shared / s.touched every higher face sharing a point with face f.
void collect_shared(std::span<const Index> face, Index f, const PointFaceLists& pf, Scratch& s)
{
    s.touched.clear();
    Shared* const shared = s.shared.data();
    for (Index i = 0; i < static_cast<Index>(face.size()); ++i)
        for (const Index g : pf.higher(face[i], f))
        {
            Shared& sg = shared[g];
            if (sg.count == 0)
            {
                s.touched.push_back(g);
                sg.first_pos = i;
            }
            ++sg.count;
            sg.last_pos = i;
        }
}

void scan_face(const PolyMesh& mesh, const PointFaceLists& pf, Index f, Scratch& s,
               FaceFaceConnectivity& out)
{
    // Memory latency dominates: prefetch the point-face lists of the next face and the list
    // offsets of the one after (no effect on results).
    if (f + 2 < mesh.n_faces())
    {
        for (const Index p : mesh.faces[f + 1])
            __builtin_prefetch(pf.values + pf.offsets[p]);
        for (const Index p : mesh.faces[f + 2])
            __builtin_prefetch(pf.offsets + p);
    }
    const std::span<const Index> face = mesh.faces[f];
    collect_shared(face, f, pf, s);
    for (const Index g : s.touched)
        __builtin_prefetch(mesh.faces.offsets.data() + g);
    const Index n_f = static_cast<Index>(face.size());
    for (const Index g : s.touched)
    {
        const Shared sg = s.shared[g];
        s.shared[g].count = 0;
        const std::span<const Index> other = mesh.faces[g];
        const Index n_g = static_cast<Index>(other.size());
        if (sg.count == n_g || sg.count == n_f)
        {
            if (n_g != n_f)
                ++out.duplicates[f];
            else
                ++out.baffles[f];
        }
        else if (sg.count >= 2 && !consecutive_on_both(face, other, f, g, sg, pf, s.positions))
            out.order_errors[f] = 1;
        else
            continue;
        // OpenFOAM inserts both faces of the pair into the set.
        out.in_pair[f] = 1;
        s.partners.push_back(g);
    }
}

} // namespace

FaceFaceConnectivity face_face_connectivity(const PolyMesh& mesh, const CompactList& point_faces)
{
    const std::size_t n_faces = static_cast<std::size_t>(mesh.n_faces());
    FaceFaceConnectivity out{std::vector<Index>(n_faces, 0), std::vector<Index>(n_faces, 0),
                             std::vector<char>(n_faces, 0), std::vector<char>(n_faces, 0)};
    const PointFaceLists pf{point_faces.offsets.data(), point_faces.values.data()};
    std::vector<Index> partners;
#pragma omp parallel if (mesh.n_faces() > detail::parallel_threshold)
    {
        Scratch scratch{std::vector<Shared>(n_faces), {}, {}, {}};
#pragma omp for schedule(dynamic, 1024)
        for (Index f = 0; f < mesh.n_faces(); ++f)
            scan_face(mesh, pf, f, scratch, out);
#pragma omp critical
        partners.insert(partners.end(), scratch.partners.begin(), scratch.partners.end());
    }
    for (const Index g : partners)
        out.in_pair[static_cast<std::size_t>(g)] = 1;
    return out;
}

} // namespace meshmorph
