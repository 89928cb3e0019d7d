// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of io/foam_lists.h: every ASCII and binary list form, size checks, hostile input,
// and that the parallel ASCII path gives exactly the serial result.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "io_test_util.h"
#include "meshmorph/io/foam_lists.h"

using namespace meshmorph;
using namespace meshmorph::io;

namespace
{

FoamHeader ascii_header()
{
    return FoamHeader{};
}

FoamHeader binary_header(int label_bytes = 4, int scalar_bytes = 8)
{
    FoamHeader h;
    h.format = FoamFormat::binary;
    h.label_bytes = label_bytes;
    h.scalar_bytes = scalar_bytes;
    return h;
}

std::vector<Index> labels(const std::string& text, const FoamHeader& h = ascii_header(),
                          ListReadOptions options = {})
{
    FoamTokenizer tok(text, "test/owner");
    std::vector<Index> v = read_label_list(tok, h, options);
    expect_end_of_file(tok, "owner");
    return v;
}

template <class T> std::string raw_block(const std::vector<T>& values)
{
    std::string s = "\n" + std::to_string(values.size()) + "\n(";
    s.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    return s + ")";
}

} // namespace

TEST(FoamLists, reads_every_ascii_label_list_form)
{
    EXPECT_EQ(labels("3(1 2 3)"), (std::vector<Index>{1, 2, 3}));
    EXPECT_EQ(labels("3\n(\n1\n2\n3\n)\n"), (std::vector<Index>{1, 2, 3}));
    EXPECT_EQ(labels("4{7}"), (std::vector<Index>{7, 7, 7, 7}));
    EXPECT_EQ(labels("(5 6)"), (std::vector<Index>{5, 6}));
    EXPECT_EQ(labels("0()"), std::vector<Index>{});
    EXPECT_EQ(labels("// comment\n2 /* c */ ( 1 // x\n 2 )"), (std::vector<Index>{1, 2}));
    EXPECT_EQ(labels("2(-1 +4)"), (std::vector<Index>{-1, 4}));
}

TEST(FoamLists, reads_binary_labels_of_32_and_64_bits)
{
    const std::vector<std::int32_t> v32{0, 1, -1, 123456789};
    EXPECT_EQ(labels(raw_block(v32), binary_header(4)), (std::vector<Index>{0, 1, -1, 123456789}));
    const std::vector<std::int64_t> v64{0, 1, -1, 123456789};
    EXPECT_EQ(labels(raw_block(v64), binary_header(8)), (std::vector<Index>{0, 1, -1, 123456789}));
    // Empty binary list: `0` alone, and `0()`.
    EXPECT_TRUE(labels("\n0\n", binary_header()).empty());
    EXPECT_TRUE(labels("0()", binary_header()).empty());
    // Raw bytes that look like brackets and newlines are data, not syntax.
    const std::vector<std::int32_t> tricky{')' | ('\n' << 8), '(' | ('{' << 8), '/' | ('/' << 8)};
    EXPECT_EQ(labels(raw_block(tricky), binary_header()),
              std::vector<Index>(tricky.begin(), tricky.end()));
}

TEST(FoamLists, rejects_64_bit_labels_that_do_not_fit)
{
    if (sizeof(Index) == 8)
        GTEST_SKIP() << "64-bit build: every int64 label fits";
    const std::vector<std::int64_t> v{1, std::int64_t(1) << 40};
    const std::string msg = test::error_of([&] { labels(raw_block(v), binary_header(8)); });
    EXPECT_NE(msg.find("test/owner"), std::string::npos) << msg;
    EXPECT_NE(msg.find("byte offset"), std::string::npos) << msg;
}

TEST(FoamLists, reads_scalars_and_converts_single_precision)
{
    FoamTokenizer a("3(1 -2.5e-3 1e+300)", "s");
    EXPECT_EQ(read_scalar_list(a, ascii_header()), (std::vector<double>{1, -2.5e-3, 1e300}));
    const std::vector<float> f{0.5f, -1.25f, 3.0f};
    const std::string fb = raw_block(f);
    FoamTokenizer b(fb, "s");
    EXPECT_EQ(read_scalar_list(b, binary_header(4, 4)), (std::vector<double>{0.5, -1.25, 3.0}));
}

