// SPDX-License-Identifier: GPL-3.0-or-later
// The catalogue of bad cases of issue 12 (docs/bad-input.md lists each with its test): both
// applications run as processes on a small real case with one thing wrong. Each must exit
// non-zero with an "Error: " naming the file (and line) or the dictionary entry, and leave
// the case byte-identical; a broken but readable mesh is reported by checkMeshQuality as
// checkMesh does (failed checks, exit 1).
#include <gtest/gtest.h>

#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>

#include "fault_case.h"
#include "meshmorph/app/exit_status.h"
#include "meshmorph/io/write_poly_mesh.h"

namespace fs = std::filesystem;
using namespace meshmorph;
using test::App;

namespace
{

const std::vector<App> both_apps{App::morph_mesh, App::check_mesh_quality};

fs::path mesh_file(const fs::path& dir, const std::string& name)
{
    return dir / "constant/polyMesh" / name;
}

//! Replaces the first `from` in a mesh file with `to`; returns the line of the change.
int edit_mesh_file(const fs::path& dir, const std::string& name, const std::string& from,
                   const std::string& to)
{
    std::string text = test::read_file(mesh_file(dir, name));
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from << " not in " << name;
    const int line = test::line_of(text, from);
    text.replace(at, from.size(), to);
    test::write_file(mesh_file(dir, name), text);
    return line;
}

//! A generated box case (for geometric defects), ascii, with the base morphDict.
fs::path make_box_case(const std::string& name, const PolyMesh& mesh)
{
    const fs::path dir = test::scratch_dir("faults/" + name);
    io::write_poly_mesh(mesh, io::default_poly_mesh_files(io::FoamFormat::ascii), dir, "constant");
    test::write_file(dir / "system/controlDict",
                     "FoamFile { version 2.0; format ascii; class dictionary; object "
                     "controlDict; }\ndeltaT 1;\nwritePrecision 12;\n");
    test::write_morph_dict(dir, "method rbf;\nconflicts last;\n"
                                "boundary { zMax { type translate; vector (0 0 0.01); } }\n");
    return dir;
}

} // namespace

TEST(BadInput, the_base_case_is_accepted_by_both_applications)
{
    const fs::path dir = test::make_fault_case("base");
    const test::ProcessRun check = test::run_app(App::check_mesh_quality, dir);
    EXPECT_EQ(check.status, app::exit_ok) << check.out << check.err;
    EXPECT_NE(check.out.find("Mesh OK."), std::string::npos) << check.out;
    const test::ProcessRun morph = test::run_app(App::morph_mesh, dir);
    EXPECT_EQ(morph.status, app::exit_ok) << morph.out << morph.err;
    EXPECT_TRUE(fs::exists(dir / "1/polyMesh/points"));
}

TEST(BadInput, missing_files_are_named)
{
    for (const std::string name : {"points", "faces", "owner", "neighbour", "boundary"})
    {
        const fs::path dir = test::make_fault_case("missing_" + name);
        fs::remove(mesh_file(dir, name));
        for (App app : both_apps)
            test::expect_rejected(app, dir, app::exit_input_error,
                                  {(dir / "constant/polyMesh").string(), name});
    }
    const fs::path dir = test::make_fault_case("missing_dict");
    fs::remove(dir / "system/morphDict");
    test::expect_rejected(App::morph_mesh, dir, app::exit_input_error,
                          {(dir / "system/morphDict").string()});
    for (App app : both_apps)
    {
        const test::ProcessRun r = test::run_app(app, dir / "nothere");
        EXPECT_EQ(r.status, app::exit_input_error) << r.err;
        EXPECT_NE(r.err.find((dir / "nothere").string()), std::string::npos) << r.err;
        EXPECT_FALSE(fs::exists(dir / "nothere"));
    }
}

// The committed malformed fixtures (tests/data/io/malformed, the reader's unit tests), each
// dropped into the case: truncated, garbage, binary-as-ascii, counts, labels, short faces,
// boundary gaps.
struct Fixture
{
    const char* name;  // directory under tests/data/io/malformed
    const char* file;  // the mesh file it replaces
    const char* base;  // curved_block variant
    const char* where; // "file:line" (or file name) the message must hold
};

