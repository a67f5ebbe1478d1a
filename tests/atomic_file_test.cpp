// atomic_file: contents arrive whole, replace the old file, and failures name the path.
#include "io/atomic_file.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "test_util.h"
#include "util/error.h"

namespace clppm {
namespace {

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

size_t entry_count(const std::string& dir) {
    size_t n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) n += !e.path().empty();
    return n;
}

TEST(AtomicFile, WritesAndReplaces) {
    std::string dir = test::make_temp_dir("atomic");
    std::string path = dir + "/stats.json";
    write_file_atomic(path, "first");
    EXPECT_EQ(read_text(path), "first");
    std::string binary("a\0b\n", 4);
    write_file_atomic(path, binary);
    EXPECT_EQ(read_text(path), binary);
    write_file_atomic(path, "");
    EXPECT_EQ(read_text(path), "");
    EXPECT_EQ(entry_count(dir), 1u);
}

TEST(AtomicFile, RelativePathInCurrentDirectory) {
    std::string dir = test::make_temp_dir("atomic");
    auto old = std::filesystem::current_path();
    std::filesystem::current_path(dir);
    write_file_atomic("plain.txt", "x");
    EXPECT_NO_THROW(check_writable("other.txt"));
    std::filesystem::current_path(old);
    EXPECT_EQ(read_text(dir + "/plain.txt"), "x");
    EXPECT_EQ(entry_count(dir), 1u);
}

TEST(AtomicFile, ErrorsAreOneLineNamingThePath) {
    std::string dir = test::make_temp_dir("atomic");
    std::string missing = dir + "/nope/a.txt";
    try {
        write_file_atomic(missing, "x");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "cannot write " + missing + ": directory " + dir + "/nope does not exist");
    }
    EXPECT_THROW(write_file_atomic("", "x"), Error);
    EXPECT_THROW(write_file_atomic(dir + "/", "x"), Error);
    EXPECT_THROW(check_writable(dir + "/"), Error);
    EXPECT_EQ(entry_count(dir), 0u);
}

TEST(AtomicFile, ParentDirectory) {
    EXPECT_EQ(parent_directory("a.exr"), ".");
    EXPECT_EQ(parent_directory("out/a.exr"), "out");
    EXPECT_EQ(parent_directory("/a.exr"), "/");
    EXPECT_EQ(parent_directory("/x/y/a.exr"), "/x/y");
}

} // namespace
} // namespace clppm