TEST(FoamLists, reads_vectors_ascii_binary_and_uniform)
{
    FoamTokenizer a("2((0 1 2) (3.5 -4 5e-1))", "p");
    const Points p = read_vector_list(a, ascii_header());
    ASSERT_EQ(p.rows(), 2);
    EXPECT_EQ(p(1, 0), 3.5);
    EXPECT_EQ(p(1, 2), 0.5);

    FoamTokenizer u("3{(1 2 3)}", "p");
    const Points q = read_vector_list(u, ascii_header());
    ASSERT_EQ(q.rows(), 3);
    EXPECT_EQ(q(2, 1), 2.0);

    const std::vector<double> d{1, 2, 3, 4, 5, 6};
    const std::string db = raw_block(d).replace(1, 1, "2"); // the count is 2 vectors
    FoamTokenizer b(db, "p");
    const Points r = read_vector_list(b, binary_header());
    ASSERT_EQ(r.rows(), 2);
    EXPECT_EQ(r(1, 2), 6.0);

    const std::vector<float> f{1, 2, 3};
    const std::string fc = raw_block(f).replace(1, 1, "1");
    FoamTokenizer c(fc, "p");
    const Points s = read_vector_list(c, binary_header(4, 4));
    EXPECT_EQ(s(0, 2), 3.0);
}

TEST(FoamLists, reads_int64_labels_beyond_the_build_label_range)
{
    const std::vector<std::int64_t> v{5000000000LL, -3};
    const std::string block = raw_block(v);
    FoamTokenizer b(block, "d");
    EXPECT_EQ(read_int64_list(b, binary_header(8)), v);
    FoamTokenizer a("2(5000000000 -3)", "d");
    EXPECT_EQ(read_int64_list(a, ascii_header()), v);
    FoamTokenizer u("3{-7}", "d");
    EXPECT_EQ(read_int64_list(u, ascii_header()), (std::vector<std::int64_t>(3, -7)));
    // The int64 range, to its ends; one past it is an error naming the line, never a value
    // wrapped around modulo 2^64 (the fast ASCII kernel once read 19 digits unchecked).
    FoamTokenizer ends("2(9223372036854775807 -9223372036854775808)", "d");
    EXPECT_EQ(read_int64_list(ends, ascii_header()),
              (std::vector<std::int64_t>{INT64_MAX, INT64_MIN}));
    for (const char* text :
         {"3(1 9999999999999999999 2)", "1(9223372036854775808)", "(1 9999999999999999999 2)"})
    {
        FoamTokenizer big(text, "d");
        EXPECT_THROW(read_int64_list(big, ascii_header()), ParseError) << text;
    }
    // 32-bit labels widen.
    const std::vector<std::int32_t> narrow{-1, 2147483647};
    const std::string nb = raw_block(narrow);
    FoamTokenizer n(nb, "d");
    EXPECT_EQ(read_int64_list(n, binary_header(4)), (std::vector<std::int64_t>{-1, 2147483647}));
}

TEST(FoamLists, reads_bool_lists_ascii_words_and_binary_bytes)
{
    FoamTokenizer a("5(0 1 true off yes)", "flipMap");
    EXPECT_EQ(read_bool_list(a, ascii_header()), (std::vector<std::uint8_t>{0, 1, 1, 0, 1}));
    FoamTokenizer u("4{0}", "flipMap");
    EXPECT_EQ(read_bool_list(u, ascii_header()), std::vector<std::uint8_t>(4, 0));
    const std::vector<char> bytes{0, 1, 7, 0};
    const std::string block = raw_block(bytes);
    FoamTokenizer b(block, "flipMap");
    EXPECT_EQ(read_bool_list(b, binary_header()), (std::vector<std::uint8_t>{0, 1, 1, 0}));
    FoamTokenizer empty("\n0\n", "flipMap");
    EXPECT_TRUE(read_bool_list(empty, binary_header()).empty());

    FoamTokenizer two("\n3(0 2 1)", "test/flipMap");
    std::string m = test::error_of([&] { read_bool_list(two, ascii_header()); });
    EXPECT_NE(m.find("test/flipMap:2"), std::string::npos) << m;
    EXPECT_NE(m.find("not a bool"), std::string::npos) << m;
    FoamTokenizer word("2(0 maybe)", "test/flipMap");
    m = test::error_of([&] { read_bool_list(word, ascii_header()); });
    EXPECT_NE(m.find("test/flipMap:1"), std::string::npos) << m;
    EXPECT_NE(m.find("'maybe'"), std::string::npos) << m;
}