class BadMeshFile : public testing::TestWithParam<Fixture>
{
};

TEST_P(BadMeshFile, both_applications_name_file_and_line_and_change_nothing)
{
    const Fixture& f = GetParam();
    const fs::path dir = test::make_fault_case(std::string("fixture_") + f.name, f.base);
    fs::copy_file(test::data_path(std::string("io/malformed/") + f.name + "/" + f.file),
                  mesh_file(dir, f.file), fs::copy_options::overwrite_existing);
    for (App app : both_apps)
        test::expect_rejected(app, dir, app::exit_input_error,
                              {"constant/polyMesh/" + std::string(f.where)});
}

INSTANTIATE_TEST_SUITE_P(
    Catalogue, BadMeshFile,
    testing::Values(Fixture{"truncated_faces", "faces", "ascii", "faces:19:"},
                    Fixture{"points_truncated_binary", "points", "binary", "points:"},
                    Fixture{"faces_garbage", "faces", "ascii", "faces:"},
                    Fixture{"points_ascii_under_binary", "points", "ascii", "points:"},
                    Fixture{"owner_count_mismatch", "owner", "ascii", "owner:73:"},
                    Fixture{"neighbour_too_long", "neighbour", "ascii", "neighbour:"},
                    Fixture{"owner_huge_count", "owner", "ascii", "owner:20:"},
                    Fixture{"face_label_out_of_range", "faces", "ascii", "faces:30:"},
                    Fixture{"faces_binary_label_out_of_range", "faces", "binary", "faces:"},
                    Fixture{"owner_negative", "owner", "ascii", "owner:25:"},
                    Fixture{"neighbour_not_upper", "neighbour", "ascii", "neighbour:22:"},
                    Fixture{"face_too_few_vertices", "faces", "ascii", "faces:25:"},
                    Fixture{"boundary_gap", "boundary", "ascii", "boundary:26:"}),
    [](const testing::TestParamInfo<Fixture>& p) { return std::string(p.param.name); });

TEST(BadInput, truncated_and_garbage_points_are_named)
{
    const fs::path cut = test::make_fault_case("truncated_points");
    const std::string text = test::read_file(mesh_file(cut, "points"));
    test::write_file(mesh_file(cut, "points"), text.substr(0, text.size() / 2));
    for (App app : both_apps)
        test::expect_rejected(app, cut, app::exit_input_error, {"constant/polyMesh/points:"});

    const fs::path garbage = test::make_fault_case("garbage_points");
    std::mt19937 rng(12);
    std::string bytes(text.size(), '\0');
    for (char& c : bytes)
        c = static_cast<char>(rng() & 0xff);
    test::write_file(mesh_file(garbage, "points"), bytes);
    for (App app : both_apps)
        test::expect_rejected(app, garbage, app::exit_input_error, {"constant/polyMesh/points"});
}

TEST(BadInput, binary_data_under_an_ascii_header_is_named)
{
    const fs::path dir = test::make_fault_case("binary_as_ascii", "binary");
    edit_mesh_file(dir, "points", "format      binary;", "format      ascii;");
    for (App app : both_apps)
        test::expect_rejected(app, dir, app::exit_input_error, {"constant/polyMesh/points:"});
}

TEST(BadInput, nan_and_inf_coordinates_are_named_with_their_line)
{
    for (const std::string bad : {"nan", "inf", "-Inf"})
    {
        const fs::path dir = test::make_fault_case("non_finite_" + bad);
        const int line = edit_mesh_file(dir, "points", "(0.2 0 0)", "(0.2 " + bad + " 0)");
        for (App app : both_apps)
            test::expect_rejected(
                app, dir, app::exit_input_error,
                {"constant/polyMesh/points:" + std::to_string(line) + ":", "non-finite"});
    }
}

