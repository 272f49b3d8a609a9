// read_text_file: a file's bytes unchanged; an unreadable file is an Error naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/text_file.hpp"

namespace fs = std::filesystem;

namespace kinetofem {
namespace {

TEST(ReadTextFile, ReturnsTheBytesUnchanged) {
  const fs::path file = fs::path(::testing::TempDir()) / "kinetofem_read_text_file.txt";
  const std::string bytes = std::string("line 1\r\nline 2\n") + '\0' + "after a NUL";
  std::ofstream(file, std::ios::binary) << bytes;
  EXPECT_EQ(read_text_file(file), bytes);
  fs::remove(file);
}

TEST(ReadTextFile, AMissingFileIsAnErrorNamingIt) {
  const fs::path file = fs::path(::testing::TempDir()) / "kinetofem_no_such_file.txt";
  try {
    read_text_file(file);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), file.string() + ": cannot open the file");
  }
}

}  // namespace
}  // namespace kinetofem
