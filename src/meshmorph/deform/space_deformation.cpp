// SPDX-License-Identifier: GPL-3.0-or-later
// The space-deformation interface: apply(), argument checks shared by the methods.
#include "meshmorph/deform/space_deformation.h"

#include <dlfcn.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <string>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/lapack.h"

namespace meshmorph
{

void SpaceDeformation::write_field(FieldWriter& /*out*/) const
{
    throw InvalidInput("this kind of deformation (" + report().method +
                       ") cannot be sent to other ranks");
}

Points SpaceDeformation::transpose(const Eigen::Ref<const Points>& /*points*/,
                                   const Eigen::Ref<const Points>& /*weights*/) const
{
    throw InvalidInput("this kind of deformation (" + report().method +
                       ") has no reverse pass (transpose) for sensitivities");
}

Points displacements(const SpaceDeformation& deformation, const Eigen::Ref<const Points>& points)
{
    Points out(points.rows(), 3);
    deformation.evaluate(points, out);
    return out;
}

Points apply(const SpaceDeformation& deformation, const Eigen::Ref<const Points>& points)
{
    Points out(points.rows(), 3);
    deformation.evaluate(points, out);
    out += points;
    return out;
}

void SpaceDeformation::refit(const Eigen::Ref<const Points>& /*displacements*/)
{
    throw InvalidInput(report().method + ": refit with the fit's choices held is not available");
}

namespace detail
{

void use_one_blas_thread()
{
    // OpenBLAS splits its factorisations differently for different thread counts, and the
    // last bits of the result follow (2.4e-13 of the displacement on the venturi squeeze
    // between OPENBLAS_NUM_THREADS 1 and 2). The fits are a small part of a morph; the
    // evaluation, which is most of it, runs on OpenMP's threads. Looked up at run time so
    // that any other BLAS (reference, BLIS) links as well. Only OpenBLAS's pthread build
    // (Debian's default, openblas_get_parallel() == 1) is told: in its OpenMP build the call
    // would also set OpenMP's thread count, making every later parallel loop serial.
    static std::once_flag once;
    std::call_once(once,
                   []
                   {
                       using GetParallel = int (*)();
                       using SetThreads = void (*)(int);
                       auto* parallel = reinterpret_cast<GetParallel>(
                           ::dlsym(RTLD_DEFAULT, "openblas_get_parallel"));
                       auto* set = reinterpret_cast<SetThreads>(
                           ::dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
                       if (parallel && set && parallel() == 1)
                           set(1);
                   });
}

int lapack_int(long long n)
{
    use_one_blas_thread();
    if (n < 0 || n > std::numeric_limits<int>::max())
        throw InvalidInput("matrix dimension " + std::to_string(n) +
                           " exceeds LAPACK's 32-bit integer range");
    return static_cast<int>(n);
}

void require_finite(const Eigen::Ref<const Points>& p, const char* what)
{
    for (Eigen::Index i = 0; i < p.rows(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!std::isfinite(p(i, c)))
            {
                std::ostringstream s;
                s << what << " row " << i << " is not finite: (" << p(i, 0) << ' ' << p(i, 1) << ' '
                  << p(i, 2) << ')';
                throw InvalidInput(s.str());
            }
}

void check_fit_arguments(const Eigen::Ref<const Points>& handles,
                         const Eigen::Ref<const Points>& displacements)
{
    if (handles.rows() == 0)
        throw InvalidInput("fit: no handles given (m == 0)");
    if (displacements.rows() != handles.rows())
        throw InvalidInput("fit: " + std::to_string(handles.rows()) + " handles but " +
                           std::to_string(displacements.rows()) + " displacements");
    require_finite(handles, "fit: handle");
    require_finite(displacements, "fit: displacement");
}

void check_evaluate_arguments(bool is_fitted, const Eigen::Ref<const Points>& points,
                              const Eigen::Ref<Points>& out, const char* method)
{
    if (!is_fitted)
        throw InvalidInput(std::string(method) + ": evaluate() called before fit()");
    require_finite(points, (std::string(method) + " evaluate: point").c_str());
    check_output_rows(points, out, method);
}

void check_transpose_arguments(bool is_fitted, const Eigen::Ref<const Points>& points,
                               const Eigen::Ref<const Points>& weights, const char* method)
{
    if (!is_fitted)
        throw InvalidInput(std::string(method) + ": transpose() called before fit()");
    require_finite(points, (std::string(method) + " transpose: point").c_str());
    require_finite(weights, (std::string(method) + " transpose: weight").c_str());
    if (weights.rows() != points.rows())
        throw InvalidInput(std::string(method) + " transpose: " + std::to_string(weights.rows()) +
                           " weight rows for " + std::to_string(points.rows()) + " points");
}

void check_output_rows(const Eigen::Ref<const Points>& points, const Eigen::Ref<Points>& out,
                       const char* method)
{
    if (out.rows() != points.rows())
        throw InvalidInput(std::string(method) + ": evaluate() output has " +
                           std::to_string(out.rows()) + " rows for " +
                           std::to_string(points.rows()) + " points");
}

void residual_report(const Eigen::Ref<const Points>& got,
                     const Eigen::Ref<const Points>& displacements, FitReport& report)
{
    double max_r = 0.0, sum_r2 = 0.0, max_d = 0.0;
    for (Eigen::Index i = 0; i < got.rows(); ++i)
    {
        const double r = (got.row(i) - displacements.row(i)).norm();
        max_r = std::max(max_r, r);
        sum_r2 += r * r;
        max_d = std::max(max_d, displacements.row(i).norm());
    }
    report.max_residual = max_r;
    report.max_fitted_residual = max_r;
    report.rms_residual = got.rows() > 0 ? std::sqrt(sum_r2 / double(got.rows())) : 0.0;
    report.max_displacement = max_d;
}

void residual_report(const SpaceDeformation& d, const Eigen::Ref<const Points>& handles,
                     const Eigen::Ref<const Points>& displacements, FitReport& report)
{
    Points got(handles.rows(), 3);
    d.evaluate(handles, got);
    residual_report(got, displacements, report);
}

} // namespace detail
} // namespace meshmorph