TEST(BadInput, boundary_patches_that_overlap_or_leave_faces_out_are_named)
{
    const fs::path overlap = test::make_fault_case("boundary_overlap");
    const int line =
        edit_mesh_file(overlap, "boundary", "startFace       24;", "startFace       22;");
    (void)line;
    for (App app : both_apps)
        test::expect_rejected(app, overlap, app::exit_input_error,
                              {"constant/polyMesh/boundary:", "outlet", "startFace 22"});
    const fs::path short_end = test::make_fault_case("boundary_short");
    edit_mesh_file(short_end, "boundary", "nFaces          12;\n        startFace       40;",
                   "nFaces          10;\n        startFace       40;");
    for (App app : both_apps)
        test::expect_rejected(app, short_end, app::exit_input_error,
                              {"constant/polyMesh/boundary:", "not in any patch"});
}

TEST(BadInput, morph_dict_errors_name_file_line_and_entry)
{
    struct Case
    {
        const char* name;
        const char* body;
        std::vector<std::string> needles;
    };
    const std::vector<Case> cases{
        {"unknown_key", "method rbf;\nstepz 2;\nboundary {}\n", {"morphDict:3:", "stepz"}},
        {"unknown_type",
         "boundary\n{\n    outlet { type glide; }\n}\n",
         {"morphDict:4:", "glide", "outlet"}},
        {"wrong_value_type", "steps many;\nboundary {}\n", {"morphDict:2:", "steps"}},
        {"unknown_method", "method spline;\n", {"morphDict:2:", "spline"}},
        {"unknown_patch", "boundary\n{\n    wing { type fixed; }\n}\n", {"morphDict:", "wing"}},
        {"syntax_error", "boundary\n{\n    outlet { type fixed;\n", {"morphDict:"}},
    };
    for (const Case& c : cases)
    {
        const fs::path dir = test::make_fault_case(std::string("dict_") + c.name, "ascii", c.body);
        std::vector<std::string> needles = c.needles;
        needles[0] = (dir / "system").string() + "/" + needles[0];
        test::expect_rejected(App::morph_mesh, dir, app::exit_input_error, needles);
    }
}

TEST(BadInput, conflicting_constraints_with_rule_error_name_the_patches)
{
    const fs::path dir = test::make_fault_case(
        "conflicts", "ascii",
        "conflicts error;\nboundary\n{\n    outlet { type translate; vector (0.01 0 0); }\n"
        "    walls { type translate; vector (0 0.01 0); }\n}\n");
    test::expect_rejected(App::morph_mesh, dir, app::exit_input_error,
                          {"outlet", "walls", "conflicts"});
}

TEST(BadInput, a_target_surface_that_is_missing_or_empty_is_named)
{
    const std::string dict = "conflicts last;\nboundary\n{\n    outlet { type surface; file "
                             "\"constant/triSurface/target.stl\"; }\n}\n";
    const fs::path missing = test::make_fault_case("surface_missing", "ascii", dict);
    test::expect_rejected(App::morph_mesh, missing, app::exit_input_error,
                          {"constant/triSurface/target.stl", "outlet"});
    for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
             {"empty_file", ""}, {"no_facets", "solid target\nendsolid target\n"}})
    {
        const fs::path dir = test::make_fault_case("surface_" + name, "ascii", dict);
        test::write_file(dir / "constant/triSurface/target.stl", text);
        test::expect_rejected(App::morph_mesh, dir, app::exit_input_error,
                              {"constant/triSurface/target.stl"});
    }
}

TEST(BadInput, a_target_surface_far_from_its_patch_is_a_warning_naming_it)
{
    // The outlet (x = 0.2, 0.1 across) projected onto the plane x = 50. A large motion may
    // be meant, so the morph goes on (and writes), but a warning names the entry and file.
    const fs::path dir =
        test::make_fault_case("surface_far", "ascii",
                              "conflicts last;\nboundary\n{\n    outlet { type surface; file "
                              "\"constant/triSurface/far.stl\"; }\n}\n");
    test::write_file(dir / "constant/triSurface/far.stl",
                     "solid far\n facet normal 1 0 0\n  outer loop\n   vertex 50 -9 -9\n"
                     "   vertex 50 9 -9\n   vertex 50 0 9\n  endloop\n endfacet\nendsolid far\n");
    const test::TreeSnapshot before = test::snapshot_tree(dir / "constant");
    const test::ProcessRun r = test::run_app(App::morph_mesh, dir, {"-force"});
    EXPECT_EQ(r.status, app::exit_ok) << r.err;
    EXPECT_NE(r.err.find("Warning: " + (dir / "system/morphDict").string() +
                         ":5: boundary entry outlet: the surface \"constant/triSurface/far.stl\" "
                         "is far from its points"),
              std::string::npos)
        << r.err;
    EXPECT_EQ(test::tree_diff(before, test::snapshot_tree(dir / "constant")), "");
}

