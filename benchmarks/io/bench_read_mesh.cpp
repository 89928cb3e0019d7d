// SPDX-License-Identifier: GPL-3.0-or-later
// benchReadMesh: polyMesh read throughput and peak memory, against OpenFOAM's checkMesh.
//
// Usage: benchReadMesh [-repeat N] [-serial] [-write DIR] [-noCheckMesh] <case>
//
// Reads <case>'s polyMesh N times (default 3) and prints, for the best run, the bytes read
// (decompressed), the time and MB/s, per-file sizes, the in-memory mesh size and the peak
// resident set size (getrusage). Peak RSS is per process, so run one case per invocation.
// With -write, also times writing the mesh back (same formats) into DIR. If OpenFOAM's
// checkMesh is on PATH, times `checkMesh -case <case> -constant` (which reads the same
// mesh and then checks it) for comparison.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <string>

#include <omp.h>
#include <sys/resource.h>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/read_poly_mesh.h"
#include "meshmorph/io/write_poly_mesh.h"

namespace fs = std::filesystem;
using namespace meshmorph;

namespace
{

double now()
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

// Process CPU time (all threads): on a machine shared with other jobs, wall time measures
// the load as much as the reader; CPU time is what the read costs.
double cpu_now()
{
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double peak_rss_mb()
{
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0; // ru_maxrss is in KiB on Linux
}

double load_average()
{
    double load = 0;
    return ::getloadavg(&load, 1) == 1 ? load : -1.0;
}

double mesh_mb(const PolyMesh& m)
{
    const double bytes = static_cast<double>(m.points.size()) * sizeof(double) +
                         static_cast<double>(m.faces.offsets.size() + m.faces.values.size() +
                                             m.owner.size() + m.neighbour.size()) *
                             sizeof(Index);
    return bytes / 1e6;
}

std::string describe(const io::FoamFileInfo& f)
{
    return std::string(f.header.is_binary() ? "binary" : "ascii") + (f.is_compressed ? "+gz" : "") +
           " " + std::to_string(f.bytes / 1000000.0).substr(0, 6) + " MB";
}

} // namespace

int main(int argc, char** argv)
{
    int repeat = 3;
    bool serial = false;
    bool run_check_mesh = true;
    fs::path write_dir;
    fs::path case_dir;
    for (int i = 1; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (a == "-repeat" && i + 1 < argc)
            repeat = std::max(1, std::atoi(argv[++i]));
        else if (a == "-serial")
            serial = true;
        else if (a == "-noCheckMesh")
            run_check_mesh = false;
        else if (a == "-write" && i + 1 < argc)
            write_dir = argv[++i];
        else if (a == "-help" || a == "--help" || (!a.empty() && a[0] == '-'))
        {
            std::cout << "Usage: benchReadMesh [-repeat N] [-serial] [-write DIR] [-noCheckMesh] "
                         "<case>\n";
            return a == "-help" || a == "--help" ? 0 : 2;
        }
        else
            case_dir = a;
    }
    if (case_dir.empty())
    {
        std::cerr << "Error: no case given (benchReadMesh -help)\n";
        return 2;
    }
    try
    {
        std::cout << "Case      : " << case_dir.string() << "\n"
                  << "Threads   : " << (serial ? 1 : omp_get_max_threads())
                  << (serial ? "" : " (used for large ASCII lists when the load allows)") << "\n"
                  << "Load avg  : " << load_average() << " on " << omp_get_num_procs() << " cores\n"
                  << "RSS before: " << peak_rss_mb() << " MB\n";
        io::PolyMeshReadOptions options;
        options.parallel = !serial;
        // Peak RSS is taken after the first read: later repeats would add the allocator's
        // retained memory, not the reader's.
        double t0 = now();
        double c0 = cpu_now();
        io::FoamPolyMesh m = io::read_poly_mesh(case_dir, options);
        double best = now() - t0;
        double best_cpu = cpu_now() - c0;
        const double peak_first_read = peak_rss_mb();
        for (int r = 1; r < repeat; ++r)
        {
            m = io::FoamPolyMesh(); // release the previous mesh first
            t0 = now();
            c0 = cpu_now();
            m = io::read_poly_mesh(case_dir, options);
            best = std::min(best, now() - t0);
            best_cpu = std::min(best_cpu, cpu_now() - c0);
        }
        const PolyMesh& mesh = m.mesh;
        const double mb = static_cast<double>(m.total_bytes()) / 1e6;
        std::printf("Mesh      : %lld points, %lld faces, %lld internal faces, %lld cells\n",
                    static_cast<long long>(mesh.n_points()), static_cast<long long>(mesh.n_faces()),
                    static_cast<long long>(mesh.n_internal_faces()),
                    static_cast<long long>(mesh.n_cells));
        std::cout << "Files     : points " << describe(m.points) << ", faces " << describe(m.faces)
                  << " (" << m.faces.header.class_name << "), owner " << describe(m.owner)
                  << ", neighbour " << describe(m.neighbour) << "\n";
        std::printf("Read      : %.1f MB (decompressed) in %.3f s = %.0f MB/s (best of %d)\n", mb,
                    best, mb / best, repeat);
        std::printf("Read CPU  : %.3f s of CPU time = %.0f MB/s per CPU-second\n", best_cpu,
                    mb / best_cpu);
        std::printf("Memory    : mesh %.1f MB in memory, peak RSS of the first read %.1f MB "
                    "(%.2f x mesh)\n",
                    mesh_mb(mesh), peak_first_read, peak_first_read / mesh_mb(mesh));
        if (!write_dir.empty())
        {
            fs::remove_all(write_dir);
            t0 = now();
            io::write_points(mesh.points, m.points, write_dir, "constant");
            const double t_points = now() - t0;
            t0 = now();
            io::write_poly_mesh(mesh, m, write_dir, "constant");
            const double t_all = now() - t0;
            std::printf(
                "Write     : points %.3f s (%.0f MB/s), whole polyMesh %.3f s (%.0f MB/s)\n",
                t_points, m.points.bytes / 1e6 / t_points, t_all, mb / t_all);
        }
        if (run_check_mesh && std::system("command -v checkMesh > /dev/null 2>&1") == 0)
        {
            if (std::getenv("WM_PROJECT_DIR") == nullptr)
                setenv("WM_PROJECT_DIR", "/usr/share/openfoam", 0);
            const std::string cmd = "checkMesh -case '" + case_dir.string() + "' -constant > '" +
                                    (case_dir / "log.benchCheckMesh").string() + "' 2>&1";
            const auto children_cpu = []
            {
                rusage u{};
                getrusage(RUSAGE_CHILDREN, &u);
                return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
                       1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
            };
            const double cpu_start = children_cpu();
            const double wall_start = now();
            const int rc = std::system(cmd.c_str());
            const double t = now() - wall_start;
            std::printf("checkMesh : %.3f s wall, %.3f s CPU (exit %d; reads the same mesh, then "
                        "checks it; log %s)\n",
                        t, children_cpu() - cpu_start, rc,
                        (case_dir / "log.benchCheckMesh").c_str());
        }
    }
    catch (const meshmorph::Error& e)
    {
        std::cerr << "Error: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
