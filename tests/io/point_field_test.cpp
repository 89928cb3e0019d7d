// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of io/point_field.h with fixtures written by OpenFOAM's moveMesh
// (tests/data/io/point_field, see its README.md) and hand-made broken variants.
#include <gtest/gtest.h>

#include <string>

#include "io_test_util.h"
#include "meshmorph/io/point_field.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"

using namespace meshmorph;
using namespace meshmorph::io;
namespace fs = std::filesystem;

namespace
{

const PointPatchField& patch_field(const PointVectorField& f, const std::string& name)
{
    for (const PointPatchField& p : f.patches)
        if (p.patch == name)
            return p;
    throw std::runtime_error("no patch " + name);
}

// A copy of the ASCII fixture case whose 0/pointDisplacement has `from` replaced by `to`.
fs::path edited_case(const std::string& name, const std::string& from, const std::string& to)
{
    const fs::path dir = test::scratch_dir("pf_" + name);
    test::copy_tree(test::data_path("io/point_field/ascii"), dir);
    std::string text = test::file_bytes(dir / "0/pointDisplacement");
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    test::write_bytes(dir / "0/pointDisplacement", text);
    return dir;
}

} // namespace

TEST(PointField, matches_patches_by_name_group_and_regex)
{
    const fs::path case_dir = test::data_path("io/point_field/ascii");
    const FoamPolyMesh m = read_poly_mesh(case_dir, {});
    const PointVectorField f = read_point_vector_field(case_dir, "0", "pointDisplacement", m.mesh);
    ASSERT_EQ(f.patches.size(), m.mesh.patches.size());
    EXPECT_TRUE(f.internal_is_uniform);
    EXPECT_EQ(f.internal.rows(), m.mesh.n_points());
    EXPECT_TRUE(f.internal.isZero(0));

    const PointPatchField& outlet = patch_field(f, "outlet");
    EXPECT_EQ(outlet.matched_by, PointPatchField::Match::name);
    EXPECT_EQ(outlet.type, "fixedValue");
    ASSERT_TRUE(outlet.value);
    const std::vector<Index> outlet_points =
        patch_points(m.mesh, m.mesh.patches[static_cast<std::size_t>(m.mesh.find_patch("outlet"))]);
    ASSERT_EQ(outlet.value->rows(), static_cast<Eigen::Index>(outlet_points.size()));
    // The fixture moves the outlet's only interior point (x = 0.2, y = z = 0.05) by 0.01 in x.
    for (std::size_t i = 0; i < outlet_points.size(); ++i)
    {
        const Eigen::RowVector3d x = m.mesh.points.row(outlet_points[i]);
        const bool centre = std::abs(x.y() - 0.05) < 1e-12 && std::abs(x.z() - 0.05) < 1e-12;
        EXPECT_EQ(outlet.value->row(static_cast<Eigen::Index>(i)),
                  centre ? Eigen::RowVector3d(0.01, 0, 0) : Eigen::RowVector3d(0, 0, 0));
    }
    EXPECT_EQ(patch_field(f, "walls").matched_by, PointPatchField::Match::group);
    EXPECT_EQ(patch_field(f, "walls").key, "wall");
    EXPECT_EQ(patch_field(f, "inlet").matched_by, PointPatchField::Match::regex);
    EXPECT_EQ(patch_field(f, "frontAndBack").matched_by, PointPatchField::Match::regex);
    EXPECT_TRUE(patch_field(f, "frontAndBack").is_uniform);
}

TEST(PointField, applied_values_reproduce_openfoam_movemesh)
{
    // moveMesh wrote 1/pointDisplacement (full nonuniform internalField) and
    // 1/polyMesh/points = constant points + displacement.
    for (const char* variant : {"ascii", "binary"})
    {
        SCOPED_TRACE(variant);
        const fs::path case_dir = test::data_path(std::string("io/point_field/") + variant);
        const FoamPolyMesh m0 = read_poly_mesh(case_dir, {});
        PolyMeshReadOptions at1;
        at1.time = TimeSelection::at("1");
        const FoamPolyMesh m1 = read_poly_mesh(case_dir, at1);
        EXPECT_EQ(m1.points_instance, "1");
        const PointVectorField f0 =
            read_point_vector_field(case_dir, "0", "pointDisplacement", m0.mesh);
        const PointVectorField f1 =
            read_point_vector_field(case_dir, "1", "pointDisplacement", m0.mesh);
        EXPECT_EQ(f1.header.is_binary(), std::string(variant) == "binary");
        EXPECT_FALSE(f1.internal_is_uniform);

        // Our boundary evaluation of the 0 field equals OpenFOAM's on every boundary point.
        const Points applied = apply_patch_values(f0, m0.mesh);
        const std::vector<char> on_boundary = boundary_point_mask(m0.mesh);
        for (Index p = 0; p < m0.mesh.n_points(); ++p)
        {
            if (on_boundary[static_cast<std::size_t>(p)])
            {
                EXPECT_EQ(applied.row(p), f1.internal.row(p)) << "point " << p;
            }
        }

        // And the moved points are the original ones plus OpenFOAM's displacement. ASCII
        // points are printed at writePrecision 12: allow that rounding (|x| <= 0.21).
        const double tol = std::string(variant) == "binary" ? 0.0 : 1e-12;
        const Points expected = m0.mesh.points + f1.internal;
        EXPECT_LE((m1.mesh.points - expected).cwiseAbs().maxCoeff(), tol);
    }
}

