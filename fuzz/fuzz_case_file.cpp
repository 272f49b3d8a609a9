// libFuzzer target: a case file's text through the path of `kinetofem run`
// (run_case.cpp): read case.type with a one-key schema and unknown keys
// allowed, pick that type's schema, parse again against it, then read every
// declared key with its getter. Any outcome but a value or kinetofem::Error
// (a crash, a sanitizer report, another exception type) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/case_types.hpp"
#include "kinetofem/core/error.hpp"

namespace {

using kinetofem::app::CaseFile;
using kinetofem::app::KeySpec;

void read_every_key(const CaseFile& c, const std::vector<KeySpec>& schema) {
  for (const auto& s : schema) {
    if (s.type == KeySpec::Type::TableArray) continue;
    const auto bracket = s.path.find("[]");
    const std::size_t elements = bracket == std::string::npos ? 1 : c.count(s.path.substr(0, bracket));
    for (std::size_t k = 0; k < elements; ++k) {
      try {
        switch (s.type) {
          case KeySpec::Type::Number: (void)c.number(s.path, k); break;
          case KeySpec::Type::Integer: (void)c.integer(s.path, k); break;
          case KeySpec::Type::String: (void)c.text_value(s.path, k); break;
          case KeySpec::Type::Boolean: (void)c.boolean(s.path, k); break;
          case KeySpec::Type::Vector3: (void)c.vector3(s.path, k); break;
          case KeySpec::Type::StringList: (void)c.strings(s.path, k); break;
          case KeySpec::Type::Array: (void)c.node(s.path, k); break;
          case KeySpec::Type::TableArray: break;
        }
        (void)c.where(s.path, k);
      } catch (const kinetofem::Error&) {
        // a required key that is absent: a proper error
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const CaseFile any = CaseFile::parse(
        text, "fuzz.toml", {{.path = "case.type", .type = KeySpec::Type::String, .required = true}},
        /*allow_unknown=*/true);
    const auto& type = kinetofem::app::case_type_named(any.text_value("case.type"), "fuzz.toml: ");
    const CaseFile c = CaseFile::parse(text, "fuzz.toml", type.schema());
    read_every_key(c, type.schema());
  } catch (const kinetofem::Error&) {
    // bad input, properly reported
  }
  return 0;
}
