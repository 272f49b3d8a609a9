# cmake -DINPUT=file -DOUTPUT=file.cpp -DFUNCTION=ns::name -DSHOWN=path -P embed_text.cmake
# Writes OUTPUT: `std::string_view ns::name()` returning INPUT's bytes (see
# KinetofemEmbed.cmake).
foreach(required INPUT OUTPUT FUNCTION SHOWN)
  if(NOT DEFINED ${required})
    message(FATAL_ERROR "embed_text.cmake: ${required} not given")
  endif()
endforeach()
file(READ "${INPUT}" text)
set(delimiter "kinetofem_embed")
string(FIND "${text}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains the raw-string delimiter )${delimiter}\"")
endif()
string(REGEX REPLACE "::[^:]*$" "" namespace "${FUNCTION}")
string(REGEX REPLACE "^.*::" "" name "${FUNCTION}")
set(generated "// Generated from ${SHOWN} by cmake/embed_text.cmake: do not edit.
#include <string_view>

namespace ${namespace} {

std::string_view ${name}();

std::string_view ${name}() {
  static constexpr char text[] = R\"${delimiter}(${text})${delimiter}\";
  return {text, sizeof(text) - 1};
}

}  // namespace ${namespace}
")
file(WRITE "${OUTPUT}" "${generated}")
