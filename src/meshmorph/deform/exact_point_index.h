// SPDX-License-Identifier: GPL-3.0-or-later
//! \file Internal: points found by their exact coordinates. A mesh morph evaluates its field
//! at every mesh point, and the constrained ones are exactly the handles of the fit, where
//! a field may already know its value (IdwTree's sources, CorrectedDeformation's global
//! part); a hash look-up then replaces a sum.
#pragma once

#include <bit>
#include <cstdint>
#include <vector>

#include "meshmorph/core/types.h"

namespace meshmorph::detail
{

//! A point's exact coordinates as a hash key.
struct PointKey
{
    std::uint64_t x, y, z;
    bool operator==(const PointKey&) const = default;
};
//! splitmix64's finaliser on each coordinate: every bit of the key reaches the low bits
//! that pick a slot (coordinates such as 0.5 or 1.25 have 50 trailing zero bits).
struct PointKeyHash
{
    static std::uint64_t mix(std::uint64_t z)
    {
        z ^= z >> 30;
        z *= 0xbf58476d1ce4e5b9ull;
        z ^= z >> 27;
        z *= 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    std::size_t operator()(const PointKey& k) const
    {
        return static_cast<std::size_t>(mix(k.x ^ mix(k.y ^ mix(k.z))));
    }
};

inline PointKey point_key(double x, double y, double z)
{
    // + 0.0 turns -0 into +0, which compares equal to it.
    return {std::bit_cast<std::uint64_t>(x + 0.0), std::bit_cast<std::uint64_t>(y + 0.0),
            std::bit_cast<std::uint64_t>(z + 0.0)};
}

//! The rows of a point array by exact coordinates: an open-addressing hash table (linear
//! probing, at most half full), one cache line or two per look-up where a node-based map
//! took several. Coordinates inserted twice map to neither (find gives -1), so a look-up
//! never picks one of several candidates.
class ExactPointIndex
{
public:
    ExactPointIndex() = default;
    //! Room for `n` points.
    explicit ExactPointIndex(std::size_t n)
    {
        std::size_t capacity = 16;
        while (capacity < 2 * n)
            capacity *= 2;
        slots_.assign(capacity, Slot{});
        mask_ = capacity - 1;
    }
    //! Every row of points.
    explicit ExactPointIndex(const Eigen::Ref<const Points>& points)
        : ExactPointIndex(static_cast<std::size_t>(points.rows()))
    {
        for (Eigen::Index i = 0; i < points.rows(); ++i)
            insert(points(i, 0), points(i, 1), points(i, 2), Index(i));
    }

    bool empty() const { return size_ == 0; }

    //! Adds a point as `row`; a point already present then maps to no row. At most the
    //! number of points the index was made for.
    void insert(double x, double y, double z, Index row)
    {
        const PointKey k = point_key(x, y, z);
        for (std::size_t i = slot_of(k);; i = (i + 1) & mask_)
        {
            Slot& s = slots_[i];
            if (s.row == empty_slot)
            {
                s = {k, row};
                ++size_;
                return;
            }
            if (s.key == k)
            {
                s.row = -1;
                return;
            }
        }
    }

    //! The row whose coordinates equal (x, y, z), or -1.
    Index find(double x, double y, double z) const
    {
        if (size_ == 0)
            return -1;
        const PointKey k = point_key(x, y, z);
        for (std::size_t i = slot_of(k);; i = (i + 1) & mask_)
        {
            const Slot& s = slots_[i];
            if (s.row == empty_slot)
                return -1;
            if (s.key == k)
                return s.row;
        }
    }

    //! find() for every row of `points` (OpenMP over rows).
    std::vector<Index> find_rows(const Eigen::Ref<const Points>& points) const
    {
        const std::int64_t n = points.rows();
        std::vector<Index> rows(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static) if (n > 4096)
        for (std::int64_t i = 0; i < n; ++i)
            rows[std::size_t(i)] = find(points(i, 0), points(i, 1), points(i, 2));
        return rows;
    }

private:
    static constexpr Index empty_slot = -2;
    struct Slot
    {
        PointKey key{0, 0, 0};
        Index row = empty_slot;
    };
    std::size_t slot_of(const PointKey& k) const
    {
        return PointKeyHash{}(k)&mask_;
    }

    std::vector<Slot> slots_;
    std::size_t mask_ = 0;
    std::size_t size_ = 0;
};

} // namespace meshmorph::detail
