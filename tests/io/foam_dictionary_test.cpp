// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of OpenFOAM dictionaries (io/foam_dictionary.h).
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <zlib.h>

#include "helpers.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/foam_dictionary.h"
#include "meshmorph/io/foam_lists.h"

using namespace meshmorph;
using namespace meshmorph::io;
namespace fs = std::filesystem;

namespace
{

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
    catch (const std::exception& e)
    {
        ADD_FAILURE() << "expected a ParseError, got: " << e.what();
        return {};
    }
    ADD_FAILURE() << "expected a ParseError";
    return {};
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

// Include files served from memory.
ParseOptions memory_files(std::map<std::string, std::string> files)
{
    ParseOptions o;
    o.read_file = [files](const fs::path& p) -> std::optional<std::string>
    {
        const auto it = files.find(p.lexically_normal().string());
        if (it == files.end())
            return std::nullopt;
        return it->second;
    };
    return o;
}

std::string binary_block(const void* data, std::size_t bytes, std::size_t n)
{
    std::string s = "\n" + std::to_string(n) + "\n(";
    s.append(static_cast<const char*>(data), bytes);
    s += ")";
    return s;
}

} // namespace

TEST(FoamDictionary, typed_getters_on_nested_dictionaries)
{
    const std::string text = "scale 0.001;\n"
                             "nIter 25;\n"
                             "big 5000000000;\n"
                             "name wing;\n"
                             "title \"a b\";\n"
                             "on1 yes; on2 on; on3 true; off1 no; off2 off; off3 false; off4 0;\n"
                             "origin (1 -2 3.5);\n"
                             "weights 3(0.5 1 2e-3);\n"
                             "ids (4 5 6);\n"
                             "names 2(top bottom);\n"
                             "handles ((0 0 0) (1 1 1));\n"
                             "boundary\n{\n    wing\n    {\n        type fixedValue;\n"
                             "        value (0 0 0.05);\n    }\n}\n";
    const FoamDictionary d = parse_dictionary(text, "system/morphDict");
    EXPECT_DOUBLE_EQ(d.get<double>("scale"), 0.001);
    EXPECT_DOUBLE_EQ(d.get<double>("nIter"), 25.0); // an integer is a valid scalar
    EXPECT_EQ(d.get<std::int64_t>("nIter"), 25);
    EXPECT_EQ(d.get<Index>("nIter"), 25);
    EXPECT_EQ(d.get<std::int64_t>("big"), 5000000000LL);
    EXPECT_TRUE(contains(parse_error_of([&] { d.get<std::int32_t>("big"); }), "32 bits"));
    EXPECT_EQ(d.get<std::string>("name"), "wing");
    EXPECT_EQ(d.get<std::string>("title"), "a b");
    for (const char* k : {"on1", "on2", "on3"})
        EXPECT_TRUE(d.get<bool>(k)) << k;
    for (const char* k : {"off1", "off2", "off3", "off4"})
        EXPECT_FALSE(d.get<bool>(k)) << k;
    EXPECT_EQ(d.get<Vector3>("origin"), Vector3(1, -2, 3.5));
    EXPECT_EQ(d.get<std::vector<double>>("weights"), (std::vector<double>{0.5, 1, 2e-3}));
    EXPECT_EQ(d.get<std::vector<std::int64_t>>("ids"), (std::vector<std::int64_t>{4, 5, 6}));
    EXPECT_EQ(d.get<std::vector<std::int32_t>>("ids"), (std::vector<std::int32_t>{4, 5, 6}));
    EXPECT_EQ(d.get<std::vector<std::string>>("names"),
              (std::vector<std::string>{"top", "bottom"}));
    const auto handles = d.get<std::vector<Vector3>>("handles");
    ASSERT_EQ(handles.size(), 2u);
    EXPECT_EQ(handles[1], Vector3(1, 1, 1));

    EXPECT_TRUE(d.found("boundary"));
    EXPECT_TRUE(d.is_dict("boundary"));
    EXPECT_FALSE(d.is_dict("scale"));
    EXPECT_FALSE(d.found("nothing"));
    const FoamDictionary& wing = d.sub_dict("boundary").sub_dict("wing");
    EXPECT_EQ(wing.scope(), "boundary.wing");
    EXPECT_EQ(wing.line(), 15u);
    EXPECT_EQ(wing.end_line(), 18u);
    EXPECT_EQ(wing.get<std::string>("type"), "fixedValue");
    EXPECT_EQ(wing.entry_line("value"), 17u);
    EXPECT_EQ(wing.path(), "system/morphDict");
    EXPECT_DOUBLE_EQ(wing.get_or<double>("relax", 0.7), 0.7);
    EXPECT_EQ(wing.get_or<std::string>("type", "x"), "fixedValue");
    EXPECT_EQ(wing.get_or("type", "x"), "fixedValue");
    EXPECT_EQ(wing.get_or("kind", "rbf"), "rbf");
    EXPECT_EQ(wing.get_or("n", 3), 3);
    EXPECT_EQ(d.keys().front(), "scale");
    EXPECT_EQ(d.keys().back(), "boundary");
    EXPECT_EQ(d.size(), 18u);
}

TEST(FoamDictionary, undefined_keyword_names_file_line_and_scope)
{
    const std::string text = "FoamFile { version 2.0; format ascii; class dictionary; }\n"
                             "a 1;\n"
                             "boundary\n{\n    wing\n    {\n        type fixedValue;\n    }\n}\n";
    const FoamDictionary d = parse_dictionary(text, "system/morphDict");
    const FoamDictionary& wing = d.sub_dict("boundary").sub_dict("wing");
    EXPECT_EQ(parse_error_of([&] { wing.get<Vector3>("vector"); }),
              "system/morphDict:6: keyword 'vector' is undefined in dictionary 'boundary.wing'");
    EXPECT_EQ(parse_error_of([&] { d.get<double>("b"); }),
              "system/morphDict:1: keyword 'b' is undefined in dictionary 'morphDict'");
    EXPECT_EQ(parse_error_of([&] { d.sub_dict("a"); }),
              "system/morphDict:2: keyword 'a' in dictionary 'morphDict': expected a "
              "sub-dictionary '{ ... }' but found a value");
}