TEST(FoamLists, word_lists_are_ascii_tokens_even_in_binary_files)
{
    for (const FoamHeader& h : {ascii_header(), binary_header()})
    {
        FoamTokenizer a("3(wall \"my patch\" empty)", "inGroups");
        EXPECT_EQ(read_word_list(a, h), (std::vector<std::string>{"wall", "my patch", "empty"}));
        FoamTokenizer u("2{wall}", "inGroups");
        EXPECT_EQ(read_word_list(u, h), (std::vector<std::string>{"wall", "wall"}));
        FoamTokenizer e("0()", "inGroups");
        EXPECT_TRUE(read_word_list(e, h).empty());
    }
    FoamTokenizer bad("2(wall 3)", "test/boundary");
    const std::string m = test::error_of([&] { read_word_list(bad, ascii_header()); });
    EXPECT_NE(m.find("test/boundary:1"), std::string::npos) << m;
    EXPECT_NE(m.find("expected a word"), std::string::npos) << m;
}

TEST(FoamLists, reads_face_lists_in_all_four_forms)
{
    CompactList expected;
    expected.push_back({0, 1, 2, 3});
    expected.push_back({4, 5, 6});
    expected.push_back({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11});

    FoamTokenizer a(
        "3\n(\n4(0 1 2 3)\n3(4 5 6)\n\n12\n(\n0\n1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n11\n)\n\n)", "f");
    EXPECT_EQ(read_face_list(a, ascii_header(), false), expected);

    FoamTokenizer b("4(0 4 7 19) 19(0 1 2 3 4 5 6 0 1 2 3 4 5 6 7 8 9 10 11)", "f");
    EXPECT_EQ(read_face_list(b, ascii_header(), true), expected);

    const std::vector<std::int32_t> offsets(expected.offsets.begin(), expected.offsets.end());
    const std::vector<std::int32_t> flat(expected.values.begin(), expected.values.end());
    const std::string compact = raw_block(offsets) + raw_block(flat);
    FoamTokenizer c(compact, "f");
    EXPECT_EQ(read_face_list(c, binary_header(), true), expected);

    // Binary faceList: ASCII skeleton, each face a binary block.
    std::string text = "\n3\n(";
    for (Index f = 0; f < expected.size(); ++f)
    {
        const std::vector<std::int32_t> face(expected[f].begin(), expected[f].end());
        text += raw_block(face);
    }
    text += "\n)";
    FoamTokenizer d(text, "f");
    EXPECT_EQ(read_face_list(d, binary_header(), false), expected);
}

TEST(FoamLists, rejects_bad_compact_offsets)
{
    FoamTokenizer a("3(1 4 7) 7(0 1 2 3 4 5 6)", "test/faces");
    const std::string first = test::error_of([&] { read_face_list(a, ascii_header(), true); });
    EXPECT_NE(first.find("test/faces:1"), std::string::npos) << first;
    FoamTokenizer b("3(0 4 3) 3(0 1 2)", "test/faces");
    const std::string decreasing = test::error_of([&] { read_face_list(b, ascii_header(), true); });
    EXPECT_NE(decreasing.find("decrease"), std::string::npos) << decreasing;
    FoamTokenizer c("3(0 3 6) 5(0 1 2 3 4)", "test/faces");
    const std::string size = test::error_of([&] { read_face_list(c, ascii_header(), true); });
    EXPECT_NE(size.find("expected 6"), std::string::npos) << size;
}