TEST(BadInput, a_lattice_below_4_per_axis_is_named)
{
    const fs::path ffd = test::make_fault_case("lattice_ffd", "ascii",
                                               "method ffd;\nffd\n{\n    lattice (3 4 4);\n    "
                                               "displacements ( ((1 1 1) (0 0 0.01)) );\n}\n");
    test::expect_rejected(App::morph_mesh, ffd, app::exit_input_error,
                          {"morphDict:5:", "lattice", "at least 4"});
    const fs::path dmffd =
        test::make_fault_case("lattice_dmffd", "ascii",
                              std::string(test::base_morph_dict) + "dmffd { lattice (4 4 2); }\n");
    test::expect_rejected(App::morph_mesh, dmffd, app::exit_input_error,
                          {"morphDict:8:", "lattice", "at least 4"}, {"-method", "dmffd"});
}

TEST(BadInput, a_deformation_that_inverts_cells_is_refused)
{
    // The outlet (x = 0.2) pushed past the inlet (x = 0).
    const fs::path dir = test::make_fault_case("inverts", "ascii",
                                               "conflicts last;\nsteps 1;\nboundary\n{\n    outlet "
                                               "{ type translate; vector (-0.5 0 0); }\n}\n");
    test::expect_rejected(App::morph_mesh, dir, app::exit_refused, {"negative-volume", "-force"});
}