TEST(PointField, reports_missing_entries_and_unsupported_types_by_patch)
{
    const FoamPolyMesh m = read_poly_mesh(test::data_path("io/point_field/ascii"), {});
    const auto error_for = [&](const fs::path& dir) {
        return test::error_of([&]
                              { read_point_vector_field(dir, "0", "pointDisplacement", m.mesh); });
    };
    const std::string missing =
        error_for(edited_case("missing", "    \"(inlet|front.*)\"\n", "    \"front.*\"\n"));
    EXPECT_NE(missing.find("Cannot find patchField entry for inlet"), std::string::npos) << missing;
    EXPECT_NE(missing.find("0/pointDisplacement:"), std::string::npos) << missing;

    const std::string slip =
        error_for(edited_case("slip", "wall\n    {\n        type            fixedValue;",
                              "wall\n    {\n        type            slip;"));
    EXPECT_NE(slip.find("walls"), std::string::npos) << slip;
    EXPECT_NE(slip.find("unsupported"), std::string::npos) << slip;
    EXPECT_NE(slip.find("0/pointDisplacement:28:"), std::string::npos) << slip;

    const std::string size = error_for(edited_case("size", "9((0 0 0) (0 0 0) ", "8((0 0 0) "));
    EXPECT_NE(size.find("0/pointDisplacement:34:"), std::string::npos) << size;
    EXPECT_NE(size.find("9 points"), std::string::npos) << size;

    const std::string no_value = error_for(
        edited_case("no_value", "        value           uniform (0 0 0);\n    }\n    outlet",
                    "    }\n    outlet"));
    EXPECT_NE(no_value.find("walls"), std::string::npos) << no_value;
    EXPECT_NE(no_value.find("value"), std::string::npos) << no_value;

    const std::string internal =
        error_for(edited_case("internal", "internalField   uniform (0 0 0);",
                              "internalField   nonuniform List<vector> 2((0 0 0) (1 1 1));"));
    EXPECT_NE(internal.find("0/pointDisplacement:17:"), std::string::npos) << internal;
    EXPECT_NE(internal.find("36"), std::string::npos) << internal;

    const std::string klass = error_for(edited_case("class", "pointVectorField", "volVectorField"));
    EXPECT_NE(klass.find("wrong class"), std::string::npos) << klass;
}

TEST(PointField, conflicting_values_on_shared_points_are_reported)
{
    // Move the whole outlet: its edge points are shared with the walls and frontAndBack, which
    // prescribe zero, which OpenFOAM would resolve by evaluation order.
    const fs::path dir = edited_case("conflict",
                                     "nonuniform List<vector> 9((0 0 0) (0 0 0) (0.01 0 0) (0 0 0) "
                                     "(0 0 0) (0 0 0) (0 0 0) (0 0 0) (0 0 0))",
                                     "uniform (0.01 0 0)");
    const FoamPolyMesh m = read_poly_mesh(dir, {});
    const PointVectorField f = read_point_vector_field(dir, "0", "pointDisplacement", m.mesh);
    const std::string msg = test::error_of([&] { apply_patch_values(f, m.mesh); });
    EXPECT_NE(msg.find("outlet"), std::string::npos) << msg;
    EXPECT_NE(msg.find("different prescribed values"), std::string::npos) << msg;
}

TEST(PointField, empty_patches_default_to_empty_and_constraints_need_their_type)
{
    const PolyMesh mesh = test::make_block_mesh(
        2, 2, 1, [](double u, double v, double w) { return Vector3(u, v, 0.1 * w); },
        {"patch", "patch", "wall", "wall", "empty", "empty"});
    const fs::path case_dir = test::scratch_dir("pf_empty");
    write_poly_mesh(mesh, default_poly_mesh_files(FoamFormat::ascii), case_dir, "constant");
    const std::string head = "FoamFile { version 2.0; format ascii; class pointVectorField; "
                             "object pointDisplacement; }\ndimensions [0 1 0 0 0 0 0];\n"
                             "internalField uniform (0 0 0);\n";
    test::write_bytes(
        case_dir / "0/pointDisplacement",
        head + "boundaryField\n{\n    \".*\" { type fixedValue; value uniform (1 2 3); }\n}\n");
    const PointVectorField f = read_point_vector_field(case_dir, "0", "pointDisplacement", mesh);
    EXPECT_EQ(patch_field(f, "zMin").type, "empty");
    EXPECT_EQ(patch_field(f, "zMin").matched_by, PointPatchField::Match::empty_default);
    EXPECT_FALSE(patch_field(f, "zMax").is_prescribed());
    EXPECT_EQ(patch_field(f, "xMin").matched_by, PointPatchField::Match::regex);
    EXPECT_EQ(patch_field(f, "xMin").value->row(0), Eigen::RowVector3d(1, 2, 3));

    test::write_bytes(
        case_dir / "0/pointDisplacement",
        head + "boundaryField\n{\n    \".*\" { type fixedValue; value uniform (0 0 0); }\n"
               "    zMin { type fixedValue; value uniform (0 0 0); }\n}\n");
    const std::string msg =
        test::error_of([&] { read_point_vector_field(case_dir, "0", "pointDisplacement", mesh); });
    EXPECT_NE(msg.find("zMin"), std::string::npos) << msg;
    EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
}

