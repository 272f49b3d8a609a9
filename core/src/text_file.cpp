#include "kinetofem/core/text_file.hpp"

#include <fstream>
#include <sstream>

#include "kinetofem/core/error.hpp"

namespace kinetofem {

std::string read_text_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  require(bool(in), "{}: cannot open the file", file.string());
  std::stringstream content;
  content << in.rdbuf();
  return content.str();
}

}  // namespace kinetofem
