// SPDX-License-Identifier: GPL-3.0-or-later
// Fitted fields written and read back (src/meshmorph/deform/field_io.*): every kind of
// deformation evaluates bit-identically after the round trip, as a -parallel run needs.
#include "meshmorph/deform/field_io.h"

#include <cstring>
#include <stdexcept>

#include <gtest/gtest.h>

#include "deform_test_helpers.h"
#include "meshmorph/core/exceptions.h"
#include "meshmorph/deform/corrected_deformation.h"
#include "meshmorph/deform/dmffd_deformation.h"
#include "meshmorph/deform/ffd_deformation.h"
#include "meshmorph/deform/field_stream.h"
#include "meshmorph/deform/greedy_rbf_deformation.h"
#include "meshmorph/deform/idw_deformation.h"
#include "meshmorph/deform/rbf_deformation.h"

namespace meshmorph
{
namespace
{

//! Fits `d` to a smooth field on sphere points, writes and reads it, and compares the two at
//! other points: equal to the last bit, and the same report.
void expect_round_trip(SpaceDeformation& d)
{
    const Points handles = test::sphere_points(400, Vector3(0.5, 0.5, 0.5), 0.5);
    d.fit(handles, test::smooth_field(handles));
    const std::string bytes = write_field(d);
    const std::unique_ptr<SpaceDeformation> restored = read_field(bytes);
    const Points query = test::sphere_points(1000, Vector3(0.4, 0.5, 0.6), 0.7);
    Points want(query.rows(), 3), got(query.rows(), 3);
    d.evaluate(query, want);
    restored->evaluate(query, got);
    EXPECT_EQ(want, got) << d.report().method;
    EXPECT_EQ(restored->report().method, d.report().method);
    EXPECT_EQ(restored->report().num_centres, d.report().num_centres);
    EXPECT_EQ(restored->report().max_residual, d.report().max_residual);
    EXPECT_TRUE(restored->is_fitted());
    EXPECT_THROW(restored->fit(handles, handles), InvalidInput);
    EXPECT_EQ(write_field(*restored), bytes) << "a restored field writes the same bytes";
}

TEST(FieldIo, direct_rbf)
{
    RbfDeformation rbf;
    expect_round_trip(rbf);
}

TEST(FieldIo, wendland_rbf_rebuilds_its_grid)
{
    RbfSettings s;
    s.kernel = RbfKernel::wendland_c2;
    s.support_radius = 0.6;
    RbfDeformation rbf(s);
    expect_round_trip(rbf);
}

//! A greedy RBF to a loose tolerance made exact by its IDW correction (the morph's default
//! above 5000 constraints).
CorrectedDeformation corrected_greedy_rbf()
{
    GreedySettings coarse;
    coarse.tolerance = 0.05;
    coarse.rms_tolerance = 0.05;
    return CorrectedDeformation(std::make_unique<GreedyRbfDeformation>(coarse));
}

TEST(FieldIo, greedy_rbf_with_its_local_correction)
{
    CorrectedDeformation corrected = corrected_greedy_rbf();
    expect_round_trip(corrected);
}

TEST(FieldIo, idw)
{
    IdwDeformation idw;
    expect_round_trip(idw);
}

TEST(FieldIo, dmffd)
{
    DmffdSettings s;
    s.lattice.control_points = {6, 5, 7};
    DmffdDeformation dm(s);
    expect_round_trip(dm);
}

//! 20000 handles on a sphere, and the points of a small box on one side (a rank's part).
Points region_handles()
{
    return test::sphere_points(20000, Vector3(0.5, 0.5, 0.5), 0.5);
}
Points region_query()
{
    return test::random_points(3000, 0.0, 0.2, 11); // a corner of the sphere
}

//! Writes the fitted `d` (handles: region_handles()) for the points of region_query() and
//! compares there: equal to the last bit, in fewer bytes.
void expect_region_round_trip_of_fitted(const SpaceDeformation& d)
{
    const Points query = region_query();
    const QueryRegion region = query_region(query);
    const std::string everywhere = write_field(d), here = write_field(d, &region);
    EXPECT_LT(here.size(), everywhere.size() / 4) << d.report().method;
    const std::unique_ptr<SpaceDeformation> restored = read_field(here);
    Points want(query.rows(), 3), got(query.rows(), 3);
    d.evaluate(query, want);
    restored->evaluate(query, got);
    EXPECT_EQ(want, got) << d.report().method;
    EXPECT_EQ(restored->report().num_handles, d.report().num_handles);
    // A point far outside the region needs sources that were not written: an error, never
    // a silently wrong value.
    Points outside(1, 3), value(1, 3);
    outside << 1.0, 1.0, 1.0;
    EXPECT_THROW(restored->evaluate(outside, value), std::logic_error);
}

//! Fits `d` to a smooth field on region_handles(), then expect_region_round_trip_of_fitted.
void expect_region_round_trip(SpaceDeformation& d)
{
    const Points handles = region_handles();
    d.fit(handles, test::smooth_field(handles));
    expect_region_round_trip_of_fitted(d);
}

TEST(FieldIo, idw_written_for_a_region_keeps_its_locally_essential_tree)
{
    IdwDeformation idw;
    expect_region_round_trip(idw);
}

TEST(FieldIo, idw_with_quiet_nodes_written_for_a_region)
{
    // Quiet nodes are opened later (IdwTree); a rank's essential tree must keep their
    // opening radii, or its points would sum other terms than the serial run's.
    IdwDeformation idw;
    const Points handles = region_handles();
    const Points residual = test::residual_like_field(handles, 0.1);
    idw.fit(handles, residual, test::small_values(residual));
    expect_region_round_trip_of_fitted(idw);
}

TEST(FieldIo, idw_quiet_flags_for_another_number_of_handles_are_an_error)
{
    // The flags are the IDW block's last item (the fit report follows the block): a count,
    // then one byte per handle. A file whose count does not match its handles is refused as
    // a file error, not a usage one.
    IdwDeformation idw;
    const Points handles = region_handles();
    const Points residual = test::residual_like_field(handles, 0.1);
    idw.fit(handles, residual, test::small_values(residual));
    const std::string bytes = write_field(idw);
    FieldWriter block;
    idw.write_field(block);
    const std::string body = block.bytes(), report = bytes.substr(body.size());
    ASSERT_EQ(bytes.substr(0, body.size()), body);
    const std::size_t n = std::size_t(handles.rows()), at = body.size() - n - 8;
    std::uint64_t count = 0;
    std::memcpy(&count, body.data() + at, sizeof count);
    ASSERT_EQ(count, n) << "the flags are no longer the block's last item";
    const std::uint64_t fewer = n - 1;
    std::string corrupt = body.substr(0, at);
    corrupt.append(reinterpret_cast<const char*>(&fewer), sizeof fewer);
    corrupt += body.substr(at + 8, n - 1) + report;
    try
    {
        read_field(corrupt);
        ADD_FAILURE() << "read a field with too few quiet flags";
    }
    catch (const IoError& e)
    {
        EXPECT_NE(std::string(e.what()).find("quiet flags"), std::string::npos) << e.what();
    }
}

TEST(FieldIo, greedy_rbf_correction_written_for_a_region)
{
    CorrectedDeformation corrected = corrected_greedy_rbf();
    expect_region_round_trip(corrected);
}

TEST(FieldIo, truncated_or_foreign_bytes_are_errors_and_unfitted_fields_cannot_be_written)
{
    RbfDeformation rbf;
    EXPECT_THROW(write_field(rbf), InvalidInput);
    const Points h = test::sphere_points(50, Vector3::Zero(), 1.0);
    rbf.fit(h, test::smooth_field(h));
    const std::string bytes = write_field(rbf);
    for (std::size_t n : {std::size_t(0), std::size_t(3), bytes.size() / 2, bytes.size() - 1})
        EXPECT_THROW(read_field(bytes.substr(0, n)), IoError) << n << " bytes";
    EXPECT_THROW(read_field(bytes + "x"), IoError);
    std::string foreign = bytes;
    foreign[0] = 9;
    EXPECT_THROW(read_field(foreign), IoError);
}

} // namespace
} // namespace meshmorph