TEST(FoamDictionary, conversion_errors_name_file_line_and_keyword)
{
    const std::string text = "\n"
                             "count 2.5;\n"
                             "flag maybe;\n"
                             "v (1 2);\n"
                             "w (1 2 3) extra;\n"
                             "list 3(1 2);\n"
                             "sub { }\n";
    const FoamDictionary d = parse_dictionary(text, "dict");
    std::string m = parse_error_of([&] { d.get<std::int64_t>("count"); });
    EXPECT_TRUE(contains(m, "dict:2: keyword 'count'")) << m;
    m = parse_error_of([&] { d.get<bool>("flag"); });
    EXPECT_TRUE(contains(m, "dict:3: keyword 'flag'")) << m;
    m = parse_error_of([&] { d.get<Vector3>("v"); });
    EXPECT_TRUE(contains(m, "dict:4:")) << m;
    m = parse_error_of([&] { d.get<Vector3>("w"); });
    EXPECT_TRUE(contains(m, "dict:5:") && contains(m, "extra")) << m;
    m = parse_error_of([&] { d.get<std::vector<double>>("list"); });
    EXPECT_TRUE(contains(m, "dict:6:") && contains(m, "3")) << m;
    m = parse_error_of([&] { d.get<double>("sub"); });
    EXPECT_TRUE(contains(m, "dict:7:") && contains(m, "sub-dictionary")) << m;
}

TEST(FoamDictionary, regex_keys_exact_match_wins_then_last_regex)
{
    const std::string text = "\".*\" { type any; }\n"
                             "\"(walls|bottom)\" { type wallish; }\n"
                             "\"wal.*\" { type wal; }\n"
                             "bottom { type exact; }\n";
    const FoamDictionary d = parse_dictionary(text, "f");
    EXPECT_EQ(d.sub_dict("bottom").get<std::string>("type"), "exact");
    EXPECT_EQ(d.sub_dict("walls").get<std::string>("type"), "wal"); // last written wins
    EXPECT_EQ(d.sub_dict("top").get<std::string>("type"), "any");
    EXPECT_TRUE(d.find("(walls|bottom)") != nullptr);
    EXPECT_FALSE(d.find("wallsX") == nullptr); // ".*" matches anything
    EXPECT_TRUE(d.entries()[1].is_regex());
    EXPECT_EQ(d.entries()[1].keyword(), "(walls|bottom)");
    // Whole-match semantics: "wal.*" does not match "xwall".
    const FoamDictionary e = parse_dictionary("\"wal.*\" 1;", "f");
    EXPECT_FALSE(e.found("xwall"));
    EXPECT_TRUE(e.found("wall"));
    EXPECT_TRUE(
        contains(parse_error_of([] { parse_dictionary("\n\"(unclosed\" 1;", "f"); }), "f:2:"));
}

TEST(FoamDictionary, duplicate_keys_merge_recursively_by_default)
{
    const std::string text = "a 1;\n"
                             "s { x 1; y 2; t { p 1; } }\n"
                             "a 2;\n"
                             "s { y 3; z 4; t { q 2; } }\n";
    const FoamDictionary d = parse_dictionary(text, "f");
    EXPECT_EQ(d.size(), 2u);
    EXPECT_EQ(d.get<int>("a"), 2);
    EXPECT_EQ(d.entry("a").line(), 3u);
    const FoamDictionary& s = d.sub_dict("s");
    EXPECT_EQ(s.keys(), (std::vector<std::string>{"x", "y", "t", "z"}));
    EXPECT_EQ(s.get<int>("y"), 3);
    EXPECT_EQ(s.sub_dict("t").keys(), (std::vector<std::string>{"p", "q"}));
    // A value replacing a dictionary (and vice versa) replaces it.
    const FoamDictionary e = parse_dictionary("s { a 1; }\ns 5;\n", "f");
    EXPECT_EQ(e.get<int>("s"), 5);
}

TEST(FoamDictionary, input_modes)
{
    FoamDictionary d = parse_dictionary("#inputMode overwrite\ns { a 1; }\ns { b 2; }\n", "f");
    EXPECT_FALSE(d.sub_dict("s").found("a"));
    EXPECT_TRUE(d.sub_dict("s").found("b"));
    d = parse_dictionary("#inputMode protect\na 1;\na 2;\n#inputMode merge\nb 1;\nb 2;", "f");
    EXPECT_EQ(d.get<int>("a"), 1);
    EXPECT_EQ(d.get<int>("b"), 2);
    {
        log::CaptureScope capture;
        d = parse_dictionary("#inputMode warn\na 1;\na 2;\n", "f");
        EXPECT_EQ(d.get<int>("a"), 1);
        EXPECT_TRUE(contains(capture.text(), "f:3:")) << capture.text();
    }
    const std::string m =
        parse_error_of([] { parse_dictionary("#inputMode error\na 1;\n\na 2;\n", "f"); });
    EXPECT_TRUE(contains(m, "f:4:") && contains(m, "duplicate")) << m;
    EXPECT_TRUE(
        contains(parse_error_of([] { parse_dictionary("\n#inputMode bogus\n", "f"); }), "f:2:"));
}

TEST(FoamDictionary, include_relative_to_including_file_on_disk)
{
    const fs::path file = test::data_path("dict/include_case/system/morphDict");
    const FoamDictionary d = read_dictionary(file);
    ASSERT_TRUE(d.header().has_value());
    EXPECT_EQ(d.header()->object, "morphDict");
    EXPECT_DOUBLE_EQ(d.get<double>("tolerance"), 1e-8);
    EXPECT_EQ(d.get<std::string>("method"), "rbf");
    EXPECT_DOUBLE_EQ(d.get<double>("nu"), 1.5e-05); // via <constant>/
    EXPECT_FALSE(d.found("FoamFile"));              // included headers are not entries
    const FoamDictionary& b = d.sub_dict("boundary");
    EXPECT_EQ(b.keys(), (std::vector<std::string>{"wing", "inlet"}));
    const FoamDictionary& wing = b.sub_dict("wing");
    EXPECT_EQ(wing.scope(), "boundary.wing");
    EXPECT_EQ(wing.get<Vector3>("vector"), Vector3(0, 0, 0.05));
    // Entries from an included file name that file and line.
    EXPECT_TRUE(contains(wing.entry("vector").path(), "common/wingPatch"));
    EXPECT_EQ(wing.entry("vector").line(), 4u);
    const std::string m = parse_error_of([&] { wing.get<double>("vector"); });
    EXPECT_TRUE(contains(m, "wingPatch:4:")) << m;
}

