// SPDX-License-Identifier: GPL-3.0-or-later
// benchPaper: the C++ sections of the paper benchmarks (Sieger, Menzel, Botsch, "On Shape
// Deformation Techniques for Simulation-based Design Optimization", Sec. 3). Each section
// writes one JSON file; benchmarks/paper/deformationBenchmarks runs them (and the OpenFOAM
// parts) and writes the report.
//
// Usage: benchPaper <section> -out FILE.json [-quick] [-key value ...]
//   performance  [-points K] [-repeat N] [-scale 0|1] [-directLimit M]   (Sec. 3.1)
//   robustness                                                           (Sec. 3.2)
//   quality                                                              (Sec. 3.3)
//   precision                                                            (Sec. 3.5)
//   pipe -case DIR [-name NAME] [-motion squeeze|shift] [-step S] [-max A]
//        [-methods rbf,dmffd-5,...]                                      (Sec. 3.6.1)
//   motorbike -case CACHE -runs DIR [-lifts L1,L2,...] [-handles "x y z;..."]
//        [-methods rbf,dmffd-10,...]                                     (Sec. 3.6.2)
// The adaptivity benchmark (Sec. 3.4) is benchAdaptivity (benchmarks/deform).
#include <cstdio>
#include <functional>
#include <map>
#include <string>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/core/log.h"
#include "sections.h"

int main(int argc, char** argv)
{
    const std::map<std::string, std::function<paper::Json(const paper::Options&)>> sections = {
        {"performance", paper::run_performance},
        {"robustness", paper::run_robustness},
        {"quality", paper::run_quality},
        {"precision", paper::run_precision},
        {"pipe", paper::run_pipe},
        {"motorbike", paper::run_motorbike}};
    if (argc < 2 || !sections.count(argv[1]))
    {
        std::fprintf(stderr, "usage: benchPaper performance|robustness|quality|precision|pipe|"
                             "motorbike -out FILE.json [-quick] [-key value ...]\n");
        return 2;
    }
    paper::Options options;
    for (int i = 2; i < argc; ++i)
    {
        const std::string a = argv[i];
        if (a == "-quick")
            options.quick = true;
        else if (a.size() > 1 && a[0] == '-' && i + 1 < argc)
        {
            if (a == "-out")
                options.out = argv[++i];
            else
                options.value[a.substr(1)] = argv[++i];
        }
        else
        {
            std::fprintf(stderr, "benchPaper: bad argument '%s'\n", a.c_str());
            return 2;
        }
    }
    if (options.out.empty())
    {
        std::fprintf(stderr, "benchPaper: -out FILE.json is required\n");
        return 2;
    }
    // Greedy budget stops and planar-handle notes are expected in these set-ups.
    meshmorph::log::set_level(meshmorph::log::Level::error);
    try
    {
        paper::Json j = sections.at(argv[1])(options);
        j["section"] = argv[1];
        j["quick"] = options.quick;
        paper::write_json(options.out, j);
    }
    catch (const meshmorph::Error& e)
    {
        std::fprintf(stderr, "benchPaper %s: error: %s\n", argv[1], e.what());
        return 1;
    }
    return 0;
}
