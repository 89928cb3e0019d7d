// SPDX-License-Identifier: GPL-3.0-or-later
// benchTokenizer [MB]: throughput of the OpenFOAM tokenizer's hot-loop readers and of the
// dictionary parser on synthetic ASCII lists (default 50 MB of points, as a large mesh).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_tokenizer.h"

using namespace meshmorph::io;
using Clock = std::chrono::steady_clock;

namespace
{

double seconds_since(Clock::time_point t0)
{
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

void report(const char* what, std::size_t bytes, double s, double checksum)
{
    std::printf("%-42s %8.1f MB in %6.3f s = %7.1f MB/s   (checksum %.6g)\n", what, bytes / 1e6, s,
                bytes / 1e6 / s, checksum);
}

} // namespace

int main(int argc, char** argv)
{
    const double target_mb = argc > 1 ? std::atof(argv[1]) : 50.0;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-10.0, 10.0);

    // Points as OpenFOAM writes them with writePrecision 17: `(x y z)` per line.
    std::string points = "\n";
    std::size_t n = 0;
    const std::size_t reserve = static_cast<std::size_t>(target_mb * 1e6) + 1000;
    std::string body;
    body.reserve(reserve);
    char buf[128];
    while (body.size() < target_mb * 1e6)
    {
        const int len =
            std::snprintf(buf, sizeof buf, "(%.17g %.17g %.17g)\n", u(rng), u(rng), u(rng));
        body.append(buf, static_cast<std::size_t>(len));
        ++n;
    }
    points += std::to_string(n) + "\n(\n" + body + ")\n";

    // Labels as in owner/neighbour: one per line.
    std::string labels = std::to_string(0) + "\n(\n";
    std::size_t m = 0;
    std::string lbody;
    lbody.reserve(reserve);
    std::uniform_int_distribution<int> ui(0, 20000000);
    while (lbody.size() < target_mb * 1e6)
    {
        lbody += std::to_string(ui(rng));
        lbody += '\n';
        ++m;
    }
    labels = std::to_string(m) + "\n(\n" + lbody + ")\n";

    {
        const Clock::time_point t0 = Clock::now();
        FoamTokenizer tok(points, "points");
        const std::int64_t count = tok.expect_size();
        tok.expect('(');
        double sum = 0.0, xyz[3];
        for (std::int64_t i = 0; i < count; ++i)
        {
            tok.read_vector(xyz);
            sum += xyz[0] + xyz[1] + xyz[2];
        }
        tok.expect(')');
        report("read_vector (points, %.17g)", points.size(), seconds_since(t0), sum);
    }
    {
        const Clock::time_point t0 = Clock::now();
        FoamTokenizer tok(labels, "owner");
        const std::int64_t count = tok.expect_size();
        tok.expect('(');
        std::int64_t sum = 0, v = 0;
        for (std::int64_t i = 0; i < count; ++i)
        {
            if (!tok.read_label(v))
                return 1;
            sum += v;
        }
        tok.expect(')');
        report("read_label (owner-like labels)", labels.size(), seconds_since(t0),
               static_cast<double>(sum));
    }
    {
        const Clock::time_point t0 = Clock::now();
        FoamTokenizer tok(points, "points");
        double sum = 0.0;
        std::size_t tokens = 0;
        for (FoamToken t = tok.next(); !t.is_end(); t = tok.next())
        {
            ++tokens;
            sum += t.scalar;
        }
        report("next() generic tokens (points)", points.size(), seconds_since(t0), sum);
    }
    {
        const std::string field = "internalField nonuniform List<vector> " + points + ";\n";
        const Clock::time_point t0 = Clock::now();
        const FoamDictionary d = parse_dictionary(field, "0/pointDisplacement");
        const auto& c = *d.entry("internalField").tokens().at(1).compound;
        report("parse_dictionary nonuniform List<vector>", field.size(), seconds_since(t0),
               c.scalars.empty() ? 0.0 : c.scalars.back());
    }
    return 0;
}
