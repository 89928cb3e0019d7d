// SPDX-License-Identifier: GPL-3.0-or-later
// VTK XML export: the mesh as plain arrays (vtk_export.h), serialised by the VTK module and
// then written atomically.
#include "meshmorph/io/vtk_writer.h"

#include <algorithm>
#include <set>
#include <string_view>

#include "meshmorph/core/cell_shapes.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/vtk_export.h"
#include "meshmorph/io/vtk_module_loader.h"

namespace meshmorph::io
{
namespace
{

void check_fields(const std::filesystem::path& path, const std::vector<VtkField>& fields,
                  Index rows, std::string_view what,
                  std::initializer_list<std::string_view> reserved)
{
    std::set<std::string> names;
    for (const VtkField& f : fields)
    {
        const std::string where =
            path.string() + ": " + std::string(what) + " array '" + f.name + "'";
        if (f.name.empty())
            throw InvalidInput(path.string() + ": " + std::string(what) + " array with empty name");
        if (std::find(reserved.begin(), reserved.end(), f.name) != reserved.end())
            throw InvalidInput(where + ": name is reserved by the writer");
        if (!names.insert(f.name).second)
            throw InvalidInput(where + ": duplicate name");
        if (f.values.rows() != rows)
            throw InvalidInput(where + ": " + std::to_string(f.values.rows()) + " rows, expected " +
                               std::to_string(rows));
        if (f.values.cols() < 1)
            throw InvalidInput(where + ": no components");
    }
}

//! The field as an array description (no copy).
VtkDoubles doubles(const VtkField& f)
{
    return {f.name, static_cast<int>(f.values.cols()), f.values.rows(), f.values.data()};
}

//! The field's rows `rows`, gathered into `storage` (which must outlive the description).
VtkDoubles gathered(const VtkField& f, const std::vector<Index>& rows, std::vector<double>& storage)
{
    const std::size_t k = static_cast<std::size_t>(f.values.cols());
    storage.resize(rows.size() * k);
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < k; ++j)
            storage[i * k + j] = f.values(rows[i], Eigen::Index(j));
    return {f.name, static_cast<int>(k), static_cast<std::int64_t>(rows.size()), storage.data()};
}

std::vector<VtkId> ids(const std::vector<Index>& values)
{
    return {values.begin(), values.end()};
}

//! The data set's bytes from the VTK module. \throw IoError naming the path.
std::string serialise(const VtkExport& data, const std::filesystem::path& path)
{
    std::string out, error;
    if (!vtk_serialiser()(data, out, error))
        throw IoError(path.string() + ": " + error);
    return out;
}

} // namespace

void write_vtu(const std::filesystem::path& path, const PolyMesh& mesh,
               const std::vector<VtkField>& point_data, const std::vector<VtkField>& cell_data)
{
    check_fields(path, point_data, mesh.n_points(), "point", {});
    check_fields(path, cell_data, mesh.n_cells, "cell", {"cellID"});
    if (static_cast<Index>(mesh.owner.size()) != mesh.n_faces())
        throw InvalidInput(path.string() + ": " + std::to_string(mesh.owner.size()) +
                           " owners for " + std::to_string(mesh.n_faces()) + " faces");
    for (Index v : mesh.faces.values)
        if (v < 0 || v >= mesh.n_points())
            throw InvalidInput(path.string() + ": face point label " + std::to_string(v) +
                               " outside [0, " + std::to_string(mesh.n_points()) + ")");

    const CompactList cf = cell_faces(mesh);
    const VtkCells cells = vtk_cells(mesh, cf, classify_cells(mesh, cf));
    const Index n_cells = mesh.n_cells;

    VtkExport data;
    data.kind = VtkExport::Kind::unstructured_grid;
    data.n_points = mesh.n_points();
    data.points = mesh.points.data();
    data.cell_types.resize(static_cast<std::size_t>(n_cells));
    for (Index c = 0; c < n_cells; ++c)
        data.cell_types[std::size_t(c)] = static_cast<unsigned char>(cells.types[c]);
    data.offsets = ids(cells.points.offsets);
    data.connectivity = ids(cells.points.values);
    if (!cells.face_streams.values.empty())
    {
        data.face_locations.assign(static_cast<std::size_t>(n_cells), -1);
        for (Index c = 0; c < n_cells; ++c)
            if (cells.face_streams.item_size(c) > 0)
                data.face_locations[std::size_t(c)] = cells.face_streams.offsets[c];
        data.faces = ids(cells.face_streams.values);
    }
    for (const VtkField& f : point_data)
        data.point_data.push_back(doubles(f));
    VtkIds cell_ids{"cellID", std::vector<VtkId>(static_cast<std::size_t>(n_cells))};
    for (Index c = 0; c < n_cells; ++c)
        cell_ids.values[std::size_t(c)] = c;
    data.cell_ids.push_back(std::move(cell_ids));
    for (const VtkField& f : cell_data)
        data.cell_data.push_back(doubles(f));
    write_file_atomic(path, serialise(data, path));
}

