// SPDX-License-Identifier: GPL-3.0-or-later
// Deformation benchmarks: dgemm reference rate, RBF fit (GFLOP/s of the m^3/3 Cholesky) and
// evaluation (kernel evaluations / s), FFD evaluation, greedy fit. The paper's Fig. 6 set-up
// (427 constraints, 8^3 lattice, handle basis, serial and OpenMP) is benchPaper's
// performance section (benchmarks/paper/performance.cpp, run by deformationBenchmarks).
//
// Usage: deform_benchmarks [--benchmark_filter=<regex>]
#include <benchmark/benchmark.h>

#include <omp.h>

#include <time.h>

#include <cmath>
#include <random>

#include "meshmorph/deform/ffd_deformation.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n,
                       const int* k, const double* alpha, const double* a, const int* lda,
                       const double* b, const int* ldb, const double* beta, double* c,
                       const int* ldc);

namespace
{
using meshmorph::Points;

//! CPU seconds of the whole process (all threads). Rates per CPU-second show the per-core
//! throughput even when other jobs share the cores (spin-waiting threads count as busy, so
//! these rates are conservative).
double process_cpu_seconds()
{
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

Points random_points(Eigen::Index n, unsigned seed)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Points p(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            p(i, c) = u(gen);
    return p;
}

Points field(const Points& x)
{
    Points d(x.rows(), 3);
    for (Eigen::Index i = 0; i < x.rows(); ++i)
        d.row(i) = Eigen::RowVector3d(0.1 * std::sin(2 * x(i, 0) + x(i, 1)),
                                      0.05 * std::cos(3 * x(i, 1)) * x(i, 2),
                                      0.08 * std::exp(-x(i, 0) * x(i, 0)));
    return d;
}

void BM_dgemm(benchmark::State& state)
{
    const int n = static_cast<int>(state.range(0));
    const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n), b = Eigen::MatrixXd::Random(n, n);
    Eigen::MatrixXd c(n, n);
    const double one = 1.0, zero = 0.0;
    const double c0 = process_cpu_seconds();
    for (auto _ : state)
    {
        dgemm_("N", "N", &n, &n, &n, &one, a.data(), &n, b.data(), &n, &zero, c.data(), &n);
        benchmark::DoNotOptimize(c.data());
    }
    const double cpu = process_cpu_seconds() - c0;
    state.counters["GFLOP/s"] = benchmark::Counter(2.0 * n * double(n) * n * 1e-9,
                                                   benchmark::Counter::kIsIterationInvariantRate);
    state.counters["GFLOP/cpu-s"] =
        2.0 * n * double(n) * n * 1e-9 * double(state.iterations()) / cpu;
}
BENCHMARK(BM_dgemm)->Arg(2000)->Arg(4000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_rbf_fit(benchmark::State& state)
{
    const Eigen::Index m = state.range(0);
    const Points h = random_points(m, 1);
    const Points d = field(h);
    double cond = 0.0;
    const double c0 = process_cpu_seconds();
    for (auto _ : state)
    {
        meshmorph::RbfDeformation rbf;
        rbf.fit(h, d);
        cond = rbf.report().condition_estimate;
    }
    // Rate of the dominant m^3/3 Cholesky flops over the whole fit (assembly, QR, residual).
    state.counters["GFLOP/s"] = benchmark::Counter(double(m) * m * m / 3.0 * 1e-9,
                                                   benchmark::Counter::kIsIterationInvariantRate);
    state.counters["GFLOP/cpu-s"] =
        double(m) * m * m / 3.0 * 1e-9 * double(state.iterations()) / (process_cpu_seconds() - c0);
    state.counters["cond"] = cond;
}
BENCHMARK(BM_rbf_fit)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->Arg(4000)
    ->Arg(8000)
    ->Arg(16000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

void BM_rbf_evaluate(benchmark::State& state)
{
    const Eigen::Index m = state.range(0), n = state.range(1);
    const int threads = static_cast<int>(state.range(2));
    const Points h = random_points(m, 1);
    meshmorph::RbfDeformation rbf;
    rbf.fit(h, field(h));
    const Points x = random_points(n, 2);
    Points out(n, 3);
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    const double c0 = process_cpu_seconds();
    for (auto _ : state)
    {
        rbf.evaluate(x, out);
        benchmark::DoNotOptimize(out.data());
    }
    const double cpu = process_cpu_seconds() - c0;
    omp_set_num_threads(saved);
    // Per CPU-second times threads: the rate if each thread had a core to itself.
    state.counters["Geval/cpu-s*threads"] =
        double(m) * double(n) * 1e-9 * double(state.iterations()) / cpu * threads;
    state.counters["Geval/s"] = benchmark::Counter(double(m) * double(n) * 1e-9,
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_rbf_evaluate)
    ->Args({500, 1000000, 1})
    ->Args({500, 1000000, 2})
    ->Args({2000, 100000, 1})
    ->Args({2000, 100000, 2})
    ->Args({4000, 1000000, 2})
    ->Args({16000, 100000, 1})
    ->Args({16000, 100000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

//! FFD evaluation on 1e6 points, axis-aligned (direct local coordinates) vs a parallelepiped
//! (Newton). range(0): 0 axis-aligned, 1 skewed; range(1): threads.
void BM_ffd_evaluate(benchmark::State& state)
{
    meshmorph::FfdBox box;
    if (state.range(0) == 1)
        box.axes.col(0) = Eigen::Vector3d(1.0, 0.2, 0.0);
    const meshmorph::FfdLattice lattice(box, {10, 10, 10});
    meshmorph::FfdDeformation ffd(lattice, meshmorph::FfdOutside::clamp);
    ffd.set_control_displacements(field(lattice.control_points()));
    const Points x = random_points(1000000, 7);
    Points out(x.rows(), 3);
    const int saved = omp_get_max_threads();
    omp_set_num_threads(static_cast<int>(state.range(1)));
    for (auto _ : state)
    {
        ffd.evaluate(x, out);
        benchmark::DoNotOptimize(out.data());
    }
    omp_set_num_threads(saved);
    state.counters["Mpoints/s"] =
        benchmark::Counter(double(x.rows()) * 1e-6, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ffd_evaluate)
    ->ArgsProduct({{0, 1}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

//! Greedy refinement on 20000 sphere points (tolerance 1e-2 / 1e-3 of the max displacement).
void BM_greedy_fit(benchmark::State& state)
{
    const Eigen::Index n = 20000;
    Points x(n, 3);
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (Eigen::Index i = 0; i < n; ++i)
    {
        const double z = 1.0 - 2.0 * (double(i) + 0.5) / double(n);
        const double r = std::sqrt(1.0 - z * z);
        x.row(i) = Eigen::RowVector3d(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    const Points d = field(x);
    meshmorph::GreedySettings s;
    s.tolerance = 1e-2;
    s.rms_tolerance = 1e-3;
    meshmorph::Index centres = 0;
    for (auto _ : state)
    {
        meshmorph::GreedyRbfDeformation g(s);
        g.fit(x, d);
        centres = g.report().num_centres;
    }
    state.counters["centres"] = double(centres);
}
BENCHMARK(BM_greedy_fit)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

} // namespace

BENCHMARK_MAIN();