TEST(FoamDictionary, missing_include_is_an_error_naming_the_directive_line)
{
    const fs::path file = test::data_path("dict/include_case/system/brokenInclude");
    const std::string m = parse_error_of([&] { read_dictionary(file); });
    EXPECT_TRUE(contains(m, "brokenInclude:4:")) << m;
    EXPECT_TRUE(contains(m, "notThere")) << m;
}

TEST(FoamDictionary, include_from_memory_with_env_and_case_paths)
{
    ::setenv("MESHMORPH_TEST_INC", "/data/inc", 1);
    ParseOptions o = memory_files({{"/case/system/a", "x 1;\n#include \"sub/b\""},
                                   {"/case/system/sub/b", "y 2;"},
                                   {"/data/inc/c", "z 3;"},
                                   {"/case/constant/d", "w 4;"},
                                   {"/case/system/e", "v 5;"}});
    const std::string text = "#include \"a\"\n#include \"$MESHMORPH_TEST_INC/c\"\n"
                             "#include \"${MESHMORPH_TEST_INC}/c\"\n"
                             "#include \"<case>/constant/d\"\n#include \"<system>/e\"\n"
                             "#sinclude \"nothing\"\n";
    const FoamDictionary d = parse_dictionary(text, "/case/system/top", o);
    EXPECT_EQ(d.keys(), (std::vector<std::string>{"x", "y", "z", "w", "v"}));
    // An explicit case directory overrides the one derived from the path.
    o.case_dir = "/case";
    EXPECT_EQ(parse_dictionary("#include \"<constant>/d\"", "/elsewhere/f", o).get<int>("w"), 4);
    const std::string m = parse_error_of(
        [&] {
            parse_dictionary("\n#include \"$MESHMORPH_UNDEFINED_VAR_X/c\"", "/case/system/top", o);
        });
    EXPECT_TRUE(contains(m, "top:2:")) << m;
}

TEST(FoamDictionary, include_cycle_is_an_error)
{
    ParseOptions o = memory_files({{"/c/system/a", "#include \"a\""}});
    const std::string m =
        parse_error_of([&] { parse_dictionary("#include \"a\"", "/c/system/a", o); });
    EXPECT_TRUE(contains(m, "nesting")) << m;
}

TEST(FoamDictionary, remove_directive)
{
    const FoamDictionary d =
        parse_dictionary("a 1; b 2; c 3; d1 4; d2 5;\n#remove a\n#remove (b c)\n#remove \"d.*\"\n"
                         "e 6;",
                         "f");
    EXPECT_EQ(d.keys(), (std::vector<std::string>{"e"}));
}

TEST(FoamDictionary, variable_substitution_and_scoping)
{
    const std::string text = "top 1;\n"
                             "vel (1 0 0);\n"
                             "a { b 2; c { d 3; } }\n"
                             "inlet { type fixedValue; value $vel; }\n"
                             "copy $a;\n"
                             "s1 $a.b;\n"
                             "s2 $a.c.d;\n"
                             "s3 ${top};\n"
                             "outer\n{\n    x 10;\n    inner\n    {\n        x 20;\n"
                             "        p $..x;\n        q $x;\n        r $:a.b;\n"
                             "        t $top;\n        u $.x;\n    }\n}\n"
                             "merged { $a e 5; }\n";
    const FoamDictionary d = parse_dictionary(text, "f");
    EXPECT_EQ(d.sub_dict("inlet").get<Vector3>("value"), Vector3(1, 0, 0));
    EXPECT_EQ(d.sub_dict("inlet").entry("value").source_text(), "$vel");
    ASSERT_TRUE(d.is_dict("copy"));
    EXPECT_EQ(d.sub_dict("copy").get<int>("b"), 2);
    EXPECT_EQ(d.sub_dict("copy").sub_dict("c").scope(), "copy.c");
    EXPECT_EQ(d.get<int>("s1"), 2);
    EXPECT_EQ(d.get<int>("s2"), 3);
    EXPECT_EQ(d.get<int>("s3"), 1);
    const FoamDictionary& inner = d.sub_dict("outer").sub_dict("inner");
    EXPECT_EQ(inner.get<int>("p"), 10);
    EXPECT_EQ(inner.get<int>("q"), 20);
    EXPECT_EQ(inner.get<int>("r"), 2);
    EXPECT_EQ(inner.get<int>("t"), 1); // found in an enclosing scope
    EXPECT_EQ(inner.get<int>("u"), 20);
    const FoamDictionary& merged = d.sub_dict("merged");
    EXPECT_EQ(merged.keys(), (std::vector<std::string>{"b", "c", "e"}));
    EXPECT_EQ(merged.sub_dict("c").scope(), "merged.c");

    const std::string m =
        parse_error_of([] { parse_dictionary("a 1;\n\nb $nothingLikeThis;", "f"); });
    EXPECT_TRUE(contains(m, "f:3:") && contains(m, "$nothingLikeThis")) << m;
}

TEST(FoamDictionary, slash_scoping_of_openfoam_v1912)
{
    // channel395DFSEM's controlDict: `timeStart ${/timeStart};` inside functions.
    const std::string text = "top 1;\n"
                             "a { b 2; c { d 3; } }\n"
                             "outer\n{\n    x 10;\n    inner\n    {\n        x 20;\n"
                             "        root ${/top};\n        path $/a/c/d;\n"
                             "        parent $../x;\n        mixed ${/a/b};\n    }\n}\n";
    const FoamDictionary d = parse_dictionary(text, "f");
    const FoamDictionary& inner = d.sub_dict("outer").sub_dict("inner");
    EXPECT_EQ(inner.get<int>("root"), 1);
    EXPECT_EQ(inner.get<int>("path"), 3);
    EXPECT_EQ(inner.get<int>("parent"), 10);
    EXPECT_EQ(inner.get<int>("mixed"), 2);
    EXPECT_THROW(parse_dictionary("x { y $../../../z; }\n", "f"), ParseError);
}