TEST(FoamLists, size_mismatch_errors_name_file_and_line)
{
    const std::string fewer = test::error_of([] { labels("3\n(\n1\n2\n)"); });
    EXPECT_NE(fewer.find("test/owner:5"), std::string::npos) << fewer;
    EXPECT_NE(fewer.find("ends after 2"), std::string::npos) << fewer;
    const std::string more = test::error_of([] { labels("2\n(\n1\n2\n3\n)"); });
    EXPECT_NE(more.find("test/owner:5"), std::string::npos) << more;
    const std::string expected = test::error_of(
        []
        {
            ListReadOptions o;
            o.expected_size = 4;
            labels("\n\n3(1 2 3)", ascii_header(), o);
        });
    EXPECT_NE(expected.find("test/owner:3"), std::string::npos) << expected;
    const std::string word = test::error_of([] { labels("3(1 two 3)"); });
    EXPECT_NE(word.find("test/owner:1"), std::string::npos) << word;
    const std::string scalar = test::error_of([] { labels("2(1 2.5)"); });
    EXPECT_NE(scalar.find("test/owner:1"), std::string::npos) << scalar;
    const std::string trailing = test::error_of([] { labels("2(1 2) 3"); });
    EXPECT_NE(trailing.find("test/owner:1"), std::string::npos) << trailing;
}

TEST(FoamLists, hostile_counts_fail_before_allocating)
{
    // Each of these would need terabytes if the count were trusted.
    for (const std::string text :
         {"1000000000000\n(\n1\n2\n)", "1000000000000{0}", "9223372036854775807(1)", "-5(1)"})
    {
        const std::string msg = test::error_of([&] { labels(text); });
        EXPECT_NE(msg.find("test/owner:1"), std::string::npos) << text << " -> " << msg;
    }
    const std::string binary =
        test::error_of([] { labels("\n1000000000000\n(abcd)", binary_header()); });
    EXPECT_NE(binary.find("byte offset"), std::string::npos) << binary;
    // A face size that passes the list-level checks but not its own brackets, in a list
    // big enough for the parallel path.
    std::string many = "\n100000\n(\n2000000000(1 2 3)\n";
    for (int i = 1; i < 100000; ++i)
        many += "3(0 1 2)\n";
    many += ")\n";
    FoamTokenizer big(many, "test/faces");
    ListReadOptions chunked;
    chunked.force_parallel = true;
    const std::string big_face =
        test::error_of([&] { read_face_list(big, ascii_header(), false, chunked); });
    EXPECT_NE(big_face.find("test/faces:4"), std::string::npos) << big_face;
    FoamTokenizer faces("2(1000000000000(1 2 3) 3(0 1 2))", "test/faces");
    const std::string face = test::error_of([&] { read_face_list(faces, ascii_header(), false); });
    EXPECT_NE(face.find("test/faces:1"), std::string::npos) << face;
}

TEST(FoamLists, truncated_and_ascii_under_binary_header_are_errors)
{
    const std::vector<std::int32_t> v{1, 2, 3, 4};
    const std::string block = raw_block(v);
    const std::string truncated =
        test::error_of([&] { labels(block.substr(0, block.size() - 6), binary_header()); });
    EXPECT_NE(truncated.find("test/owner"), std::string::npos) << truncated;
    const std::string ascii_body =
        test::error_of([] { labels("\n4\n(\n1\n2\n3\n4\n)\n", binary_header()); });
    EXPECT_NE(ascii_body.find("byte offset"), std::string::npos) << ascii_body;
    const std::string wrong_size = test::error_of([&] { labels(raw_block(v), binary_header(8)); });
    EXPECT_NE(wrong_size.find("test/owner"), std::string::npos) << wrong_size;
}

TEST(FoamLists, chunked_reading_finds_the_end_of_a_list_followed_by_others)
{
    // The last ')' of the text closes the second list, not the first: the chunked path must
    // not take it for the end of the first one.
    std::string text = "\n2000\n(\n";
    for (int i = 0; i < 2000; ++i)
        text += std::to_string(i) + "\n";
    text += ")\nnext 3(7 8 9)\n";
    FoamTokenizer tok(text, "test/zones");
    ListReadOptions chunked;
    chunked.force_parallel = true;
    const std::vector<std::int64_t> first = read_int64_list(tok, ascii_header(), chunked);
    ASSERT_EQ(first.size(), 2000u);
    EXPECT_EQ(first[1999], 1999);
    EXPECT_TRUE(tok.next().is_word("next"));
    EXPECT_EQ(read_label_list(tok, ascii_header(), chunked), (std::vector<Index>{7, 8, 9}));
}

