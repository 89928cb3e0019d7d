// SPDX-License-Identifier: GPL-3.0-or-later
// The designBasis file: a text magic line, a JSON header line, binary blocks.
#include "meshmorph/design/design_basis.h"

#include <bit>
#include <cstdint>
#include <functional>

#include <nlohmann/json.hpp>

#include "meshmorph/core/exceptions.h"
#include "meshmorph/io/temp_file.h"

namespace meshmorph::design
{

namespace fs = std::filesystem;

namespace
{

// The binary blocks are native doubles and int64; every platform meshMorph builds on is
// little-endian, which the header records so that a file moved elsewhere is refused.
static_assert(std::endian::native == std::endian::little, "designBasis assumes little-endian");

constexpr const char* magic_line = "meshMorph designBasis";

nlohmann::json header_json(const DesignBasisHeader& h)
{
    nlohmann::json bounds = nlohmann::json::array();
    for (const auto& b : h.bounds)
        bounds.push_back(b ? nlohmann::json::array({b->first, b->second}) : nlohmann::json());
    return {{"endian", "little"},
            {"points", h.points_fingerprint},
            {"topology", h.topology_fingerprint},
            {"dictionary", h.dict_fingerprint},
            {"instance", h.instance},
            {"method", h.method},
            {"nPoints", h.n_points},
            {"names", h.names},
            {"bounds", bounds},
            {"negativeVolumeCellsBefore", h.negative_volume_cells_before},
            {"incorrectlyOrientedFacePyramidsBefore", h.wrong_pyramids_before},
            {"storage", h.shared ? "shared" : "fields"},
            {"sharedTemplate", h.shared_template}};
}

DesignBasisHeader header_from_json(const nlohmann::json& j)
{
    DesignBasisHeader h;
    if (j.at("endian") != "little")
        throw InvalidInput("written on a big-endian machine");
    h.points_fingerprint = j.at("points");
    h.topology_fingerprint = j.at("topology");
    h.dict_fingerprint = j.at("dictionary");
    h.instance = j.at("instance");
    h.method = j.at("method");
    h.n_points = j.at("nPoints");
    h.names = j.at("names").get<std::vector<std::string>>();
    for (const nlohmann::json& b : j.at("bounds"))
        h.bounds.push_back(b.is_null() ? std::nullopt
                                       : std::optional(std::make_pair(b.at(0).get<double>(),
                                                                      b.at(1).get<double>())));
    h.negative_volume_cells_before = j.at("negativeVolumeCellsBefore");
    h.wrong_pyramids_before = j.at("incorrectlyOrientedFacePyramidsBefore");
    if (j.contains("storage")) // version 1 had fields only
    {
        if (j.at("storage") != "fields" && j.at("storage") != "shared")
            throw InvalidInput("unknown storage");
        h.shared = j.at("storage") == "shared";
        h.shared_template = j.at("sharedTemplate");
    }
    if (h.shared && (h.shared_template < 0 || h.shared_template >= Index(h.names.size())))
        throw InvalidInput("sharedTemplate out of range");
    if (h.bounds.size() != h.names.size() || h.n_points < 0)
        throw InvalidInput("inconsistent sizes");
    return h;
}

template <class T> void write_raw(std::ofstream& out, const T* data, std::size_t n)
{
    out.write(reinterpret_cast<const char*>(data), std::streamsize(n * sizeof(T)));
}

template <class T> bool read_raw(std::ifstream& in, T* data, std::size_t n)
{
    in.read(reinterpret_cast<char*>(data), std::streamsize(n * sizeof(T)));
    return bool(in);
}

//! Bytes of a block with c point labels and a field of n rows.
std::uintmax_t block_bytes(std::uintmax_t c, std::uintmax_t n)
{
    return 8 * (4 + 1 + c + 3 * c + 3 * n);
}

//! The versions read: 1 (fields only) and the current one.
bool readable_version(const std::string& magic)
{
    for (int version = 1; version <= DesignBasisHeader::current_version; ++version)
        if (magic == std::string(magic_line) + ' ' + std::to_string(version))
            return true;
    return false;
}

} // namespace

fs::path design_basis_path(const fs::path& mesh_case, const std::string& region)
{
    return mesh_case / "constant" / region / "designBasis";
}

DesignBasisWriter::DesignBasisWriter(const fs::path& target, const DesignBasisHeader& header)
    : target_(target), temp_(io::temp_path_for(target)), header_(header)
{
    io::remove_stale_temps(target);
    out_.open(temp_, std::ios::binary | std::ios::trunc);
    if (!out_)
        throw IoError("cannot write " + target.string() + " (temporary " + temp_.string() + ")");
    out_ << magic_line << ' ' << DesignBasisHeader::current_version << '\n'
         << header_json(header).dump() << '\n';
}

DesignBasisWriter::~DesignBasisWriter()
{
    if (committed_)
        return;
    out_.close();
    std::error_code ignored;
    fs::remove(temp_, ignored);
}

void DesignBasisWriter::append(const VariableBlock& block)
{
    const double fit[4] = {block.fit.max_constraint_error, block.fit.relative_constraint_error,
                           block.fit.centres, block.fit.seconds};
    write_raw(out_, fit, 4);
    const std::vector<std::int64_t> labels(block.constrained.begin(), block.constrained.end());
    const std::int64_t count = std::int64_t(labels.size());
    write_raw(out_, &count, 1);
    write_raw(out_, labels.data(), labels.size());
    write_raw(out_, block.prescribed.data(), std::size_t(block.prescribed.size()));
    write_raw(out_, block.field.data(), std::size_t(block.field.size()));
    ++written_;
}

void DesignBasisWriter::commit()
{
    if (written_ != header_.names.size())
        throw InvalidInput("design set-up: " + std::to_string(written_) + " of " +
                           std::to_string(header_.names.size()) + " variables written");
    out_.flush();
    const bool ok = bool(out_);
    out_.close();
    if (!ok)
        throw IoError("cannot write " + target_.string() + " (disk full?)");
    std::error_code ec;
    fs::rename(temp_, target_, ec);
    if (ec)
        throw IoError("cannot rename " + temp_.string() + " to " + target_.string() + ": " +
                      ec.message());
    committed_ = true;
    io::sync_directory(target_.parent_path());
}

DesignBasisReader::DesignBasisReader(const fs::path& path) : path_(path)
{
    in_.open(path, std::ios::binary);
    if (!in_)
        throw IoError("cannot open the design set-up " + path.string() +
                      " (run morphMesh -variables first)");
    const auto bad = [&](const std::string& why)
    { return ParseError(path.string(), 0, "not a meshMorph design set-up: " + why); };
    std::string magic, header;
    std::getline(in_, magic);
    const std::string expected =
        std::string(magic_line) + ' ' + std::to_string(DesignBasisHeader::current_version);
    if (magic.rfind(magic_line, 0) != 0)
        throw bad("it does not start with '" + std::string(magic_line) + "'");
    if (!readable_version(magic))
        throw ParseError(path.string(), 1,
                         "design set-up format '" + magic + "', this morphMesh reads up to '" +
                             expected + "' (run morphMesh -variables again)");
    std::getline(in_, header);
    try
    {
        header_ = header_from_json(nlohmann::json::parse(header));
    }
    catch (const std::exception& e)
    {
        throw bad(std::string("bad header (") + e.what() + ")");
    }
    blocks_start_ = in_.tellg();
    check_blocks(bad);
}

void DesignBasisReader::check_blocks(const std::function<ParseError(const std::string&)>& bad)
{
    // Walk the blocks so that a truncated, padded or hostile file is refused before use:
    // every count bounded by the file's size first (no overflow), every label in range.
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path_, ec);
    if (ec)
        throw bad("cannot read its size (" + ec.message() + ")");
    const std::uintmax_t n = std::uintmax_t(header_.field_rows());
    if (n > size / 24)
        throw bad("its header's " + std::to_string(n) + " points do not fit in its size");
    std::uintmax_t at = std::uintmax_t(blocks_start_);
    std::vector<std::int64_t> labels;
    for (std::size_t j = 0; j < header_.names.size(); ++j)
    {
        std::int64_t c = -1;
        in_.seekg(std::streamoff(at + 32));
        if (at + 40 > size || !read_raw(in_, &c, 1) || c < 0 || std::uintmax_t(c) > size / 32)
            throw bad("truncated at the block of " + header_.names[j]);
        labels.resize(std::size_t(c));
        if (!read_raw(in_, labels.data(), labels.size()))
            throw bad("truncated at the block of " + header_.names[j]);
        for (std::int64_t l : labels)
            if (l < 0 || l >= header_.n_points)
                throw bad("constrained point label " + std::to_string(l) + " out of range");
        at += block_bytes(std::uintmax_t(c), n);
        if (at > size)
            throw bad("truncated at the block of " + header_.names[j]);
    }
    if (at != size)
        throw bad("its size (" + std::to_string(size) + " bytes) does not match its header (" +
                  std::to_string(at) + ")");
    rewind();
}