TEST(FoamDictionary, referenced_variables_are_the_top_level_helpers)
{
    const FoamDictionary d = parse_dictionary("height 0.04;\nlift $height;\nspan 2;\nx { y 1; }\n"
                                              "b { v (0 0 $lift); w ${/span}; u $:x.y; }\n"
                                              "unused 3;\n",
                                              "f");
    EXPECT_EQ(d.referenced_variables(), (std::vector<std::string>{"height", "lift", "span", "x"}));
}

TEST(FoamDictionary, code_directives_are_rejected_with_file_and_line)
{
    for (const char* directive : {"#calc", "#eval", "#codeStream"})
    {
        const std::string value_form = std::string("a 1;\n\nb ") + directive + " \"$a * 2\";\n";
        std::string m = parse_error_of([&] { parse_dictionary(value_form, "system/dict"); });
        EXPECT_TRUE(contains(m, "system/dict:3:") && contains(m, directive)) << m;
        const std::string keyword_form = std::string("\n") + directive + " { code #{ x #}; }\n";
        m = parse_error_of([&] { parse_dictionary(keyword_form, "system/dict"); });
        EXPECT_TRUE(contains(m, "system/dict:2:") && contains(m, directive)) << m;
    }
    const std::string m =
        parse_error_of([] { parse_dictionary("\n#includeEtc \"caseDicts/x\"\n", "system/dict"); });
    EXPECT_TRUE(contains(m, "system/dict:2:") && contains(m, "#includeEtc")) << m;
}

TEST(FoamDictionary, lists_uniform_nested_and_unsized)
{
    const FoamDictionary d = parse_dictionary("u 4{2.5};\nuv 2{(1 2 3)};\nn ((0 0 0) (1 1 1));\n"
                                              "e 0();\nw (a \"b c\" d);\n"
                                              "dims [0 1 -1 0 0 0 0];\nl2 2((1 2) (3 4));\n",
                                              "f");
    EXPECT_EQ(d.get<std::vector<double>>("u"), std::vector<double>(4, 2.5));
    EXPECT_EQ(d.get<std::vector<Vector3>>("uv"), std::vector<Vector3>(2, Vector3(1, 2, 3)));
    EXPECT_EQ(d.get<std::vector<Vector3>>("n").size(), 2u);
    EXPECT_TRUE(d.get<std::vector<std::int64_t>>("e").empty());
    EXPECT_EQ(d.get<std::vector<std::string>>("w"), (std::vector<std::string>{"a", "b c", "d"}));
    EXPECT_EQ(d.entry("dims").tokens().size(), 9u);
    EXPECT_EQ(d.entry("l2").source_text(), "2((1 2) (3 4))");
}

// Found by fuzz/dictionary_fuzzer.cpp: `N{v}` with N = 2e9 allocated 16-48 GB.
TEST(FoamDictionary, huge_uniform_lists_are_errors_not_allocations)
{
    const std::string compound =
        parse_error_of([] { parse_dictionary("\na List<vector> 2000000000{(0 0 0)};\n", "d"); });
    EXPECT_TRUE(contains(compound, "d:2:") && contains(compound, "2000000000") &&
                contains(compound, "exceeds the plausible size 16777216"))
        << compound;
    const FoamDictionary d = parse_dictionary("b 2000000000{1.5};\nc 16777216{1};\n", "d");
    const std::string plain = parse_error_of([&] { d.get<std::vector<double>>("b"); });
    EXPECT_TRUE(contains(plain, "d:1:") && contains(plain, "keyword 'b'") &&
                contains(plain, "exceeds the plausible size 16777216"))
        << plain;
    EXPECT_EQ(d.get<std::vector<double>>("c").size(), 16777216u);
}

// Stack overflows found by fuzzing (sub-dictionaries and std::regex recurse): a clear error.
TEST(FoamDictionary, deep_nesting_and_long_regex_keys_are_errors_not_crashes)
{
    std::string nested = "FoamFile { format ascii; class dictionary; }\n";
    for (int i = 0; i < 100000; ++i)
        nested += "a {\n";
    const std::string deep = parse_error_of([&] { parse_dictionary(nested, "system/deep"); });
    EXPECT_TRUE(contains(deep, "system/deep:130:") &&
                contains(deep, "is nested deeper than 128 levels"))
        << deep.substr(0, 200);
    std::string ok;
    for (int i = 0; i < 128; ++i)
        ok += "a { ";
    ok += "b 1;" + std::string(128, '}');
    EXPECT_NO_THROW(parse_dictionary(ok, "system/ok"));

    const std::string long_key = "x 1;\n\"" + std::string(20000, 'a') + "\" 1;\n";
    const std::string key = parse_error_of([&] { parse_dictionary(long_key, "system/re"); });
    EXPECT_TRUE(contains(key, "system/re:2:") &&
                contains(key, "regular expression keyword of 20000 characters is longer than "
                              "the 1024 supported"))
        << key.substr(0, 200);
    const std::string removed = parse_error_of(
        [&] { parse_dictionary("#remove \"" + std::string(1025, 'a') + "\"\n", "system/rm"); });
    EXPECT_TRUE(contains(removed, "system/rm:1:") &&
                contains(removed, "after '#remove' of 1025 characters"))
        << removed.substr(0, 200);
    const std::string longest = "\"(" + std::string(1022, 'a') + ")\" 1;\n";
    EXPECT_TRUE(parse_dictionary(longest, "system/re").found(std::string(1022, 'a')));
}