void write_vtp_patches(const std::filesystem::path& path, const PolyMesh& mesh,
                       const std::vector<Index>& patches, const std::vector<VtkField>& point_data,
                       const std::vector<VtkField>& face_data)
{
    std::vector<Index> selected = patches;
    if (selected.empty())
        for (Index p = 0; p < static_cast<Index>(mesh.patches.size()); ++p)
            selected.push_back(p);
    Index n_faces = 0;
    for (Index p : selected)
    {
        if (p < 0 || p >= static_cast<Index>(mesh.patches.size()))
            throw InvalidInput(path.string() + ": patch index " + std::to_string(p) +
                               " out of range [0, " + std::to_string(mesh.patches.size()) + ")");
        const Patch& patch = mesh.patches[p];
        if (patch.start_face < 0 || patch.n_faces < 0 ||
            patch.start_face + patch.n_faces > mesh.n_faces())
            throw InvalidInput(path.string() + ": patch '" + patch.name + "' faces [" +
                               std::to_string(patch.start_face) + ", " +
                               std::to_string(patch.start_face + patch.n_faces) +
                               ") outside the mesh's " + std::to_string(mesh.n_faces()) + " faces");
        n_faces += patch.n_faces;
    }
    check_fields(path, point_data, mesh.n_points(), "point", {"pointID"});
    check_fields(path, face_data, n_faces, "face", {"patchID", "faceID"});

    // Compact point numbering in order of first appearance.
    std::vector<Index> local(static_cast<std::size_t>(mesh.n_points()), -1);
    std::vector<Index> point_ids;
    std::vector<Index> offsets{0};
    std::vector<Index> conn;
    std::vector<Index> patch_ids;
    std::vector<Index> face_ids;
    for (Index p : selected)
    {
        const Patch& patch = mesh.patches[p];
        for (Index f = patch.start_face; f < patch.start_face + patch.n_faces; ++f)
        {
            for (Index v : mesh.faces[f])
            {
                if (v < 0 || v >= mesh.n_points())
                    throw InvalidInput(path.string() + ": face " + std::to_string(f) +
                                       " has point label " + std::to_string(v) + " outside [0, " +
                                       std::to_string(mesh.n_points()) + ")");
                if (local[v] < 0)
                {
                    local[v] = static_cast<Index>(point_ids.size());
                    point_ids.push_back(v);
                }
                conn.push_back(local[v]);
            }
            offsets.push_back(static_cast<Index>(conn.size()));
            patch_ids.push_back(p);
            face_ids.push_back(f);
        }
    }

    Points xyz(static_cast<Eigen::Index>(point_ids.size()), 3);
    for (std::size_t i = 0; i < point_ids.size(); ++i)
        xyz.row(Eigen::Index(i)) = mesh.points.row(point_ids[i]);
    VtkExport data;
    data.kind = VtkExport::Kind::poly_data;
    data.n_points = xyz.rows();
    data.points = xyz.data();
    data.offsets = ids(offsets);
    data.connectivity = ids(conn);
    data.point_ids.push_back({"pointID", ids(point_ids)});
    std::vector<std::vector<double>> storage(point_data.size());
    for (std::size_t k = 0; k < point_data.size(); ++k)
        data.point_data.push_back(gathered(point_data[k], point_ids, storage[k]));
    data.cell_ids.push_back({"patchID", ids(patch_ids)});
    data.cell_ids.push_back({"faceID", ids(face_ids)});
    for (const VtkField& f : face_data)
        data.cell_data.push_back(doubles(f));
    for (const Patch& patch : mesh.patches)
        data.field_strings.push_back(patch.name);
    write_file_atomic(path, serialise(data, path));
}

} // namespace meshmorph::io
