// SPDX-License-Identifier: GPL-3.0-or-later
//! \file A binary buffer for fitted fields (field_io.h): trivially copyable values, vectors
//! and matrices in the machine's byte order (the ranks of one run share it). Reading past
//! the end is an error, never undefined behaviour.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/core/exceptions.h"

namespace meshmorph
{

//! What a written field is (its first value).
enum class FieldKind : std::uint32_t
{
    rbf = 1,       //!< an RBF expansion (direct or greedy): detail::RbfModel
    idw = 2,       //!< IDW: settings, handles, values
    ffd = 3,       //!< an FFD lattice and its control displacements (FFD, DM-FFD)
    sum = 4,       //!< two fields added (a global field and its local correction)
    idw_local = 5, //!< IDW for one region only: normalisation and the essential tree
    limited = 6,   //!< a field projected onto a ball: its radius, then the field
};

//! Where a written field will be evaluated (a -parallel rank's points): fields whose size
//! grows with the handles (IDW) write only what evaluations there need.
struct QueryRegion
{
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0}; //!< bounding box of the points (plain: sent)
};

class FieldWriter
{
public:
    FieldWriter() = default;
    explicit FieldWriter(const QueryRegion* region) : region_(region) {}
    //! The region the field is written for, or nullptr (everywhere).
    const QueryRegion* region() const { return region_; }
    template <class T> void put(const T& value)
    {
        static_assert(std::is_trivially_copyable_v<T>);
        bytes_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    template <class T> void put_vector(const std::vector<T>& v)
    {
        put(static_cast<std::uint64_t>(v.size()));
        bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
    void put_string(const std::string& s)
    {
        put(static_cast<std::uint64_t>(s.size()));
        bytes_ += s;
    }
    template <class Derived> void put_matrix(const Eigen::PlainObjectBase<Derived>& m)
    {
        put(static_cast<std::int64_t>(m.rows()));
        put(static_cast<std::int64_t>(m.cols()));
        bytes_.append(reinterpret_cast<const char*>(m.data()),
                      static_cast<std::size_t>(m.size()) * sizeof(typename Derived::Scalar));
    }
    const std::string& bytes() const { return bytes_; }

private:
    std::string bytes_;
    const QueryRegion* region_ = nullptr;
};

class FieldReader
{
public:
    explicit FieldReader(std::string_view bytes) : bytes_(bytes) {}
    template <class T> T get()
    {
        static_assert(std::is_trivially_copyable_v<T>);
        T value;
        std::memcpy(&value, take(sizeof(T)), sizeof(T));
        return value;
    }
    template <class T> std::vector<T> get_vector()
    {
        const std::uint64_t n = get<std::uint64_t>();
        check_count(n, sizeof(T));
        std::vector<T> v(static_cast<std::size_t>(n));
        if (n > 0)
            std::memcpy(v.data(), take(v.size() * sizeof(T)), v.size() * sizeof(T));
        return v;
    }
    std::string get_string()
    {
        const std::uint64_t n = get<std::uint64_t>();
        check_count(n, 1);
        return std::string(take(static_cast<std::size_t>(n)), static_cast<std::size_t>(n));
    }
    template <class Matrix> Matrix get_matrix()
    {
        const std::int64_t rows = get<std::int64_t>();
        const std::int64_t cols = get<std::int64_t>();
        if (rows < 0 || cols < 0 ||
            (Matrix::ColsAtCompileTime > 0 && cols != Matrix::ColsAtCompileTime) ||
            (Matrix::RowsAtCompileTime > 0 && rows != Matrix::RowsAtCompileTime))
            throw IoError("fitted field: bad matrix shape");
        check_count(static_cast<std::uint64_t>(rows) * static_cast<std::uint64_t>(cols),
                    sizeof(typename Matrix::Scalar));
        Matrix m(rows, cols);
        const std::size_t n = static_cast<std::size_t>(m.size()) * sizeof(typename Matrix::Scalar);
        if (n > 0)
            std::memcpy(m.data(), take(n), n);
        return m;
    }
    bool at_end() const { return offset_ == bytes_.size(); }

private:
    const char* take(std::size_t n)
    {
        if (n > bytes_.size() - offset_)
            throw IoError("fitted field: truncated data");
        const char* p = bytes_.data() + offset_;
        offset_ += n;
        return p;
    }
    void check_count(std::uint64_t n, std::size_t size) const
    {
        if (n > (bytes_.size() - offset_) / size)
            throw IoError("fitted field: truncated data");
    }
    std::string_view bytes_;
    std::size_t offset_ = 0;
};

} // namespace meshmorph
