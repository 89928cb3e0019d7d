// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of the OpenFOAM tokenizer (io/foam_tokenizer.h) and the FoamFile header (io/foam_header.h).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.h"
#include "meshmorph/io/foam_header.h"
#include "meshmorph/io/foam_tokenizer.h"

using namespace meshmorph;
using namespace meshmorph::io;

namespace
{

std::vector<FoamToken> all_tokens(std::string_view text)
{
    FoamTokenizer tok(text, "test");
    std::vector<FoamToken> out;
    for (FoamToken t = tok.next(); !t.is_end(); t = tok.next())
        out.push_back(t);
    return out;
}

// Runs f and returns the ParseError message; fails the test if nothing is thrown.
template <class F> std::string parse_error_of(F f)
{
    try
    {
        f();
    }
    catch (const ParseError& e)
    {
        return e.what();
    }
    ADD_FAILURE() << "expected a ParseError";
    return {};
}

std::string read_file(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

} // namespace

TEST(FoamTokenizer, splits_punctuation_words_and_numbers)
{
    const auto t = all_tokens("a (1 -2.5e-3){ }[x];, List<vector> #include $var \"s\"");
    ASSERT_EQ(t.size(), 16u);
    EXPECT_TRUE(t[0].is_word("a"));
    EXPECT_TRUE(t[1].is_punct('('));
    EXPECT_TRUE(t[2].is_label());
    EXPECT_EQ(t[2].label, 1);
    EXPECT_EQ(t[3].type, TokenType::scalar);
    EXPECT_DOUBLE_EQ(t[3].scalar, -2.5e-3);
    EXPECT_TRUE(t[4].is_punct(')'));
    EXPECT_TRUE(t[5].is_punct('{'));
    EXPECT_TRUE(t[6].is_punct('}'));
    EXPECT_TRUE(t[7].is_punct('['));
    EXPECT_TRUE(t[8].is_word("x"));
    EXPECT_TRUE(t[9].is_punct(']'));
    EXPECT_TRUE(t[10].is_punct(';'));
    EXPECT_TRUE(t[11].is_punct(','));
    EXPECT_TRUE(t[12].is_word("List<vector>"));
    EXPECT_TRUE(t[13].is_word("#include"));
    EXPECT_TRUE(t[14].is_word("$var"));
    EXPECT_TRUE(t[15].is_string());
    EXPECT_EQ(t[15].text, "s");
}

TEST(FoamTokenizer, glued_count_and_bracket_are_two_tokens)
{
    const auto t = all_tokens("4(1 2 3 4) 6{0} 0()");
    ASSERT_EQ(t.size(), 14u);
    EXPECT_TRUE(t[0].is_label());
    EXPECT_EQ(t[0].label, 4);
    EXPECT_TRUE(t[1].is_punct('('));
    EXPECT_EQ(t[5].label, 4);
    EXPECT_TRUE(t[6].is_punct(')'));
    EXPECT_EQ(t[7].label, 6);
    EXPECT_TRUE(t[8].is_punct('{'));
    EXPECT_EQ(t[9].label, 0);
    EXPECT_TRUE(t[10].is_punct('}'));
    EXPECT_EQ(t[11].label, 0);
    EXPECT_TRUE(t[12].is_punct('('));
    EXPECT_TRUE(t[13].is_punct(')'));
}

TEST(FoamTokenizer, numbers_in_all_spellings)
{
    const auto t = all_tokens("0 -7 +3 1e+300 -1.5e-05 .5 -.25 5. 1E15 9223372036854775807 "
                              "99999999999999999999 1e-320");
    ASSERT_EQ(t.size(), 12u);
    EXPECT_EQ(t[0].label, 0);
    EXPECT_EQ(t[1].label, -7);
    EXPECT_EQ(t[2].label, 3);
    EXPECT_DOUBLE_EQ(t[3].scalar, 1e300);
    EXPECT_DOUBLE_EQ(t[4].scalar, -1.5e-05);
    EXPECT_DOUBLE_EQ(t[5].scalar, 0.5);
    EXPECT_DOUBLE_EQ(t[6].scalar, -0.25);
    EXPECT_DOUBLE_EQ(t[7].scalar, 5.0);
    EXPECT_EQ(t[7].type, TokenType::scalar);
    EXPECT_DOUBLE_EQ(t[8].scalar, 1e15);
    EXPECT_EQ(t[9].label, 9223372036854775807LL);
    // An integer beyond int64 becomes a scalar; a denormal is accepted.
    EXPECT_EQ(t[10].type, TokenType::scalar);
    EXPECT_DOUBLE_EQ(t[10].scalar, 1e20);
    EXPECT_EQ(t[11].type, TokenType::scalar);
    EXPECT_GT(t[11].scalar, 0.0);
}

TEST(FoamTokenizer, malformed_number_names_file_and_line)
{
    const std::string msg = parse_error_of([] { all_tokens("a\nb\n1.2.3\n"); });
    EXPECT_NE(msg.find("test:3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("1.2.3"), std::string::npos) << msg;
    EXPECT_NE(parse_error_of([] { all_tokens("1e999"); }).find("test:1:"), std::string::npos);
}

TEST(FoamTokenizer, comments_everywhere_are_skipped_and_lines_counted)
{
    const std::string text = "/* banner\n * line 2\n */ a // tail ( {\n"
                             "b/* inline */c\n"
                             "4/*x*/(1//y\n2)\n"
                             "d";
    FoamTokenizer tok(text, "f");
    FoamToken t = tok.next();
    EXPECT_TRUE(t.is_word("a"));
    EXPECT_EQ(t.line, 3u);
    t = tok.next();
    EXPECT_TRUE(t.is_word("b"));
    EXPECT_EQ(t.line, 4u);
    t = tok.next();
    EXPECT_TRUE(t.is_word("c"));
    EXPECT_EQ(tok.next().label, 4);
    EXPECT_TRUE(tok.next().is_punct('('));
    EXPECT_EQ(tok.next().label, 1);
    t = tok.next();
    EXPECT_EQ(t.label, 2);
    EXPECT_EQ(t.line, 6u);
    EXPECT_TRUE(tok.next().is_punct(')'));
    t = tok.next();
    EXPECT_TRUE(t.is_word("d"));
    EXPECT_EQ(t.line, 7u);
    EXPECT_TRUE(tok.at_end());
}

TEST(FoamTokenizer, word_ends_at_comment_and_quote)
{
    const auto t = all_tokens("abc//x\ndef/*y*/ghi\"s\" a/b");
    ASSERT_EQ(t.size(), 5u);
    EXPECT_EQ(t[0].text, "abc");
    EXPECT_EQ(t[1].text, "def");
    EXPECT_EQ(t[2].text, "ghi");
    EXPECT_TRUE(t[3].is_string());
    EXPECT_EQ(t[4].text, "a/b");
}

TEST(FoamTokenizer, strings_unescape_quotes_and_backslashes)
{
    const auto t = all_tokens(R"x("a \"b\" c\\d" "(walls|bottom)" "x\ty" "")x");
    ASSERT_EQ(t.size(), 4u);
    EXPECT_EQ(t[0].text, "a \"b\" c\\d");
    EXPECT_EQ(t[1].text, "(walls|bottom)");
    EXPECT_EQ(t[2].text, "x\\ty"); // other escapes stay as written
    EXPECT_EQ(t[3].text, "");
}

TEST(FoamTokenizer, variables_with_braces_and_scopes)
{
    const auto t = all_tokens("${FOAM_CASE}/x $:a.b $..c ${a}");
    ASSERT_EQ(t.size(), 5u);
    EXPECT_EQ(t[0].text, "${FOAM_CASE}");
    EXPECT_EQ(t[1].text, "/x");
    EXPECT_EQ(t[2].text, "$:a.b");
    EXPECT_EQ(t[3].text, "$..c");
    EXPECT_EQ(t[4].text, "${a}");
}

TEST(FoamTokenizer, unterminated_string_reports_its_start_line)
{
    const std::string msg = parse_error_of([] { all_tokens("a;\nb \"open\nstill\nopen"); });
    EXPECT_NE(msg.find("test:2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("unterminated string"), std::string::npos) << msg;
}

TEST(FoamTokenizer, unterminated_comment_reports_its_start_line)
{
    const std::string msg = parse_error_of([] { all_tokens("a\n\nb /* never\nclosed\n"); });
    EXPECT_NE(msg.find("test:3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("comment"), std::string::npos) << msg;
}

TEST(FoamTokenizer, peek_does_not_consume)
{
    FoamTokenizer tok("a\n  b", "f");
    EXPECT_TRUE(tok.peek().is_word("a"));
    EXPECT_EQ(tok.offset(), 0u);
    EXPECT_TRUE(tok.next().is_word("a"));
    EXPECT_TRUE(tok.peek().is_word("b"));
    EXPECT_EQ(tok.line(), 1u);
    const FoamToken b = tok.next();
    EXPECT_EQ(b.line, 2u);
    EXPECT_EQ(b.offset, 4u);
    EXPECT_EQ(b.end, 5u);
    EXPECT_TRUE(tok.next().is_end());
}

TEST(FoamTokenizer, expect_reports_what_was_found)
{
    FoamTokenizer tok("\n\nfoo", "constant/polyMesh/faces");
    const std::string msg = parse_error_of([&] { tok.expect('('); });
    EXPECT_EQ(msg, "constant/polyMesh/faces:3: expected '(' but found word 'foo'");
}

TEST(FoamTokenizer, fast_readers_parse_in_place)
{
    FoamTokenizer tok("3 ( 1 -2 /*c*/ 3 ) 2.5 4 (1e-3 -2 3.25) x", "f");
    std::int64_t n = 0;
    ASSERT_TRUE(tok.read_label(n));
    EXPECT_EQ(n, 3);
    std::int64_t v = 0;
    EXPECT_FALSE(tok.read_label(v)); // '(' is not a label and is not consumed
    tok.expect('(');
    std::vector<std::int64_t> got;
    while (tok.read_label(v))
        got.push_back(v);
    EXPECT_EQ(got, (std::vector<std::int64_t>{1, -2, 3}));
    tok.expect(')');
    EXPECT_FALSE(tok.read_label(v)); // 2.5 is a scalar
    double s = 0;
    ASSERT_TRUE(tok.read_scalar(s));
    EXPECT_DOUBLE_EQ(s, 2.5);
    ASSERT_TRUE(tok.read_scalar(s)); // an integer is a valid scalar
    EXPECT_DOUBLE_EQ(s, 4.0);
    double xyz[3];
    tok.read_vector(xyz);
    EXPECT_DOUBLE_EQ(xyz[0], 1e-3);
    EXPECT_DOUBLE_EQ(xyz[1], -2.0);
    EXPECT_DOUBLE_EQ(xyz[2], 3.25);
    EXPECT_FALSE(tok.read_scalar(s));
    EXPECT_TRUE(tok.next().is_word("x"));
}

TEST(FoamTokenizer, read_vector_rejects_wrong_component_count)
{
    FoamTokenizer tok("(1 2)\n", "pts");
    double xyz[3];
    const std::string msg = parse_error_of([&] { tok.read_vector(xyz); });
    EXPECT_NE(msg.find("pts:1:"), std::string::npos) << msg;
    FoamTokenizer tok2("\n(1 2 3 4)", "pts");
    const std::string msg2 = parse_error_of([&] { tok2.read_vector(xyz); });
    EXPECT_NE(msg2.find("pts:2:"), std::string::npos) << msg2;
}

TEST(FoamTokenizer, read_raw_returns_bytes_and_counts_newlines)
{
    std::string text = "2\n(";
    const double values[2] = {1.0, 10.0 / 256.0 * 256.0};
    text.append(reinterpret_cast<const char*>(values), sizeof(values));
    text += ")\nnext";
    // Make sure a newline byte inside the data is counted.
    text[3] = '\n';
    FoamTokenizer tok(text, "b");
    EXPECT_EQ(tok.expect_size(), 2);
    tok.expect('(');
    const std::string_view raw = tok.read_raw(16);
    EXPECT_EQ(raw.size(), 16u);
    EXPECT_EQ(raw[0], '\n');
    EXPECT_EQ(std::memcmp(raw.data() + 1, reinterpret_cast<const char*>(values) + 1, 15), 0);
    tok.expect(')');
    const FoamToken t = tok.next();
    EXPECT_TRUE(t.is_word("next"));
    EXPECT_EQ(t.line, 4u);
    const std::string msg = parse_error_of([&] { tok.read_raw(1); });
    EXPECT_NE(msg.find("b:4:"), std::string::npos) << msg;
}

TEST(FoamTokenizer, negative_list_size_is_rejected)
{
    FoamTokenizer tok("\n-3(", "f");
    const std::string msg = parse_error_of([&] { tok.expect_size("the number of points"); });
    EXPECT_NE(msg.find("f:2:"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------------
// FoamFile header

TEST(FoamHeader, parses_banner_and_all_keys)
{
    const std::string text =
        "/*-----*\\\n| banner |\n\\*-----*/\n"
        "FoamFile\n{\n    version 2.0;\n    format binary;\n"
        "    class vectorField;\n    arch \"LSB;label=64;scalar=32\";\n"
        "    note \"nPoints:8  nCells:1\";\n    location \"constant/polyMesh\";\n"
        "    object points;\n    unknownKey whatever;\n}\n// * * //\nbody";
    FoamTokenizer tok(text, "points");
    ASSERT_TRUE(has_header(tok));
    const FoamHeader h = parse_header(tok);
    EXPECT_EQ(h.line, 4u);
    EXPECT_EQ(h.version, "2.0");
    EXPECT_TRUE(h.is_binary());
    EXPECT_EQ(h.class_name, "vectorField");
    EXPECT_EQ(h.object, "points");
    EXPECT_EQ(h.location, "constant/polyMesh");
    EXPECT_EQ(h.note, "nPoints:8  nCells:1");
    EXPECT_EQ(h.label_bytes, 8);
    EXPECT_EQ(h.scalar_bytes, 4);
    EXPECT_TRUE(tok.next().is_word("body"));
}

TEST(FoamHeader, arch_defaults_and_variants)
{
    const auto parse = [](const std::string& arch)
    {
        std::string text = "FoamFile { format binary; class labelList;";
        if (!arch.empty())
            text += " arch \"" + arch + "\";";
        text += " }";
        FoamTokenizer tok(text, "owner");
        return parse_header(tok);
    };
    FoamHeader h = parse("");
    EXPECT_EQ(h.label_bytes, 4);
    EXPECT_EQ(h.scalar_bytes, 8);
    h = parse("LSB;label=32;scalar=64");
    EXPECT_EQ(h.label_bytes, 4);
    EXPECT_EQ(h.scalar_bytes, 8);
    h = parse("LSB;label=64;scalar=64");
    EXPECT_EQ(h.label_bytes, 8);
    h = parse("LSB;scalar=32");
    EXPECT_EQ(h.label_bytes, 4);
    EXPECT_EQ(h.scalar_bytes, 4);
    EXPECT_NE(parse_error_of([&] { parse("MSB;label=32;scalar=64"); }).find("MSB"),
              std::string::npos);
    EXPECT_NE(parse_error_of([&] { parse("LSB;label=16;scalar=64"); }).find("owner:1:"),
              std::string::npos);
}

TEST(FoamHeader, missing_header_or_keys_are_errors_with_line)
{
    const auto header_of = [](const std::string& text)
    {
        FoamTokenizer tok(text, "constant/polyMesh/points");
        parse_header(tok);
    };
    std::string msg = parse_error_of([&] { header_of("// comment\n\n8((0 0 0))"); });
    EXPECT_NE(msg.find("constant/polyMesh/points:3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("FoamFile"), std::string::npos) << msg;
    msg = parse_error_of([&] { header_of("\nFoamFile\n{\n class vectorField;\n}\n"); });
    EXPECT_NE(msg.find("points:2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("format"), std::string::npos) << msg;
    msg = parse_error_of([&] { header_of("FoamFile\n{\n format ascii;\n}\n"); });
    EXPECT_NE(msg.find("class"), std::string::npos) << msg;
    msg = parse_error_of([&] { header_of("FoamFile\n{\n format text;\n class a;\n}\n"); });
    EXPECT_NE(msg.find("points:3:"), std::string::npos) << msg;
    msg = parse_error_of([&] { header_of("FoamFile\n{\n format ascii;\n class a;\n"); });
    EXPECT_NE(msg.find("points:1:"), std::string::npos) << msg;
    // Dictionaries may omit format and class.
    FoamTokenizer tok("FoamFile { version 2.0; object controlDict; }", "controlDict");
    EXPECT_NO_THROW(parse_header(tok, false));
}

TEST(FoamHeader, format_header_reproduces_openfoam_output)
{
    // Files written by OpenFOAM v1912 (blockMesh + topoSet + foamFormatConvert).
    for (const char* name :
         {"boundary_cavity", "owner_binary", "zones_binary/faceZones", "zones_ascii/cellZones"})
    {
        const std::string text = read_file(test::data_path(std::string("dict/") + name));
        ASSERT_FALSE(text.empty()) << name;
        FoamTokenizer tok(text, name);
        const FoamHeader h = parse_header(tok);
        const std::string formatted = format_header(h);
        EXPECT_EQ(text.substr(0, formatted.size()), formatted) << name;
        ASSERT_GE(text.size(), format_footer().size());
        EXPECT_EQ(text.substr(text.size() - format_footer().size()), format_footer()) << name;
    }
}

TEST(FoamHeader, format_header_with_a_framed_banner)
{
    // The header checkMeshQuality writes on its sets (formerly written by hand in app/).
    FoamHeader h;
    h.class_name = "faceSet";
    h.location = "0";
    h.object = "nonOrthoFaces";
    const std::string text =
        format_header(h, framed_banner("Written by meshMorph 1.2.3 (checkMeshQuality)"));
    EXPECT_EQ(
        text,
        "/*--------------------------------*- C++ -*----------------------------------*\\\n"
        "  Written by meshMorph 1.2.3 (checkMeshQuality)\n"
        "\\*---------------------------------------------------------------------------*/\n"
        "FoamFile\n{\n"
        "    version     2.0;\n"
        "    format      ascii;\n"
        "    class       faceSet;\n"
        "    location    \"0\";\n"
        "    object      nonOrthoFaces;\n"
        "}\n"
        "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n\n");
    // The default banner is OpenFOAM's, which shares the frame.
    EXPECT_EQ(format_header(h),
              std::string(openfoam_banner()) + text.substr(text.find("FoamFile")));
    EXPECT_EQ(openfoam_banner().substr(0, 80), text.substr(0, 80));
    FoamTokenizer tok(text, "nonOrthoFaces");
    EXPECT_EQ(parse_header(tok).object, "nonOrthoFaces");
}

TEST(FoamHeader, format_header_writes_arch_only_for_binary)
{
    FoamHeader h;
    h.class_name = "vectorField";
    h.object = "points";
    h.location = "1/polyMesh";
    std::string text = format_header(h);
    EXPECT_EQ(text.find("arch"), std::string::npos);
    h.format = FoamFormat::binary;
    h.label_bytes = 8;
    text = format_header(h);
    EXPECT_NE(text.find("    arch        \"LSB;label=64;scalar=64\";\n"), std::string::npos);
    FoamTokenizer tok(text, "points");
    const FoamHeader back = parse_header(tok);
    EXPECT_EQ(back.label_bytes, 8);
    EXPECT_EQ(back.location, "1/polyMesh");
    EXPECT_TRUE(tok.at_end());
}
