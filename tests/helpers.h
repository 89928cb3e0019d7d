// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Small generated meshes and helpers shared by the tests (header-only).
#pragma once

#include <array>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "meshmorph/core/poly_mesh.h"

namespace meshmorph::test
{

//! Maps block coordinates (u, v, w) in [0,1]^3 to a position.
using BlockMap = std::function<Vector3(double u, double v, double w)>;

//! A structured nx x ny x nz hex block in OpenFOAM order, as blockMesh writes it:
//! cell c = i + nx (j + ny k), point p = i + (nx+1)(j + (ny+1) k); internal faces in
//! upper-triangular order; patches xMin, xMax, yMin, yMax, zMin, zMax (type `patch`, or
//! `wall` where listed in `walls`). Face normals point from owner to neighbour / outwards.
inline PolyMesh make_block_mesh(int nx, int ny, int nz, const BlockMap& map,
                                const std::array<std::string, 6>& types = {
                                    "patch", "patch", "patch", "patch", "patch", "patch"})
{
    PolyMesh mesh;
    const auto pid = [&](int i, int j, int k) -> Index
    { return i + (nx + 1) * (j + (ny + 1) * k); };
    const auto cid = [&](int i, int j, int k) -> Index { return i + nx * (j + ny * k); };
    mesh.points.resize(static_cast<Eigen::Index>(nx + 1) * (ny + 1) * (nz + 1), 3);
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i)
                mesh.points.row(pid(i, j, k)) =
                    map(double(i) / nx, double(j) / ny, double(k) / nz).transpose();

    // Faces at the +x/+y/+z side of point (i, j, k), oriented along +axis.
    const auto face_x = [&](int i, int j, int k)
    {
        return std::array<Index, 4>{pid(i, j, k), pid(i, j + 1, k), pid(i, j + 1, k + 1),
                                    pid(i, j, k + 1)};
    };
    const auto face_y = [&](int i, int j, int k)
    {
        return std::array<Index, 4>{pid(i, j, k), pid(i, j, k + 1), pid(i + 1, j, k + 1),
                                    pid(i + 1, j, k)};
    };
    const auto face_z = [&](int i, int j, int k)
    {
        return std::array<Index, 4>{pid(i, j, k), pid(i + 1, j, k), pid(i + 1, j + 1, k),
                                    pid(i, j + 1, k)};
    };
    const auto add = [&](std::array<Index, 4> f, bool reverse, Index own)
    {
        if (reverse)
            f = {f[0], f[3], f[2], f[1]};
        mesh.faces.push_back(std::span<const Index>(f));
        mesh.owner.push_back(own);
    };

    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i)
            {
                const Index c = cid(i, j, k);
                if (i + 1 < nx)
                {
                    add(face_x(i + 1, j, k), false, c);
                    mesh.neighbour.push_back(cid(i + 1, j, k));
                }
                if (j + 1 < ny)
                {
                    add(face_y(i, j + 1, k), false, c);
                    mesh.neighbour.push_back(cid(i, j + 1, k));
                }
                if (k + 1 < nz)
                {
                    add(face_z(i, j, k + 1), false, c);
                    mesh.neighbour.push_back(cid(i, j, k + 1));
                }
            }

    const std::array<std::string, 6> names{"xMin", "xMax", "yMin", "yMax", "zMin", "zMax"};
    for (int side = 0; side < 6; ++side)
    {
        Patch patch;
        patch.name = names[side];
        patch.type = types[side];
        patch.start_face = mesh.n_faces();
        const bool upper = side % 2 == 1;
        const int axis = side / 2;
        if (axis == 0)
            for (int k = 0; k < nz; ++k)
                for (int j = 0; j < ny; ++j)
                    add(face_x(upper ? nx : 0, j, k), !upper, cid(upper ? nx - 1 : 0, j, k));
        else if (axis == 1)
            for (int k = 0; k < nz; ++k)
                for (int i = 0; i < nx; ++i)
                    add(face_y(i, upper ? ny : 0, k), !upper, cid(i, upper ? ny - 1 : 0, k));
        else
            for (int j = 0; j < ny; ++j)
                for (int i = 0; i < nx; ++i)
                    add(face_z(i, j, upper ? nz : 0), !upper, cid(i, j, upper ? nz - 1 : 0));
        patch.n_faces = mesh.n_faces() - patch.start_face;
        if (patch.type == "wall")
        {
            patch.in_groups = {"wall"};
            patch.entries = {{"inGroups", "1(wall)"}};
        }
        mesh.patches.push_back(patch);
    }
    mesh.finalize();
    return mesh;
}

