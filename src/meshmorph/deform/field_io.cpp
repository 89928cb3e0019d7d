// SPDX-License-Identifier: GPL-3.0-or-later
// Fitted fields as bytes: each deformation writes its own (write_field); the reader restores
// evaluation-only deformations that evaluate with the same code and data.
#include "meshmorph/deform/field_io.h"

#include "meshmorph/deform/idw_tree.h"

#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/bspline_basis.h"
#include "meshmorph/deform/corrected_deformation.h"
#include "meshmorph/deform/ffd_deformation.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/idw_deformation.h"
#include "meshmorph/deform/rbf_evaluator.h"

namespace meshmorph
{

namespace
{

//! A restored field: evaluates, reports the original fit, cannot be refitted.
class RestoredField : public SpaceDeformation
{
public:
    void fit(const Eigen::Ref<const Points>&, const Eigen::Ref<const Points>&) override
    {
        throw InvalidInput("a field received from another rank cannot be refitted");
    }
    const FitReport& report() const override { return report_; }
    bool is_fitted() const override { return true; }
    void set_report(const FitReport& report) { report_ = report; }

private:
    FitReport report_;
};

class RbfField : public RestoredField
{
public:
    explicit RbfField(detail::RbfModel model) : model_(std::move(model)) {}
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override
    {
        detail::check_evaluate_arguments(true, points, out, "RBF");
        model_.evaluate(points, out);
    }
    void write_field(FieldWriter& out) const override
    {
        out.put(FieldKind::rbf);
        model_.write(out);
    }

private:
    detail::RbfModel model_;
};

//! IDW and FFD restore as the deformation itself (IDW refitted on the same data builds the
//! same tree); the wrapper keeps the original report.
class WrappedField : public RestoredField
{
public:
    explicit WrappedField(std::unique_ptr<SpaceDeformation> field) : field_(std::move(field)) {}
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override
    {
        field_->evaluate(points, out);
    }
    void write_field(FieldWriter& out) const override { field_->write_field(out); }

private:
    std::unique_ptr<SpaceDeformation> field_;
};

class SumField : public RestoredField
{
public:
    SumField(std::unique_ptr<SpaceDeformation> a, std::unique_ptr<SpaceDeformation> b)
        : a_(std::move(a)), b_(std::move(b))
    {
    }
    //! As CorrectedDeformation::evaluate: the global field plus the correction.
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override
    {
        a_->evaluate(points, out);
        Points correction(points.rows(), 3);
        b_->evaluate(points, correction);
        out += correction;
    }
    void write_field(FieldWriter& out) const override
    {
        out.put(FieldKind::sum);
        a_->write_field(out);
        b_->write_field(out);
    }

private:
    std::unique_ptr<SpaceDeformation> a_, b_;
};

class LimitedField : public RestoredField
{
public:
    LimitedField(double radius, std::unique_ptr<SpaceDeformation> field)
        : radius_(radius), field_(std::move(field))
    {
    }
    //! As CorrectedDeformation::evaluate with its limit.
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override
    {
        field_->evaluate(points, out);
        detail::limit_to_ball(out, radius_);
    }
    void write_field(FieldWriter& out) const override
    {
        out.put(FieldKind::limited);
        out.put(radius_);
        field_->write_field(out);
    }

private:
    double radius_;
    std::unique_ptr<SpaceDeformation> field_;
};

std::unique_ptr<SpaceDeformation> read_idw(FieldReader& in)
{
    const IdwSettings settings = in.get<IdwSettings>();
    const Points handles = in.get_matrix<Points>();
    const Points values = in.get_matrix<Points>();
    const std::vector<char> quiet = in.get_vector<char>();
    auto idw = std::make_unique<IdwDeformation>(settings);
    try
    {
        idw->fit(handles, values, quiet); // checks the counts
    }
    catch (const InvalidInput& e)
    {
        throw IoError(std::string("fitted field: ") + e.what());
    }
    return std::make_unique<WrappedField>(std::move(idw));
}

std::unique_ptr<SpaceDeformation> read_idw_local(FieldReader& in)
{
    return std::make_unique<WrappedField>(
        std::make_unique<IdwDeformation>(IdwDeformation::read_local(in)));
}

std::unique_ptr<SpaceDeformation> read_ffd(FieldReader& in)
{
    FfdBox box;
    box.origin = in.get_matrix<Vector3>();
    box.axes = in.get_matrix<Eigen::Matrix3d>();
    std::array<std::vector<double>, 3> knots;
    for (std::vector<double>& k : knots)
        k = in.get_vector<double>();
    const FfdOutside outside = in.get<FfdOutside>();
    auto ffd = std::make_unique<FfdDeformation>(FfdLattice(box, knots), outside);
    ffd->set_control_displacements(in.get_matrix<Points>());
    return std::make_unique<WrappedField>(std::move(ffd));
}

std::unique_ptr<SpaceDeformation> read_body(FieldReader& in)
{
    switch (in.get<FieldKind>())
    {
    case FieldKind::rbf:
        return std::make_unique<RbfField>(detail::RbfModel::read(in));
    case FieldKind::idw:
        return read_idw(in);
    case FieldKind::idw_local:
        return read_idw_local(in);
    case FieldKind::ffd:
        return read_ffd(in);
    case FieldKind::sum:
    {
        std::unique_ptr<SpaceDeformation> a = read_body(in);
        return std::make_unique<SumField>(std::move(a), read_body(in));
    }
    case FieldKind::limited:
    {
        const double radius = in.get<double>();
        if (!(radius >= 0.0))
            throw IoError("fitted field: a limit radius that is negative or not a number");
        return std::make_unique<LimitedField>(radius, read_body(in));
    }
    }
    throw IoError("fitted field: unknown kind");
}

void write_report(FieldWriter& out, const FitReport& r)
{
    out.put_string(r.method);
    out.put_string(r.solver);
    for (Index v : {r.num_handles, r.num_merged_duplicates, r.num_centres, r.polynomial_terms,
                    r.rank, r.iterations, r.jump_constraints})
        out.put(v);
    for (double v : {r.condition_estimate, r.max_displacement, r.max_residual, r.rms_residual,
                     r.max_fitted_residual})
        out.put(v);
}

FitReport read_report(FieldReader& in)
{
    FitReport r;
    r.method = in.get_string();
    r.solver = in.get_string();
    for (Index* v : {&r.num_handles, &r.num_merged_duplicates, &r.num_centres, &r.polynomial_terms,
                     &r.rank, &r.iterations, &r.jump_constraints})
        *v = in.get<Index>();
    for (double* v : {&r.condition_estimate, &r.max_displacement, &r.max_residual, &r.rms_residual,
                      &r.max_fitted_residual})
        *v = in.get<double>();
    return r;
}

} // namespace

QueryRegion query_region(const Points& x)
{
    QueryRegion r;
    for (int k = 0; k < 3 && x.rows() > 0; ++k)
    {
        r.lo[k] = x.col(k).minCoeff();
        r.hi[k] = x.col(k).maxCoeff();
    }
    return r;
}

std::string write_field(const SpaceDeformation& deformation, const QueryRegion* region)
{
    if (!deformation.is_fitted())
        throw InvalidInput("write_field: the deformation is not fitted");
    FieldWriter out(region);
    deformation.write_field(out);
    write_report(out, deformation.report());
    return out.bytes();
}

std::unique_ptr<SpaceDeformation> read_field(const std::string& bytes)
{
    FieldReader in(bytes);
    std::unique_ptr<SpaceDeformation> body = read_body(in);
    auto* restored = dynamic_cast<RestoredField*>(body.get());
    restored->set_report(read_report(in));
    if (!in.at_end())
        throw IoError("fitted field: trailing data");
    return body;
}

} // namespace meshmorph