// Found by fuzz/mesh_file_fuzzer.cpp: a back-reference of 21 digits overflowed a long inside
// std::regex (UBSan), as would a count {n}; nested counts make std::regex copy an atom
// millions of times.
TEST(FoamDictionary, regex_keys_with_huge_repetition_counts_are_errors)
{
    for (const std::string key :
         {"a{6666666666666666666}", "a{66666666666666666666,6}", "(a{100}){100}", "x{0,20000}"})
    {
        const std::string m =
            parse_error_of([&] { parse_dictionary("\n\"" + key + "\" 1;\n", "system/re"); });
        EXPECT_TRUE(contains(m, "system/re:2:") && contains(m, key) &&
                    contains(m, "repeats more than 10000 times in all"))
            << m;
    }
    const std::string backref = parse_error_of(
        [] { parse_dictionary("\"(a)\\\\666666666666666666666\" 1;", "system/re"); });
    EXPECT_TRUE(contains(backref, "system/re:1:") &&
                contains(backref, "has a back-reference number of more than 4 digits"))
        << backref;
    const FoamDictionary d = parse_dictionary(
        "\"a{2,3}b{5}\" 1;\n\"c\\\\{99999\\\\}\" 2;\n\"[{]9999999}\" 3;\n", "system/re");
    EXPECT_TRUE(d.found("aabbbbb"));
    EXPECT_TRUE(d.found("c{99999}"));
    EXPECT_TRUE(d.found("{9999999}"));
}

// Found by fuzz/dictionary_fuzzer.cpp: a key like "(a*)*b" took exponential time to match a
// long keyword (std::regex's backtracking matcher); back-references, which the polynomial
// matcher cannot do, are a clear error.
TEST(FoamDictionary, regex_keys_match_in_polynomial_time)
{
    const FoamDictionary d = parse_dictionary("\"(a*)*b\" 1;\n\"(x+x+)+y\" 2;\n", "system/re");
    EXPECT_EQ(d.find(std::string(5000, 'a')), nullptr);
    EXPECT_EQ(d.find(std::string(5000, 'x')), nullptr);
    ASSERT_NE(d.find("aaab"), nullptr);
    EXPECT_EQ(d.find("xxxy")->get<int>(), 2);
    const std::string backref =
        parse_error_of([] { parse_dictionary("\n\"(a)\\\\1\" 1;\n", "system/re"); });
    EXPECT_TRUE(contains(backref, "system/re:2:") &&
                contains(backref, "invalid regular expression keyword \"(a)\\1\""))
        << backref;
}

TEST(FoamDictionary, source_text_is_verbatim)
{
    const std::string text = "walls\n{\n    type            wall;\n"
                             "    inGroups        1 ( wall ) ;\n"
                             "    transform  /* c */ noOrdering;\n}\n";
    const FoamDictionary d = parse_dictionary(text, "f");
    const FoamDictionary& w = d.sub_dict("walls");
    EXPECT_EQ(w.entry("inGroups").source_text(), "1 ( wall )");
    EXPECT_EQ(w.entry("transform").source_text(), "noOrdering");
    EXPECT_EQ(d.entry("walls").source_text(), text.substr(6, text.size() - 7));
    EXPECT_EQ(w.get<std::vector<std::string>>("inGroups"), (std::vector<std::string>{"wall"}));
}

TEST(FoamDictionary, ascii_compound_lists)
{
    const std::string text = "a List<label> 4(1 2 3 4);\n"
                             "b List<scalar> 3(0.5 1e-3 2);\n"
                             "c List<vector> 2((0 0 0) (1 2 3));\n"
                             "d List<bool> 4{0};\n"
                             "e List<word> 2(wall patch);\n"
                             "f List<label> \n12\n(\n0\n1\n2\n3\n4\n5\n6\n7\n8\n9\n10\n11\n)\n;\n"
                             "g List<label> 0();\n"
                             "value nonuniform List<vector> 1((1 1 1));\n";
    const FoamDictionary d = parse_dictionary(text, "f");
    const FoamValueToken& a = d.entry("a").tokens().at(0);
    ASSERT_TRUE(a.is_compound());
    EXPECT_EQ(a.compound->labels, (std::vector<std::int64_t>{1, 2, 3, 4}));
    EXPECT_EQ(d.get<std::vector<std::int64_t>>("a"), (std::vector<std::int64_t>{1, 2, 3, 4}));
    EXPECT_EQ(d.get<std::vector<double>>("b"), (std::vector<double>{0.5, 1e-3, 2}));
    EXPECT_EQ(d.get<std::vector<Vector3>>("c")[1], Vector3(1, 2, 3));
    EXPECT_EQ(d.get<std::vector<std::int64_t>>("d"), std::vector<std::int64_t>(4, 0));
    EXPECT_EQ(d.get<std::vector<std::string>>("e"), (std::vector<std::string>{"wall", "patch"}));
    EXPECT_EQ(d.get<std::vector<std::int64_t>>("f").size(), 12u);
    EXPECT_TRUE(d.get<std::vector<std::int64_t>>("g").empty());
    const FoamEntry& v = d.entry("value");
    ASSERT_EQ(v.tokens().size(), 2u);
    EXPECT_TRUE(v.tokens()[0].is_word("nonuniform"));
    EXPECT_EQ(v.get<std::vector<Vector3>>(1), std::vector<Vector3>(1, Vector3(1, 1, 1)));
    EXPECT_EQ(v.tokens()[1].compound->size(), 1u);
    // Size mismatches name the list's line.
    std::string m = parse_error_of([] { parse_dictionary("\nx List<label> 3(1 2);", "f"); });
    EXPECT_TRUE(contains(m, "f:2:") && contains(m, "3")) << m;
    m = parse_error_of([] { parse_dictionary("x List<label> 1(1 2);", "f"); });
    EXPECT_TRUE(contains(m, "f:1:")) << m;
    m = parse_error_of([] { parse_dictionary("x List<label> 2(1 b);", "f"); });
    EXPECT_TRUE(contains(m, "f:1:") && contains(m, "'b'")) << m;
}