void DesignBasisReader::next(VariableBlock& block)
{
    double fit[4];
    std::int64_t c = 0;
    if (!read_raw(in_, fit, 4) || !read_raw(in_, &c, 1))
        throw ParseError(path_.string(), 0, "truncated design set-up");
    std::vector<std::int64_t> labels(static_cast<std::size_t>(c));
    block.prescribed.resize(Index(c), 3);
    block.field.resize(header_.field_rows(), 3);
    if (!read_raw(in_, labels.data(), labels.size()) ||
        !read_raw(in_, block.prescribed.data(), std::size_t(block.prescribed.size())) ||
        !read_raw(in_, block.field.data(), std::size_t(block.field.size())))
        throw ParseError(path_.string(), 0, "truncated design set-up");
    block.fit = {fit[0], fit[1], fit[2], fit[3]};
    block.constrained.resize(labels.size());
    for (std::size_t i = 0; i < labels.size(); ++i)
    {
        if (labels[i] < 0 || labels[i] >= header_.n_points)
            throw ParseError(path_.string(), 0,
                             "constrained point label " + std::to_string(labels[i]) +
                                 " out of range");
        block.constrained[i] = Index(labels[i]);
    }
}

void DesignBasisReader::skip()
{
    std::int64_t c = 0;
    in_.seekg(32, std::ios::cur);
    if (!read_raw(in_, &c, 1) || c < 0)
        throw ParseError(path_.string(), 0, "truncated design set-up");
    in_.seekg(
        std::streamoff(block_bytes(std::uintmax_t(c), std::uintmax_t(header_.field_rows())) - 40),
        std::ios::cur);
}

void DesignBasisReader::rewind()
{
    in_.clear();
    in_.seekg(blocks_start_);
}

} // namespace meshmorph::design