//! An axis-aligned box [lo, hi] split into nx x ny x nz hexahedra.
inline PolyMesh make_box_mesh(int nx, int ny, int nz, const Vector3& lo = Vector3(0, 0, 0),
                              const Vector3& hi = Vector3(1, 1, 1))
{
    return make_block_mesh(nx, ny, nz,
                           [&](double u, double v, double w)
                           {
                               return Vector3(lo.x() + u * (hi.x() - lo.x()),
                                              lo.y() + v * (hi.y() - lo.y()),
                                              lo.z() + w * (hi.z() - lo.z()));
                           });
}

//! Two unit hexahedra side by side along x ([0,1] and [1,2] x [0,1]^2) that share no face:
//! where they touch, each has a boundary face of its own (patch "split", type `wall`: face 0
//! of cell 0, face 1 of cell 1), so the mesh has two regions. With `shared_points` both
//! faces use the same 4 points (a baffle: the regions are point connected); otherwise cell 1
//! has its own coincident copies of them (points 12..15: the regions are fully disconnected,
//! and the copies lie 0 apart).
inline PolyMesh make_split_pair_mesh(bool shared_points)
{
    const PolyMesh box = make_box_mesh(2, 1, 1, Vector3(0, 0, 0), Vector3(2, 1, 1));
    // box: face 0 is the one internal face (owner 0, neighbour 1); points at x = 1 are
    // i = 1 of pid(i, j, k) = i + 3 (j + 2 k).
    PolyMesh mesh;
    mesh.points = box.points;
    std::vector<Index> of_cell1(static_cast<std::size_t>(box.n_points()));
    for (Index p = 0; p < box.n_points(); ++p)
    {
        of_cell1[static_cast<std::size_t>(p)] = p;
        if (!shared_points && p % 3 == 1)
        {
            mesh.points.conservativeResize(mesh.points.rows() + 1, 3);
            mesh.points.row(mesh.points.rows() - 1) = box.points.row(p);
            of_cell1[static_cast<std::size_t>(p)] = mesh.points.rows() - 1;
        }
    }
    const auto add = [&](std::vector<Index> face, Index own)
    {
        if (own == 1)
            for (Index& p : face)
                p = of_cell1[static_cast<std::size_t>(p)];
        mesh.faces.push_back(std::span<const Index>(face));
        mesh.owner.push_back(own);
    };
    for (const Patch& p : box.patches)
    {
        Patch patch = p;
        patch.start_face = mesh.n_faces();
        for (Index f = p.start_face; f < p.start_face + p.n_faces; ++f)
        {
            const std::span<const Index> face = box.faces[f];
            add(std::vector<Index>(face.begin(), face.end()), box.owner[f]);
        }
        mesh.patches.push_back(patch);
    }
    Patch split;
    split.name = "split";
    split.type = "wall";
    split.in_groups = {"wall"};
    split.entries = {{"inGroups", "1(wall)"}};
    split.start_face = mesh.n_faces();
    const std::span<const Index> middle = box.faces[0]; // oriented out of cell 0
    add(std::vector<Index>(middle.begin(), middle.end()), 0);
    add({middle[0], middle[3], middle[2], middle[1]}, 1);
    split.n_faces = 2;
    mesh.patches.push_back(split);
    mesh.finalize();
    return mesh;
}

//! Path inside tests/data.
inline std::filesystem::path data_path(const std::string& relative)
{
    return std::filesystem::path(MESHMORPH_TEST_DATA_DIR) / relative;
}

//! A fresh, empty scratch directory for one test (under the build tree).
inline std::filesystem::path scratch_dir(const std::string& name)
{
    const std::filesystem::path dir = std::filesystem::path(MESHMORPH_TEST_WORK_DIR) / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

//! Whether OpenFOAM's command-line tools (Debian package `openfoam`) can be run.
//! Sets WM_PROJECT_DIR as Debian's tools need. Tests that need OpenFOAM call
//! `if (!openfoam_available()) GTEST_SKIP() << "OpenFOAM not installed ..."`.
inline bool openfoam_available()
{
    if (std::getenv("WM_PROJECT_DIR") == nullptr && std::filesystem::exists("/usr/share/openfoam"))
        setenv("WM_PROJECT_DIR", "/usr/share/openfoam", 0);
    return std::system("command -v checkMesh >/dev/null 2>&1 && command -v blockMesh "
                       ">/dev/null 2>&1") == 0;
}

} // namespace meshmorph::test