TEST(FoamDictionary, binary_compound_lists)
{
    const std::int32_t l32[4] = {7, -1, 10, 2147483647}; // 10 is a newline byte
    const std::int64_t l64[2] = {5000000000LL, 3};
    const double s64[2] = {0.1, -2.5};
    const float s32[3] = {1.5f, 2.5f, -0.25f};
    const double v64[6] = {0, 0, 1, 1, 2, 3};
    const char b[4] = {0, 1, 1, 0};
    std::string text = "FoamFile { version 2.0; format binary; class dictionary; "
                       "arch \"LSB;label=32;scalar=64\"; }\n";
    text += "a List<label> " + binary_block(l32, sizeof l32, 4) + ";\n";
    text += "s List<scalar> " + binary_block(s64, sizeof s64, 2) + ";\n";
    text += "v List<vector> " + binary_block(v64, sizeof v64, 2) + ";\n";
    text += "f List<bool> " + binary_block(b, sizeof b, 4) + ";\n";
    text += "e List<label> 0;\n";
    text += "w List<word> 2(x y);\n";
    text += "after (1 2 3);\n";
    const FoamDictionary d = parse_dictionary(text, "field");
    EXPECT_EQ(d.get<std::vector<std::int64_t>>("a"),
              (std::vector<std::int64_t>{7, -1, 10, 2147483647}));
    EXPECT_EQ(d.get<std::vector<double>>("s"), (std::vector<double>{0.1, -2.5}));
    EXPECT_EQ(d.get<std::vector<Vector3>>("v")[1], Vector3(1, 2, 3));
    EXPECT_EQ(d.get<std::vector<std::int64_t>>("f"), (std::vector<std::int64_t>{0, 1, 1, 0}));
    EXPECT_TRUE(d.get<std::vector<std::int64_t>>("e").empty());
    EXPECT_EQ(d.get<std::vector<std::string>>("w"), (std::vector<std::string>{"x", "y"}));
    EXPECT_EQ(d.get<Vector3>("after"), Vector3(1, 2, 3));
    EXPECT_EQ(d.entry("after").line(), 17u); // the newline byte inside binary data counts

    // 64-bit labels and 32-bit scalars.
    std::string t2 = "FoamFile { format binary; class dictionary; "
                     "arch \"LSB;label=64;scalar=32\"; }\n";
    t2 += "a List<label> " + binary_block(l64, sizeof l64, 2) + ";\n";
    t2 += "s List<scalar> " + binary_block(s32, sizeof s32, 3) + ";\n";
    const FoamDictionary d2 = parse_dictionary(t2, "field");
    EXPECT_EQ(d2.get<std::vector<std::int64_t>>("a"), (std::vector<std::int64_t>{5000000000LL, 3}));
    EXPECT_EQ(d2.get<std::vector<double>>("s"), (std::vector<double>{1.5, 2.5, -0.25}));

    // Truncated binary data names the file and the list's line.
    std::string t3 = "FoamFile { format binary; class dictionary; }\n\n";
    t3 += "a List<label> \n1000\n(" + std::string(12, '\0');
    const std::string m = parse_error_of([&] { parse_dictionary(t3, "field"); });
    EXPECT_TRUE(contains(m, "field:4:") && contains(m, "1000")) << m;
}

TEST(FoamDictionary, compound_lists_follow_the_list_readers_rules)
{
    // An empty binary list is a bare `0` (or `0()`) for every contiguous kind.
    std::string text = "FoamFile { format binary; class dictionary; }\n";
    for (const char* kind : {"label", "scalar", "vector", "bool"})
        text += std::string("a_") + kind + " List<" + kind + "> 0;\nb_" + kind + " List<" + kind +
                "> 0();\n";
    text += "w List<word> 0();\n";
    const FoamDictionary d = parse_dictionary(text, "field");
    for (const char* kind : {"label", "scalar", "vector", "bool"})
        for (const char* prefix : {"a_", "b_"})
        {
            const FoamEntry& e = d.entry(prefix + std::string(kind));
            ASSERT_TRUE(e.tokens().at(0).is_compound()) << kind;
            EXPECT_EQ(e.tokens()[0].compound->size(), 0u) << prefix << kind;
        }
    EXPECT_TRUE(d.get<std::vector<std::string>>("w").empty());

    // A malformed compound gives the polyMesh list reader's message, naming the entry.
    const std::string body = "\n3(1 2)";
    const std::string from_dict =
        parse_error_of([&] { parse_dictionary("cellLabels List<label>" + body + ";", "zones"); });
    const std::string from_list = parse_error_of(
        [&]
        {
            FoamTokenizer tok(body, "zones");
            ListReadOptions o;
            o.what = "cellLabels";
            read_label_list(tok, FoamHeader{}, o);
        });
    EXPECT_EQ(from_dict, from_list);
    EXPECT_TRUE(contains(from_dict, "zones:2:") && contains(from_dict, "'cellLabels'"))
        << from_dict;
    // Bools: 0/1 and switch words; other numbers are errors naming file, line and entry.
    const FoamDictionary b = parse_dictionary("f List<bool> 4(0 1 true off);", "zones");
    EXPECT_EQ(b.get<std::vector<std::int64_t>>("f"), (std::vector<std::int64_t>{0, 1, 1, 0}));
    const std::string m =
        parse_error_of([] { parse_dictionary("\nflipMap List<bool> 2(0 3);", "zones"); });
    EXPECT_TRUE(contains(m, "zones:2:") && contains(m, "'flipMap'") && contains(m, "not a bool"))
        << m;
}

TEST(FoamDictionary, truncated_input_errors_point_at_the_open_construct)
{
    std::string m =
        parse_error_of([] { read_dictionary(test::data_path("dict/unterminated_dict")); });
    EXPECT_TRUE(contains(m, "unterminated_dict:3:") && contains(m, "outer")) << m;
    m = parse_error_of([] { parse_dictionary("a 1;\nb 2", "f"); });
    EXPECT_TRUE(contains(m, "f:2:") && contains(m, "';'")) << m;
    m = parse_error_of([] { parse_dictionary("a 1;\nb (1 2\n(3 4)\n", "f"); });
    EXPECT_TRUE(contains(m, "f:2:") && contains(m, "unterminated")) << m;
    m = parse_error_of([] { parse_dictionary("a { b 1 }\n", "f"); });
    EXPECT_TRUE(contains(m, "f:1:") && contains(m, "';'")) << m;
    m = parse_error_of([] { parse_dictionary("a 1;\n}\n", "f"); });
    EXPECT_TRUE(contains(m, "f:2:")) << m;
    m = parse_error_of([] { parse_dictionary("a (1 2));\n", "f"); });
    EXPECT_TRUE(contains(m, "f:1:")) << m;
}

