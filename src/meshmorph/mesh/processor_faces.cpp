// SPDX-License-Identifier: GPL-3.0-or-later
// The exchange across processor patches: one message per neighbouring rank, its patches'
// faces in patch order, each face as (cell centre, cell volume, number of vertices, vertices).
#include "meshmorph/mesh/processor_faces.h"

#include <cstring>
#include <map>
#include <string>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/mesh/patch_kinds.h"
#include "meshmorph/parallel/collective.h"

namespace meshmorph
{

namespace
{

int rank_entry(const Patch& p, std::string_view key)
{
    const std::string* v = find_entry(p, key);
    if (!v)
        throw InvalidInput("processor patch " + p.name + " has no " + std::string(key));
    try
    {
        return std::stoi(*v);
    }
    catch (const std::exception&)
    {
        throw InvalidInput("processor patch " + p.name + ": " + std::string(key) + " '" + *v +
                           "' is not a rank");
    }
}

//! The doubles sent for every face of `patches` (all with one neighbour), in patch order.
std::vector<double> face_records(const PolyMesh& mesh, const MeshGeometry& g,
                                 const std::vector<const ProcessorPatch*>& patches)
{
    std::vector<double> out;
    for (const ProcessorPatch* pp : patches)
    {
        const Patch& p = mesh.patches[static_cast<std::size_t>(pp->patch)];
        for (Index f = p.start_face; f < p.start_face + p.n_faces; ++f)
        {
            const Index cell = mesh.owner[static_cast<std::size_t>(f)];
            for (int k = 0; k < 3; ++k)
                out.push_back(g.cell_centres(cell, k));
            out.push_back(g.cell_volumes[cell]);
            out.push_back(static_cast<double>(mesh.faces[f].size()));
            for (Index v : mesh.faces[f])
                for (int k = 0; k < 3; ++k)
                    out.push_back(mesh.points(v, k));
        }
    }
    return out;
}

std::string as_bytes(const std::vector<double>& v)
{
    return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
}

//! Reads the records `bytes` from rank `from` into the faces of `patches`.
void read_face_records(const PolyMesh& mesh, const std::vector<const ProcessorPatch*>& patches,
                       const std::string& bytes, int from, ProcessorFaces& out)
{
    std::vector<double> v(bytes.size() / sizeof(double));
    std::memcpy(v.data(), bytes.data(), v.size() * sizeof(double));
    std::size_t at = 0;
    const auto take = [&](const Patch& p)
    {
        if (at >= v.size())
            throw InvalidInput("processor patch " + p.name + ": rank " + std::to_string(from) +
                               " sent fewer faces than the patch has (a decomposition of "
                               "another mesh?)");
        return v[at++];
    };
    const Index n_int = mesh.n_internal_faces();
    for (const ProcessorPatch* pp : patches)
    {
        const Patch& p = mesh.patches[static_cast<std::size_t>(pp->patch)];
        for (Index f = p.start_face; f < p.start_face + p.n_faces; ++f)
        {
            const Index b = f - n_int;
            for (int k = 0; k < 3; ++k)
                out.neighbour_cell_centres(b, k) = take(p);
            out.neighbour_cell_volumes[b] = take(p);
            std::vector<Vector3>& points = out.neighbour_face_points[static_cast<std::size_t>(b)];
            points.resize(static_cast<std::size_t>(take(p)));
            for (Vector3& q : points)
                for (int k = 0; k < 3; ++k)
                    q[k] = take(p);
        }
    }
    if (at != v.size())
        throw InvalidInput("processor patches to rank " + std::to_string(from) +
                           ": the neighbour sent more faces than they have (a decomposition of "
                           "another mesh?)");
}

//! The processor patches by neighbouring rank, in patch order.
std::map<int, std::vector<const ProcessorPatch*>> by_neighbour(const ProcessorFaces& processors)
{
    std::map<int, std::vector<const ProcessorPatch*>> out;
    for (const ProcessorPatch& pp : processors.patches)
        out[pp.neighbour_rank].push_back(&pp);
    return out;
}

} // namespace

std::vector<ProcessorPatch> processor_patches(const PolyMesh& mesh, int rank)
{
    std::vector<ProcessorPatch> out;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
    {
        const Patch& p = mesh.patches[i];
        if (is_processor_cyclic_patch(p))
            throw InvalidInput("patch " + p.name +
                               ": processorCyclic (a cyclic split across ranks) is not supported "
                               "yet; decompose with the cyclic patches on one processor "
                               "(decomposeParDict preservePatches)");
        if (p.type != "processor")
            continue;
        const int mine = rank_entry(p, "myProcNo");
        if (mine != rank)
            throw InvalidInput("processor patch " + p.name + " says myProcNo " +
                               std::to_string(mine) + " but is read by rank " +
                               std::to_string(rank));
        const int neighbour = rank_entry(p, "neighbProcNo");
        out.push_back({static_cast<Index>(i), neighbour, rank < neighbour});
    }
    return out;
}

ProcessorFaces exchange_processor_faces(const PolyMesh& mesh, const MeshGeometry& g,
                                        const parallel::Communicator& comm)
{
    ProcessorFaces out;
    out.comm = &comm;
    // Collective errors: a rank that cannot read its patches must not leave the others
    // waiting in the exchange.
    parallel::collective(comm, [&] { out.patches = processor_patches(mesh, comm.rank()); });
    const Index n_int = mesh.n_internal_faces();
    const Index n_boundary = mesh.n_faces() - n_int;
    out.neighbour_cell_centres = Points::Zero(n_boundary, 3);
    out.neighbour_cell_volumes = Eigen::VectorXd::Zero(n_boundary);
    out.neighbour_face_points.resize(static_cast<std::size_t>(n_boundary));
    out.on_processor_patch.assign(static_cast<std::size_t>(n_boundary), 0);
    out.owner_side.assign(static_cast<std::size_t>(n_boundary), 0);
    for (const ProcessorPatch& pp : out.patches)
    {
        const Patch& p = mesh.patches[static_cast<std::size_t>(pp.patch)];
        for (Index f = p.start_face; f < p.start_face + p.n_faces; ++f)
        {
            out.on_processor_patch[static_cast<std::size_t>(f - n_int)] = 1;
            out.owner_side[static_cast<std::size_t>(f - n_int)] = pp.owner;
        }
    }
    const auto neighbours = by_neighbour(out);
    std::vector<std::pair<int, std::string>> sends;
    for (const auto& [neighbour, patches] : neighbours)
        sends.emplace_back(neighbour, as_bytes(face_records(mesh, g, patches)));
    const std::vector<std::string> received = comm.exchange(sends);
    std::size_t i = 0;
    for (const auto& [neighbour, patches] : neighbours)
        read_face_records(mesh, patches, received[i++], neighbour, out);
    return out;
}

std::vector<double> swap_processor_values(const PolyMesh& mesh, const ProcessorFaces& processors,
                                          const std::vector<double>& values)
{
    const Index n_int = mesh.n_internal_faces();
    const auto neighbours = by_neighbour(processors);
    std::vector<std::pair<int, std::string>> sends;
    for (const auto& [neighbour, patches] : neighbours)
    {
        std::vector<double> out;
        for (const ProcessorPatch* pp : patches)
        {
            const Patch& p = mesh.patches[static_cast<std::size_t>(pp->patch)];
            out.insert(out.end(), values.begin() + (p.start_face - n_int),
                       values.begin() + (p.start_face - n_int + p.n_faces));
        }
        sends.emplace_back(neighbour, as_bytes(out));
    }
    const std::vector<std::string> received = processors.comm->exchange(sends);
    std::vector<double> swapped(values.size(), 0.0);
    std::size_t i = 0;
    for (const auto& [neighbour, patches] : neighbours)
    {
        const std::string& bytes = received[i++];
        std::size_t at = 0;
        for (const ProcessorPatch* pp : patches)
        {
            const Patch& p = mesh.patches[static_cast<std::size_t>(pp->patch)];
            if ((at + static_cast<std::size_t>(p.n_faces)) * sizeof(double) > bytes.size())
                throw InvalidInput("processor patch " + p.name + ": rank " +
                                   std::to_string(neighbour) + " has fewer faces");
            std::memcpy(swapped.data() + (p.start_face - n_int), bytes.data() + at * sizeof(double),
                        static_cast<std::size_t>(p.n_faces) * sizeof(double));
            at += static_cast<std::size_t>(p.n_faces);
        }
    }
    return swapped;
}

} // namespace meshmorph