TEST(PointField, every_spelling_of_an_empty_or_uniform_list_that_openfoam_writes_is_read)
{
    // A processor's part of a patch can hold no points: decomposePar then writes `value
    // nonuniform 0;` (binary) or `nonuniform List<vector> 0()` (ASCII). Both, and every
    // other spelling of an empty or uniform list, must read.
    PolyMesh mesh = test::make_block_mesh(
        2, 2, 1, [](double u, double v, double w) { return Vector3(u, v, 0.1 * w); },
        {"patch", "patch", "wall", "wall", "empty", "empty"});
    Patch nothing;
    nothing.name = "nothing";
    nothing.type = "patch";
    nothing.start_face = mesh.n_faces();
    mesh.patches.push_back(nothing);
    const fs::path case_dir = test::scratch_dir("pf_empty_lists");
    write_poly_mesh(mesh, default_poly_mesh_files(FoamFormat::ascii), case_dir, "constant");
    const std::size_t n_xmin = patch_points(mesh, mesh.patches[0]).size();
    const std::string n = std::to_string(n_xmin);
    const auto field =
        [&](const std::string& format, const std::string& xmin, const std::string& empty)
    {
        return "FoamFile { version 2.0; format " + format +
               "; class pointVectorField; object pointDisplacement; }\n"
               "dimensions [0 1 0 0 0 0 0];\ninternalField uniform (0 0 0);\n"
               "boundaryField\n{\n    \".*\" { type fixedValue; value uniform (0 0 0); }\n"
               "    xMin { type fixedValue; value " +
               xmin + "; }\n    nothing { type fixedValue; value " + empty + "; }\n}\n";
    };
    struct Spelling
    {
        std::string format, xmin, empty;
    };
    const std::vector<Spelling> spellings{
        {"binary", "uniform (1 2 3)", "nonuniform 0"},
        {"binary", "uniform (1 2 3)", "nonuniform List<vector> 0"},
        {"binary", "uniform (1 2 3)", "nonuniform List<vector> 0()"},
        {"ascii", "uniform (1 2 3)", "nonuniform List<vector> 0()"},
        {"ascii", "uniform (1 2 3)", "nonuniform List<vector> 0 ( )"},
        {"ascii", "uniform (1 2 3)", "nonuniform 0()"},
        {"ascii", "uniform (1 2 3)", "nonuniform ()"},
        {"ascii", "uniform (1 2 3)", "nonuniform 0"},
        {"ascii", "uniform (1 2 3)", "nonuniform List<vector> 0"},
        {"ascii", "uniform (1 2 3)", "uniform (1 2 3)"},
        {"ascii", "nonuniform List<vector> " + n + "{(1 2 3)}", "nonuniform 0{(1 2 3)}"},
        {"ascii", "nonuniform " + n + "{(1 2 3)}", "nonuniform List<vector> 0{(1 2 3)}"},
    };
    for (const Spelling& s : spellings)
    {
        const std::string what = s.format + ": xMin " + s.xmin + ", nothing " + s.empty;
        test::write_bytes(case_dir / "0/pointDisplacement", field(s.format, s.xmin, s.empty));
        try
        {
            const PointVectorField f =
                read_point_vector_field(case_dir, "0", "pointDisplacement", mesh);
            const PointPatchField& empty = patch_field(f, "nothing");
            ASSERT_TRUE(empty.value) << what;
            EXPECT_EQ(empty.value->rows(), 0) << what;
            const PointPatchField& xmin = patch_field(f, "xMin");
            ASSERT_TRUE(xmin.value) << what;
            ASSERT_EQ(xmin.value->rows(), static_cast<Eigen::Index>(n_xmin)) << what;
            for (Eigen::Index i = 0; i < xmin.value->rows(); ++i)
                EXPECT_EQ(xmin.value->row(i), Eigen::RowVector3d(1, 2, 3)) << what;
        }
        catch (const std::exception& e)
        {
            ADD_FAILURE() << what << ": " << e.what();
        }
    }
    // A size that does not match the patch is still an error naming the patch.
    test::write_bytes(case_dir / "0/pointDisplacement",
                      field("ascii", "nonuniform 0", "nonuniform 0"));
    const std::string msg =
        test::error_of([&] { read_point_vector_field(case_dir, "0", "pointDisplacement", mesh); });
    EXPECT_NE(msg.find("xMin"), std::string::npos) << msg;
}