TEST(FoamDictionary, read_dictionary_reads_gzip_and_reports_missing_files)
{
    const fs::path dir = test::scratch_dir("foam_dictionary_gz");
    const std::string text = "FoamFile { version 2.0; format ascii; class dictionary; }\nx 42;\n";
    gzFile f = gzopen((dir / "controlDict.gz").c_str(), "wb");
    ASSERT_NE(f, nullptr);
    gzwrite(f, text.data(), static_cast<unsigned>(text.size()));
    gzclose(f);
    EXPECT_EQ(read_dictionary(dir / "controlDict").get<int>("x"), 42);
    EXPECT_EQ(read_dictionary(dir / "controlDict.gz").get<int>("x"), 42);
    try
    {
        read_dictionary(dir / "missingDict");
        ADD_FAILURE() << "expected IoError";
    }
    catch (const IoError& e)
    {
        EXPECT_TRUE(contains(e.what(), "missingDict"));
    }
}

TEST(FoamDictionary, parse_header_then_body_from_one_tokenizer)
{
    const std::string text = "FoamFile { version 2.0; format ascii; class dictionary; }\n"
                             "a 1;\nb { c 2; }\n";
    FoamTokenizer tok(text, "d");
    const FoamHeader h = parse_header(tok);
    EXPECT_EQ(h.class_name, "dictionary");
    const FoamDictionary d = parse_dictionary_body(tok);
    EXPECT_EQ(d.keys(), (std::vector<std::string>{"a", "b"}));
    FoamTokenizer tok2("{ x 1; } rest", "d");
    const FoamDictionary block = parse_dictionary_block(tok2, "zone");
    EXPECT_EQ(block.get<int>("x"), 1);
    EXPECT_EQ(block.scope(), "zone");
    EXPECT_TRUE(tok2.next().is_word("rest"));
}

TEST(FoamDictionary, copies_are_deep)
{
    FoamDictionary a = parse_dictionary("s { t { x 1; } }", "f");
    FoamDictionary b = a;
    FoamEntry e;
    b = parse_dictionary("s { t { x 2; } }", "f");
    EXPECT_EQ(a.sub_dict("s").sub_dict("t").get<int>("x"), 1);
    EXPECT_EQ(b.sub_dict("s").sub_dict("t").get<int>("x"), 2);
    a.add(b.entries()[0]); // merge
    EXPECT_EQ(a.sub_dict("s").sub_dict("t").get<int>("x"), 2);
    EXPECT_TRUE(a.remove("s"));
    EXPECT_TRUE(a.empty());
}

// Real OpenFOAM dictionaries from the tutorials: every file either parses, or (when it uses a
// directive meshmorph rejects) fails with a ParseError naming file and line.
TEST(FoamDictionary, parses_openfoam_tutorial_dictionaries)
{
    std::vector<fs::path> roots = {"/usr/share/openfoam/tutorials",
                                   "/usr/share/doc/openfoam-examples/examples"};
    std::vector<fs::path> files;
    const std::vector<std::string> names = {
        "blockMeshDict", "snappyHexMeshDict", "controlDict", "fvSchemes",
        "fvSolution",    "decomposeParDict",  "topoSetDict", "surfaceFeatureExtractDict"};
    for (const fs::path& root : roots)
    {
        std::error_code ec;
        if (!fs::is_directory(root, ec))
            continue;
        for (fs::recursive_directory_iterator it(root, ec), end; it != end; it.increment(ec))
        {
            if (ec)
                break;
            if (!it->is_regular_file(ec))
                continue;
            std::string name = it->path().filename().string();
            if (name.size() > 3 && name.ends_with(".gz"))
                name.resize(name.size() - 3);
            if (std::find(names.begin(), names.end(), name) != names.end())
                files.push_back(it->path());
        }
    }
    if (files.empty())
        GTEST_SKIP() << "OpenFOAM tutorials not installed: real-dictionary parsing skipped";
    log::CaptureScope quiet; // tutorials trigger a few keyword-substitution warnings
    std::sort(files.begin(), files.end());
    const std::regex rejected("#(includeEtc|includeFunc|includeModel|calc|codeStream|eval)\\b");
    std::size_t parsed = 0, rejected_count = 0;
    for (const fs::path& file : files)
    {
        fs::path name = file;
        if (name.extension() == ".gz")
            name.replace_extension();
        std::string text;
        {
            gzFile g = gzopen(file.c_str(), "rb");
            ASSERT_NE(g, nullptr) << file;
            char buf[65536];
            int n = 0;
            while ((n = gzread(g, buf, sizeof buf)) > 0)
                text.append(buf, static_cast<std::size_t>(n));
            gzclose(g);
        }
        // Only the top file is checked for rejected directives; includes may hold more.
        const bool uses_rejected = std::regex_search(text, rejected);
        try
        {
            const FoamDictionary d = read_dictionary(name);
            ++parsed;
            EXPECT_FALSE(uses_rejected) << file << " parsed although it uses a rejected directive";
            if (name.filename() == "controlDict")
            {
                EXPECT_TRUE(d.found("application") || d.found("endTime")) << file;
            }
            if (name.filename() == "blockMeshDict")
            {
                EXPECT_TRUE(d.found("vertices") || d.found("geometry") || d.found("blocks"))
                    << file;
            }
        }
        catch (const ParseError& e)
        {
            // Rejected directives may also come from an included file. Some tutorials
            // include files their scripts generate, or use variables only OpenFOAM's
            // applications set (FOAM_EXECUTABLE); those errors are legitimate too.
            const std::string what = e.what();
            const bool legitimate = std::regex_search(what, rejected) ||
                                    what.find("cannot find include file") != std::string::npos ||
                                    (what.find("undefined variable") != std::string::npos &&
                                     what.find("FOAM_") != std::string::npos);
            EXPECT_TRUE(uses_rejected || legitimate) << what;
            EXPECT_GT(e.line(), 0u) << e.what();
            ++rejected_count;
        }
        catch (const IoError& e)
        {
            ADD_FAILURE() << file << ": " << e.what();
        }
    }
    EXPECT_GT(parsed, files.size() / 2) << "parsed " << parsed << " of " << files.size();
    RecordProperty("parsed", static_cast<int>(parsed));
    RecordProperty("rejected", static_cast<int>(rejected_count));
}