TEST(FoamLists, parallel_ascii_parsing_matches_serial)
{
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> coord(-1e3, 1e3);
    std::uniform_int_distribution<int> label(0, 1 << 20);
    const std::size_t n = 60000; // several MB of text: the parallel path is taken
    Points points(static_cast<Eigen::Index>(n), 3);
    for (Eigen::Index i = 0; i < points.rows(); ++i)
        points.row(i) = Eigen::RowVector3d(coord(rng), coord(rng), coord(rng));
    std::vector<Index> owner(n);
    for (Index& o : owner)
        o = label(rng);
    CompactList faces;
    for (std::size_t f = 0; f < n; ++f)
    {
        std::vector<Index> face(3 + f % 11);
        for (Index& v : face)
            v = label(rng);
        faces.push_back(std::span<const Index>(face));
    }
    std::string points_text, owner_text, faces_text;
    append_vector_list(points_text, points, FoamFormat::ascii);
    append_label_list(owner_text, owner, FoamFormat::ascii);
    append_face_list(faces_text, faces, FoamFormat::ascii);
    ASSERT_GT(faces_text.size(), std::size_t(1) << 20);

    for (bool parallel : {false, true})
    {
        ListReadOptions o;
        o.parallel = parallel;
        o.force_parallel = parallel;
        FoamTokenizer tp(points_text, "p");
        EXPECT_EQ(read_vector_list(tp, ascii_header(), o), points) << parallel;
        EXPECT_TRUE(tp.at_end());
        FoamTokenizer to(owner_text, "o");
        EXPECT_EQ(read_label_list(to, ascii_header(), o), owner) << parallel;
        FoamTokenizer tf(faces_text, "f");
        EXPECT_EQ(read_face_list(tf, ascii_header(), false, o), faces) << parallel;
        EXPECT_TRUE(tf.at_end());
    }

    // An error deep inside a large list still names the right line in both modes.
    std::string broken = owner_text;
    const std::size_t at = broken.find('\n', broken.size() / 2);
    broken.insert(at + 1, "x");
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(broken.begin(), broken.begin() + at + 1, '\n'));
    for (bool parallel : {false, true})
    {
        ListReadOptions o;
        o.parallel = parallel;
        o.force_parallel = parallel;
        FoamTokenizer t(broken, "test/owner");
        const std::string msg = test::error_of([&] { read_label_list(t, ascii_header(), o); });
        EXPECT_NE(msg.find("test/owner:" + std::to_string(line) + ":"), std::string::npos)
            << parallel << " " << msg;
    }
}

TEST(FoamLists, writers_follow_openfoam_layout_and_read_back)
{
    std::string s;
    append_label_list(s, {0, 0, 0, 0, 0, 0}, FoamFormat::ascii);
    EXPECT_EQ(s, "6{0}");
    s.clear();
    append_label_list(s, {1, 2, 3}, FoamFormat::ascii);
    EXPECT_EQ(s, "3(1 2 3)");
    s.clear();
    append_label_list(s, {}, FoamFormat::ascii);
    EXPECT_EQ(s, "0()");
    s.clear();
    append_label_list(s, {}, FoamFormat::binary);
    EXPECT_EQ(s, "\n0\n");
    s.clear();
    append_label_list(s, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, FoamFormat::ascii);
    EXPECT_EQ(s, "\n11\n(\n0\n1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n)\n");

    // 17 significant digits reproduce every double exactly.
    Points p(3, 3);
    p << 0.1, 1.0 / 3.0, -2.5e-300, 1e300, 123456789.123456789, -0.0, 5e-324,
        1.7976931348623157e308, 0.30000000000000004;
    s.clear();
    append_vector_list(s, p, FoamFormat::ascii);
    EXPECT_EQ(s.substr(0, 2), "3(");
    FoamTokenizer t(s, "p");
    const Points q = read_vector_list(t, ascii_header());
    ASSERT_EQ(q.rows(), 3);
    EXPECT_EQ(std::memcmp(p.data(), q.data(), sizeof(double) * 9), 0);
}
