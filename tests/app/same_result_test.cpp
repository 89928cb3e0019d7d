// SPDX-License-Identifier: GPL-3.0-or-later
// The same morph writes the same points whatever the thread count: morphMesh run as a
// process with OMP_NUM_THREADS 1, 2 and 4 on the venturi squeeze (a surface projection
// with equidistant targets), the bent venturi's local repair (untangling) and a greedy RBF
// with its IDW correction; and whatever OpenBLAS kernel the processor picks. The
// release (-march=native) and ci (generic) builds are compared by
// benchmarks/morph/same_result.sh; docs/same-result.md says what is equal to what.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "helpers.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "process_run.h"
#include "venturi_case.h"

namespace meshmorph::app
{
namespace
{

namespace fs = std::filesystem;

//! morphMesh (the executable) on a copy of `source` with OMP_NUM_THREADS=threads (and the
//! `extra` environment, its name a suffix of the copy); the points it wrote (its JSON
//! report in <copy>/morph.json).
Points morph_with_threads(const fs::path& source, int threads, const std::string& extra = "")
{
    const fs::path dir = source.string() + "_threads" + std::to_string(threads) + extra;
    fs::remove_all(dir);
    fs::copy(source, dir, fs::copy_options::recursive);
    test::ProcessOptions options;
    options.environment = {"OMP_NUM_THREADS=" + std::to_string(threads)};
    if (!extra.empty())
        options.environment.push_back(extra);
    options.timeout_seconds = 600;
    const test::ProcessRun r = test::run_process(
        {MESHMORPH_MORPH_MESH_EXE, "-case", dir.string(), "-json", (dir / "morph.json").string()},
        options);
    EXPECT_EQ(r.status, 0) << r.out << r.err;
    return io::read_points_file(dir / "1/polyMesh/points");
}

nlohmann::json report_of(const fs::path& source, int threads)
{
    std::ifstream in(source.string() + "_threads" + std::to_string(threads) + "/morph.json");
    return nlohmann::json::parse(in);
}

//! Every thread count writes bit-identical points: the parallel loops write disjoint
//! points, and no reduction's order depends on the threads.
void expect_same_points_for_every_thread_count(const fs::path& source)
{
    const Points one = morph_with_threads(source, 1);
    ASSERT_GT(one.rows(), 0);
    for (const int threads : {2, 4})
    {
        const Points other = morph_with_threads(source, threads);
        ASSERT_EQ(other.rows(), one.rows());
        EXPECT_EQ((other - one).cwiseAbs().maxCoeff(), 0.0)
            << threads << " threads against 1 on " << source;
    }
}

//! OpenBLAS kernels every x86-64 processor since 2013 runs (OpenBLAS picks one by processor;
//! OPENBLAS_CORETYPE forces it): SSE3, SSE4.2, AVX and AVX2 with FMA.
const std::vector<std::string> openblas_kernels = {"Prescott", "Nehalem", "SandyBridge", "Haswell"};

//! What a run of morphMesh decided and wrote, for comparing runs.
struct MorphOutcome
{
    int status = -1;
    nlohmann::json steps;
    Points points; //!< empty when nothing was written
};

//! The steps of a -json report without their times (which differ from run to run).
nlohmann::json without_times(nlohmann::json steps)
{
    for (nlohmann::json& step : steps)
    {
        for (const char* time : {"fit", "evaluate", "check", "write"})
            step.erase(time);
        for (const char* repair : {"untangle", "nonOrthRepair"})
            if (step.contains(repair))
                step[repair].erase("seconds");
    }
    return steps;
}

//! morphMesh on a copy of `source` under OPENBLAS_CORETYPE=kernel.
MorphOutcome morph_with_kernel(const fs::path& source, const std::string& kernel)
{
    const fs::path dir = source.string() + "_" + kernel;
    fs::remove_all(dir);
    fs::copy(source, dir, fs::copy_options::recursive);
    test::ProcessOptions options;
    options.environment = {"OMP_NUM_THREADS=2", "OPENBLAS_CORETYPE=" + kernel};
    options.timeout_seconds = 600;
    const test::ProcessRun r = test::run_process(
        {MESHMORPH_MORPH_MESH_EXE, "-case", dir.string(), "-json", (dir / "morph.json").string()},
        options);
    MorphOutcome outcome;
    outcome.status = r.status;
    std::ifstream json(dir / "morph.json");
    outcome.steps = without_times(nlohmann::json::parse(json)["steps"]);
    if (fs::exists(dir / "1/polyMesh/points"))
        outcome.points = io::read_points_file(dir / "1/polyMesh/points");
    return outcome;
}

//! Every kernel decides the same steps and repairs, with the same counts, and writes
//! bit-identical points (or none). Returns the first kernel's outcome.
MorphOutcome expect_the_same_outcome_under_every_kernel(const fs::path& source)
{
    const MorphOutcome first = morph_with_kernel(source, openblas_kernels.front());
    for (std::size_t k = 1; k < openblas_kernels.size(); ++k)
    {
        const MorphOutcome other = morph_with_kernel(source, openblas_kernels[k]);
        const std::string which = openblas_kernels[k] + " against " + openblas_kernels.front();
        EXPECT_EQ(other.status, first.status) << which;
        EXPECT_EQ(other.steps, first.steps) << which;
        EXPECT_EQ(other.points.rows(), first.points.rows()) << which;
        if (first.points.rows() > 0 && other.points.rows() == first.points.rows())
        {
            EXPECT_EQ((other.points - first.points).cwiseAbs().maxCoeff(), 0.0) << which;
        }
    }
    return first;
}

} // namespace

TEST(SameResult, venturi_squeeze_writes_the_same_points_with_1_2_and_4_threads)
{
    // Wall points on the venturi's plane of symmetry are equally near both slopes.
    expect_same_points_for_every_thread_count(test::venturi_case("same_venturi", 0.8, ""));
}

TEST(SameResult, untangling_writes_the_same_points_with_1_2_and_4_threads)
{
    // The bent venturi in one step: the local repair moves interior points (checked, so that
    // the test covers it), an iterative optimisation over threads. Offset 0.8: a repair that
    // is not borderline (see repairable_venturi_case in morph_steps_test.cpp).
    const fs::path source = test::venturi_case("same_untangle", 0.8, "steps 1;\n", "rbf", 0.8);
    expect_same_points_for_every_thread_count(source);
    EXPECT_GT(report_of(source, 1)["steps"][0]["untangle"]["pointsMoved"].get<int>(), 0);
}

TEST(SameResult, greedy_rbf_with_idw_correction_writes_the_same_points_with_1_2_and_4_threads)
{
    // A symmetric mesh: residuals and farthest points tie in exact arithmetic.
    expect_same_points_for_every_thread_count(
        test::venturi_case("same_greedy", 0.3, "rbf { greedy { tolerance 1e-2; } }\n"));
}

TEST(SameResult, the_points_do_not_depend_on_how_the_process_gets_its_memory)
{
    // With MESHMORPH_HUGE_PAGES=1 morphMesh runs itself again with glibc's huge-page
    // tunable (app/process_memory.h); by default it keeps the first process. The arguments
    // must survive the re-execution, and the points must not change.
    const fs::path source =
        test::venturi_case("same_memory", 0.3, "rbf { greedy { tolerance 1e-2; } }\n");
    const Points plain = morph_with_threads(source, 2);
    const Points huge = morph_with_threads(source, 2, "MESHMORPH_HUGE_PAGES=1");
    ASSERT_GT(plain.rows(), 0);
    ASSERT_EQ(huge.rows(), plain.rows());
    EXPECT_EQ((huge - plain).cwiseAbs().maxCoeff(), 0.0);
}

TEST(SameResult, the_verdict_and_the_points_do_not_depend_on_the_openblas_kernel)
{
    // The bent venturi at offset 1.0 in one step: the fit, then the local repair of the
    // cells it folds (checked to run). While the fits ran on OpenBLAS, the points differed
    // by up to 9e-11 between these kernels, and the repair, a hill-climb, follows its input
    // (at an earlier commit it succeeded under 9 of 13 kernels). The fits now use no BLAS
    // (deform/dense_kernels.h): every kernel gives one outcome, bit for bit.
    const fs::path source = test::venturi_case("same_kernel", 0.8, "steps 1;\n", "rbf", 1.0);
    const MorphOutcome outcome = expect_the_same_outcome_under_every_kernel(source);
    EXPECT_GT(outcome.steps[0]["untangle"]["pointsMoved"].get<int>(), 0)
        << "the premise: the repair runs";
}

TEST(SameResult, greedy_rbf_with_idw_correction_does_not_depend_on_the_openblas_kernel)
{
    // The greedy fit's factor grows by triangular solves and Cholesky factors of Schur
    // complements at a condition number near 1e9; its centres follow its residuals.
    expect_the_same_outcome_under_every_kernel(
        test::venturi_case("same_kernel_greedy", 0.3, "rbf { greedy { tolerance 1e-2; } }\n"));
}

} // namespace meshmorph::app
