// SPDX-License-Identifier: GPL-3.0-or-later
// Motion types and conflict rules: spellings and the closed-form displacements.
#include "meshmorph/morph/motion.h"

#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "meshmorph/core/exceptions.h"

namespace meshmorph::morph
{

namespace
{

const std::vector<std::pair<MotionType, std::string>>& motion_names()
{
    static const std::vector<std::pair<MotionType, std::string>> names{
        {MotionType::fixed, "fixed"},
        {MotionType::translate, "translate"},
        {MotionType::rotate, "rotate"},
        {MotionType::scale, "scale"},
        {MotionType::point_displacement, "pointDisplacement"},
        {MotionType::surface, "surface"},
        {MotionType::slip, "slip"},
        {MotionType::free, "free"}};
    return names;
}

const std::vector<std::pair<ConflictRule, std::string>>& rule_names()
{
    static const std::vector<std::pair<ConflictRule, std::string>> names{
        {ConflictRule::error, "error"},
        {ConflictRule::first, "first"},
        {ConflictRule::last, "last"},
        {ConflictRule::fixed, "fixed"},
        {ConflictRule::average, "average"}};
    return names;
}

//! The spelling of `value` in `names` ("?" if absent).
template <typename Enum>
std::string spelling(const std::vector<std::pair<Enum, std::string>>& names, Enum value)
{
    for (const auto& [v, name] : names)
        if (v == value)
            return name;
    return "?";
}

//! The value spelled `word`. \throw InvalidInput "unknown <what> 'word' (valid<list>: ...)".
template <typename Enum>
Enum parse(const std::vector<std::pair<Enum, std::string>>& names, const std::string& word,
           const std::string& what, const std::string& list)
{
    std::string valid;
    for (const auto& [v, name] : names)
    {
        if (name == word)
            return v;
        valid += (valid.empty() ? "" : " ") + name;
    }
    throw InvalidInput("unknown " + what + " '" + word + "' (valid" + list + ": " + valid + ")");
}

} // namespace

std::string to_string(MotionType type)
{
    return spelling(motion_names(), type);
}

MotionType motion_type_from_string(const std::string& word)
{
    return parse(motion_names(), word, "type", " types");
}

std::string to_string(ConflictRule rule)
{
    return spelling(rule_names(), rule);
}

ConflictRule conflict_rule_from_string(const std::string& word)
{
    return parse(rule_names(), word, "conflict rule", "");
}

Vector3 Motion::displacement(const Vector3& x) const
{
    switch (type)
    {
    case MotionType::fixed:
        return Vector3::Zero();
    case MotionType::translate:
        return vector;
    case MotionType::rotate:
    {
        const double angle = angle_degrees * std::numbers::pi / 180.0;
        const Eigen::AngleAxisd rotation(angle, axis.normalized());
        return (rotation * (x - origin) + origin - x).eval();
    }
    case MotionType::scale:
        return (origin + factor.cwiseProduct(x - origin) - x).eval();
    default:
        throw std::logic_error("Motion::displacement: not a closed-form type");
    }
}

} // namespace meshmorph::morph
