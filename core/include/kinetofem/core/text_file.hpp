#pragma once
// Reading a whole (small) input file as text: case-adjacent scripts and part
// files that are scanned or parsed before anything else reads them.
#include <filesystem>
#include <string>

namespace kinetofem {

// The file's bytes, unchanged. Error "<file>: cannot open the file" if it
// cannot be opened.
std::string read_text_file(const std::filesystem::path& file);

}  // namespace kinetofem