// checkMesh's behaviour on a readable but broken mesh: the failed checks, exit 1. morphMesh
// reads it, morphs it and writes the result: what is broken stays broken (it refuses only
// new invalid cells), and it says so in a warning.
TEST(BadInput, open_cells_are_failed_checks_not_errors)
{
    const fs::path dir = test::make_fault_case("open_cells");
    // Reverse one inlet face: its cell no longer closes, nor does the boundary.
    edit_mesh_file(dir, "faces", "4(0 12 16 4)", "4(0 4 16 12)");
    const test::TreeSnapshot before = test::snapshot_tree(dir);
    const test::ProcessRun r = test::run_app(App::check_mesh_quality, dir);
    EXPECT_EQ(r.status, app::exit_checks_failed) << r.out << r.err;
    EXPECT_NE(r.out.find("***Open cells found"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("Failed "), std::string::npos) << r.out;
    EXPECT_EQ(test::tree_diff(before, test::snapshot_tree(dir)), "");

    // morphMesh morphs it (the outlet moves a little) and warns that the defects remain.
    const test::ProcessRun m = test::run_app(App::morph_mesh, dir);
    EXPECT_EQ(m.status, app::exit_ok) << m.err;
    EXPECT_NE(m.err.find("Warning: the mesh in " + (dir / "constant/polyMesh").string() +
                         " fails 3 mesh checks before the morph"),
              std::string::npos)
        << m.err;
    EXPECT_EQ(test::tree_diff(before, test::snapshot_tree(dir)),
              "added 1 (dir)\nadded 1/polyMesh (dir)\nadded 1/polyMesh/points (" +
                  test::fnv1a_64(dir / "1/polyMesh/points") + ")\n");
}

TEST(BadInput, zero_area_faces_and_duplicate_points_are_failed_checks)
{
    // The top layer of a 2 x 2 x 2 box flattened onto the middle one: its side faces have
    // zero area, its cells zero volume, and each top point duplicates a middle one.
    PolyMesh mesh = test::make_box_mesh(2, 2, 2);
    for (Index p = 0; p < mesh.n_points(); ++p)
        if (mesh.points(p, 2) == 1.0)
            mesh.points(p, 2) = 0.5;
    const fs::path dir = make_box_case("flattened", mesh);
    const test::TreeSnapshot before = test::snapshot_tree(dir);
    const test::ProcessRun r =
        test::run_app(App::check_mesh_quality, dir, {"-allGeometry", "-allTopology"});
    EXPECT_EQ(r.status, app::exit_checks_failed) << r.out << r.err;
    EXPECT_NE(r.out.find("***Zero or negative face area detected"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("***Zero or negative cell volume detected"), std::string::npos) << r.out;
    EXPECT_EQ(test::tree_diff(before, test::snapshot_tree(dir)), "");

    // morphMesh: the lifted top and the fixed middle share positions, which no deformation
    // can honour; the error names the points file and the duplicate points' labels.
    test::expect_rejected(
        App::morph_mesh, dir, app::exit_input_error,
        {(dir / "constant/polyMesh/points").string() + ": points ", "are duplicates at"});
}

namespace
{

//! A tmpfs at `dir` for one test (needs root or CAP_SYS_ADMIN); unmounted at the end.
class TmpfsMount
{
public:
    TmpfsMount(const fs::path& dir, const std::string& options) : dir_(dir)
    {
        fs::create_directories(dir);
        mounted_ = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) == 0;
        why_ = mounted_ ? "" : std::strerror(errno);
    }
    TmpfsMount(const TmpfsMount&) = delete;
    TmpfsMount& operator=(const TmpfsMount&) = delete;
    ~TmpfsMount()
    {
        if (mounted_)
            ::umount2(dir_.c_str(), MNT_DETACH);
    }
    bool mounted() const { return mounted_; }
    const std::string& why_not() const { return why_; }
    bool remount_read_only() const
    {
        return ::mount(nullptr, dir_.c_str(), nullptr, MS_REMOUNT | MS_RDONLY, nullptr) == 0;
    }

private:
    fs::path dir_;
    bool mounted_ = false;
    std::string why_;
};

} // namespace

TEST(BadInput, a_read_only_case_is_checked_but_not_written)
{
    const fs::path mount_point = test::scratch_dir("faults/read_only_mount");
    const TmpfsMount tmpfs(mount_point, "size=4m");
    if (!tmpfs.mounted())
        GTEST_SKIP() << "cannot mount a tmpfs to make a read-only file system (" << tmpfs.why_not()
                     << "; needs root): as root, file permissions would not stop the writes";
    const fs::path dir = mount_point / "case";
    fs::copy(test::make_fault_case("read_only_source"), dir, fs::copy_options::recursive);
    ASSERT_TRUE(tmpfs.remount_read_only()) << std::strerror(errno);
    test::expect_rejected(App::morph_mesh, dir, app::exit_input_error,
                          {(dir / "1/polyMesh").string(), "Read-only file system"});
    test::expect_rejected(
        App::morph_mesh, dir, app::exit_input_error,
        {(dir / "constant/polyMesh/points.orig").string(), "Read-only file system"},
        {"-overwrite"});
    // checkMeshQuality only reads, unless asked to write into the case.
    const test::ProcessRun check = test::run_app(App::check_mesh_quality, dir);
    EXPECT_EQ(check.status, app::exit_ok) << check.err;
    test::expect_rejected(App::check_mesh_quality, dir, app::exit_input_error,
                          {(dir / "VTK").string(), "Read-only file system"}, {"-vtk"});
}

TEST(BadInput, a_full_disk_leaves_the_case_as_it_was)
{
    const fs::path mount_point = test::scratch_dir("faults/full_disk_mount");
    const TmpfsMount tmpfs(mount_point, "size=512k");
    if (!tmpfs.mounted())
        GTEST_SKIP() << "cannot mount a small tmpfs to fill (" << tmpfs.why_not()
                     << "; needs root)";
    const fs::path dir = mount_point / "case";
    fs::copy(test::make_fault_case("full_disk_source"), dir, fs::copy_options::recursive);
    { // fill what is left
        std::ofstream filler(mount_point / "filler", std::ios::binary);
        const std::string block(4096, 'x');
        while (filler.write(block.data(), block.size()))
            filler.flush();
    }
    test::expect_rejected(App::morph_mesh, dir, app::exit_input_error,
                          {(dir / "1/polyMesh/points").string(), "No space left on device"});
    test::expect_rejected(
        App::morph_mesh, dir, app::exit_input_error,
        {(dir / "constant/polyMesh/points.orig").string(), "No space left on device"},
        {"-overwrite"});
}
