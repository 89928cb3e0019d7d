// SPDX-License-Identifier: GPL-3.0-or-later
// Held fits: one fitted deformation per set of handles, refitted for new data.
#include "meshmorph/deform/held_fit.h"

#include "meshmorph/core/exceptions.h"

namespace meshmorph
{

namespace
{

//! A deformation whose fit() goes through a HeldFits and whose other calls go to the
//! deformation that fit returned.
class HeldFitView : public SpaceDeformation
{
public:
    explicit HeldFitView(HeldFits& owner) : owner_(owner) {}

    void fit(const Eigen::Ref<const Points>& handles,
             const Eigen::Ref<const Points>& displacements) override
    {
        index_ = owner_.fit(handles, displacements);
        current_ = &owner_.deformation(index_);
    }
    void refit(const Eigen::Ref<const Points>& displacements) override
    {
        fitted();
        owner_.refit(index_, displacements);
    }
    void evaluate(const Eigen::Ref<const Points>& points, Eigen::Ref<Points> out) const override
    {
        fitted().evaluate(points, out);
    }
    Points transpose(const Eigen::Ref<const Points>& points,
                     const Eigen::Ref<const Points>& weights) const override
    {
        return fitted().transpose(points, weights);
    }
    const FitReport& report() const override { return fitted().report(); }
    bool is_fitted() const override { return current_ != nullptr && current_->is_fitted(); }
    void write_field(FieldWriter& out) const override { fitted().write_field(out); }
    const Points* values_at_handles() const override
    {
        return current_ != nullptr ? current_->values_at_handles() : nullptr;
    }
    const std::vector<char>* handles_left_out() const override
    {
        return current_ != nullptr ? current_->handles_left_out() : nullptr;
    }

private:
    SpaceDeformation& fitted() const
    {
        if (current_ == nullptr)
            throw InvalidInput("held fit: used before fit");
        return *current_;
    }

    HeldFits& owner_;
    std::size_t index_ = 0;
    SpaceDeformation* current_ = nullptr;
};

//! Equal row for row, bit for bit (handles, or the data fitted to them).
bool same_handles(const Points& a, const Eigen::Ref<const Points>& b)
{
    return a.rows() == b.rows() && (a.rows() == 0 || a == b);
}

} // namespace

HeldFits::HeldFits(Maker make) : make_(std::move(make))
{
    if (!make_)
        throw InvalidInput("held fit: no deformation maker given");
}

std::unique_ptr<SpaceDeformation> HeldFits::view()
{
    return std::make_unique<HeldFitView>(*this);
}

std::size_t HeldFits::fit(const Eigen::Ref<const Points>& handles,
                          const Eigen::Ref<const Points>& displacements)
{
    for (std::size_t k = 0; k < fits_.size(); ++k)
        if (same_handles(fits_[k].handles, handles))
        {
            refit(k, displacements);
            return k;
        }
    if (frozen_)
        throw InvalidInput("held fit: " + std::to_string(handles.rows()) +
                           " handles that the chosen fits do not have (the constraints "
                           "changed after the set-up)");
    Held held{handles, displacements, make_()};
    held.deformation->fit(handles, displacements);
    fits_.push_back(std::move(held));
    return fits_.size() - 1;
}

void HeldFits::refit(std::size_t k, const Eigen::Ref<const Points>& displacements)
{
    Held& held = fits_.at(k);
    if (same_handles(held.displacements, displacements))
        return;
    held.deformation->refit(displacements);
    held.displacements = displacements;
}

} // namespace meshmorph
