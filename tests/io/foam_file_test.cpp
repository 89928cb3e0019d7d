// SPDX-License-Identifier: GPL-3.0-or-later
// Tests of io/foam_file.h: plain/gzip reads, the X / X.gz rule, atomic writes.
#include <gtest/gtest.h>

#include <string>

#include "io_test_util.h"
#include "meshmorph/core/log.h"
#include "meshmorph/io/foam_file.h"
#include "meshmorph/io/temp_file.h"

#include <csignal>

#include <sys/wait.h>
#include <unistd.h>

using namespace meshmorph;
using namespace meshmorph::io;
namespace fs = std::filesystem;

TEST(FoamFile, reads_plain_and_gz_transparently)
{
    const fs::path dir = test::scratch_dir("foam_file_plain_gz");
    std::string text = "FoamFile { format ascii; }\n";
    for (int i = 0; i < 1000; ++i)
        text += std::to_string(i) + "\n";
    test::write_bytes(dir / "a", text);
    test::write_bytes(dir / "b.gz", gzip_compress(text));

    const FileBuffer a = read_foam_file(dir / "a");
    EXPECT_EQ(a.data, text);
    EXPECT_FALSE(a.is_compressed);
    EXPECT_EQ(a.path, dir / "a");

    const FileBuffer b = read_foam_file(dir / "b"); // finds b.gz
    EXPECT_EQ(b.data, text);
    EXPECT_TRUE(b.is_compressed);
    EXPECT_EQ(b.path, dir / "b.gz");
    EXPECT_EQ(read_foam_file(dir / "b.gz").data, text);

    EXPECT_TRUE(foam_file_exists(dir / "a"));
    EXPECT_TRUE(foam_file_exists(dir / "b"));
    EXPECT_FALSE(foam_file_exists(dir / "c"));
}

TEST(FoamFile, plain_name_wins_and_warns_when_both_exist)
{
    const fs::path dir = test::scratch_dir("foam_file_both");
    test::write_bytes(dir / "points", "plain");
    test::write_bytes(dir / "points.gz", gzip_compress("compressed"));
    log::CaptureScope capture;
    const FileBuffer buffer = read_foam_file(dir / "points");
    EXPECT_EQ(buffer.data, "plain");
    EXPECT_NE(capture.text().find("points.gz"), std::string::npos) << capture.text();
}

TEST(FoamFile, missing_file_error_names_the_path)
{
    const fs::path dir = test::scratch_dir("foam_file_missing");
    const std::string msg = test::error_of([&] { read_foam_file(dir / "nothing"); });
    EXPECT_NE(msg.find((dir / "nothing").string()), std::string::npos) << msg;
    EXPECT_THROW(read_foam_file(dir / "nothing"), IoError);
}

TEST(FoamFile, corrupt_and_truncated_gzip_are_io_errors_naming_the_file)
{
    const fs::path dir = test::scratch_dir("foam_file_corrupt_gz");
    std::string text(100000, 'x');
    for (std::size_t i = 0; i < text.size(); i += 7)
        text[i] = static_cast<char>('a' + i % 26);
    const std::string gz = gzip_compress(text);
    test::write_bytes(dir / "truncated.gz", gz.substr(0, gz.size() / 2));
    std::string corrupt = gz;
    corrupt[gz.size() / 2] ^= 0x55;
    corrupt[gz.size() / 2 + 1] ^= 0x55;
    test::write_bytes(dir / "corrupt.gz", corrupt);
    for (const char* name : {"truncated.gz", "corrupt.gz"})
    {
        const std::string msg = test::error_of([&] { read_foam_file(dir / name); });
        EXPECT_NE(msg.find(name), std::string::npos) << msg;
    }
}

TEST(FoamFile, gzip_round_trip_is_deterministic_and_accepts_concatenated_members)
{
    const std::string text = "hello gzip\n";
    EXPECT_EQ(gzip_compress(text), gzip_compress(text));
    EXPECT_TRUE(is_gzip(gzip_compress(text)));
    EXPECT_EQ(gzip_decompress(gzip_compress(text) + gzip_compress(text), "x"), text + text);
    EXPECT_EQ(gzip_decompress(gzip_compress(""), "x"), "");
}

TEST(FoamFile, atomic_write_replaces_and_removes_the_other_spelling)
{
    const fs::path dir = test::scratch_dir("foam_file_atomic");
    test::write_bytes(dir / "points", "old");
    const fs::path gz = write_file_atomic(dir / "points", "new", {.compress = true});
    EXPECT_EQ(gz, dir / "points.gz");
    EXPECT_FALSE(fs::exists(dir / "points"));
    EXPECT_EQ(read_foam_file(dir / "points").data, "new");

    const fs::path plain = write_file_atomic(dir / "points", "newer");
    EXPECT_EQ(plain, dir / "points");
    EXPECT_FALSE(fs::exists(dir / "points.gz"));
    EXPECT_EQ(test::file_bytes(dir / "points"), "newer");

    // No temporary files are left behind.
    int n_files = 0;
    for ([[maybe_unused]] const fs::directory_entry& e : fs::directory_iterator(dir))
        ++n_files;
    EXPECT_EQ(n_files, 1);
}

TEST(FoamFile, failed_write_names_the_path_and_keeps_the_old_file)
{
    const fs::path dir = test::scratch_dir("foam_file_write_fail");
    const fs::path missing_dir = dir / "no" / "such" / "dir" / "points";
    const std::string msg = test::error_of([&] { write_file_atomic(missing_dir, "x"); });
    EXPECT_NE(msg.find(missing_dir.string()), std::string::npos) << msg;

    // The rename cannot replace a directory: the target stays and no temporary is left.
    fs::create_directories(dir / "points" / "inside");
    const std::string rename_msg = test::error_of([&] { write_file_atomic(dir / "points", "x"); });
    EXPECT_NE(rename_msg.find((dir / "points").string()), std::string::npos) << rename_msg;
    EXPECT_TRUE(fs::is_directory(dir / "points" / "inside"));
    int n_entries = 0;
    for ([[maybe_unused]] const fs::directory_entry& e : fs::directory_iterator(dir))
        ++n_entries;
    EXPECT_EQ(n_entries, 1); // only "points"
}

TEST(TempFile, an_interrupt_removes_the_temporaries_and_ends_the_process_as_the_signal_would)
{
    // An interrupted design set-up used to leave its 87 MB temporary until the next one.
    const std::filesystem::path dir = test::scratch_dir("temp_interrupt");
    for (const int sig : {SIGINT, SIGTERM})
    {
        const std::filesystem::path marker = dir / ("temp_name_" + std::to_string(sig));
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0)
        {
            io::remove_temps_on_interrupt();
            const std::filesystem::path temp = io::temp_path_for(dir / "basis");
            std::ofstream(temp) << "half a basis";
            std::ofstream(marker) << temp.string(); // tells the parent its name
            ::raise(sig);
            ::_exit(0); // not reached: the signal ends the process
        }
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
        std::ifstream in(marker);
        std::string temp;
        std::getline(in, temp);
        ASSERT_FALSE(temp.empty());
        EXPECT_FALSE(std::filesystem::exists(temp)) << temp << " left behind";
    }
}