// The motorBike snappyHexMeshDict, checked against values read off the tutorial file. Its
// `#include "meshQualityDict"` pulls in `#includeEtc`, so that one file is served from memory.
TEST(FoamDictionary, reads_motorbike_snappy_hex_mesh_dict)
{
    const fs::path dir =
        "/usr/share/doc/openfoam-examples/examples/incompressible/simpleFoam/motorBike/system";
    std::error_code ec;
    if (!fs::exists(dir / "snappyHexMeshDict.gz", ec))
        GTEST_SKIP() << "OpenFOAM tutorials not installed: motorBike snappyHexMeshDict skipped";
    std::string text;
    {
        gzFile g = gzopen((dir / "snappyHexMeshDict.gz").c_str(), "rb");
        ASSERT_NE(g, nullptr);
        char buf[65536];
        int n = 0;
        while ((n = gzread(g, buf, sizeof buf)) > 0)
            text.append(buf, static_cast<std::size_t>(n));
        gzclose(g);
    }
    ParseOptions o;
    o.read_file = [](const fs::path& p) -> std::optional<std::string>
    {
        if (p.filename() == "meshQualityDict")
            return std::string("maxNonOrtho 65;\n");
        return std::nullopt;
    };
    const FoamDictionary d = parse_dictionary(text, (dir / "snappyHexMeshDict").string(), o);
    EXPECT_TRUE(d.get<bool>("castellatedMesh"));
    const FoamDictionary& geometry = d.sub_dict("geometry");
    EXPECT_EQ(geometry.sub_dict("motorBike.obj").get<std::string>("name"), "motorBike");
    EXPECT_EQ(geometry.sub_dict("refinementBox").get<Vector3>("min"), Vector3(-1.0, -0.7, 0.0));
    EXPECT_EQ(geometry.sub_dict("refinementBox").get<Vector3>("max"), Vector3(8.0, 0.7, 2.5));
    const FoamDictionary& cast = d.sub_dict("castellatedMeshControls");
    EXPECT_EQ(cast.get<std::int64_t>("maxGlobalCells"), 2000000);
    EXPECT_EQ(cast.get<Index>("nCellsBetweenLevels"), 3);
    EXPECT_EQ(cast.get<Vector3>("locationInMesh"), Vector3(3.0001, 3.0001, 0.43));
    const FoamDictionary& bike = cast.sub_dict("refinementSurfaces").sub_dict("motorBike");
    EXPECT_EQ(bike.get<std::vector<std::int64_t>>("level"), (std::vector<std::int64_t>{5, 6}));
    EXPECT_EQ(bike.sub_dict("patchInfo").get<std::vector<std::string>>("inGroups"),
              (std::vector<std::string>{"motorBikeGroup"}));
    EXPECT_EQ(bike.sub_dict("patchInfo").scope(),
              "castellatedMeshControls.refinementSurfaces.motorBike.patchInfo");
    // Regex keys select per-patch layer settings.
    const FoamDictionary& layers = d.sub_dict("addLayersControls").sub_dict("layers");
    EXPECT_EQ(layers.sub_dict("motorBike_frt-fairing:001%1").get<int>("nSurfaceLayers"), 1);
    EXPECT_FALSE(layers.found("upperWall"));
    EXPECT_EQ(d.sub_dict("meshQualityControls").get<int>("maxNonOrtho"), 65);
}

// Random single-byte edits, deletions and truncations of valid dictionaries (ASCII and
// binary) only ever produce meshmorph errors: no crash, no foreign exception type.
TEST(FoamDictionary, mutated_input_fails_cleanly)
{
    const std::int32_t labels[5] = {0, 1, 2, 3, 4};
    const double scalars[3] = {0.5, 1.5, 2.5};
    std::string binary = "FoamFile { version 2.0; format binary; class dictionary; }\n"
                         "a List<label> " +
                         binary_block(labels, sizeof labels, 5) + ";\nb List<vector> " +
                         binary_block(scalars, sizeof scalars, 1) + ";\nc 0;\n";
    const std::vector<std::string> inputs = {
        "FoamFile { version 2.0; format ascii; class dictionary; object d; }\n"
        "a 1; b (1 2 3); c { d 4{0.5}; \"(x|y)\" { e List<label> 3(1 2 3); } }\n"
        "f $a; g $c.d; h { $c } i ${a}; j List<vector> 2((0 0 0) (1 1 1));\n"
        "/* comment */ k \"str\\\"ing\"; // tail\n#remove a\n#inputMode merge\n"
        "l List<bool> 3{1}; m List<word> 2(w1 w2); n [0 1 0 0 0 0 0];\n",
        binary};
    log::CaptureScope quiet; // mutated `$var` keywords warn
    std::mt19937 rng(12345);
    const std::string alphabet = "(){}[];\"/*$#\n \\0a.-:<>";
    std::size_t errors = 0;
    for (const std::string& input : inputs)
    {
        for (int trial = 0; trial < 3000; ++trial)
        {
            std::string text = input;
            const std::size_t pos = rng() % text.size();
            switch (rng() % 3)
            {
            case 0:
                text[pos] = alphabet[rng() % alphabet.size()];
                break;
            case 1:
                text.erase(pos, 1);
                break;
            default:
                text.resize(pos);
                break;
            }
            try
            {
                parse_dictionary(text, "mutated", memory_files({}));
            }
            catch (const Error&)
            {
                ++errors;
            }
            catch (const std::exception& e)
            {
                ADD_FAILURE() << "foreign exception " << e.what() << " for input:\n" << text;
            }
        }
    }
    EXPECT_GT(errors, 0u);
}
