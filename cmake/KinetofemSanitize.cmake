# Sanitizer and fuzzing builds (options of the top-level CMakeLists.txt).
#
# KINETOFEM_SANITIZE=ON: every target is compiled and linked with
#   -fsanitize=address,undefined -fno-omit-frame-pointer
# (scripts/test-sanitizers.sh configures build-asan with it and runs ctest).
#
# KINETOFEM_BUILD_FUZZ=ON (clang only): every target is compiled with
#   -fsanitize=fuzzer-no-link,address,undefined
# so libFuzzer sees coverage of our code, and fuzz/ adds the libFuzzer
# targets, linked with -fsanitize=fuzzer (scripts/fuzz.sh).
option(KINETOFEM_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(KINETOFEM_BUILD_FUZZ "Build the libFuzzer targets in fuzz/ (clang)" OFF)

if(KINETOFEM_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

if(KINETOFEM_BUILD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "KINETOFEM_BUILD_FUZZ needs clang (libFuzzer): configure with "
                        "-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ (scripts/fuzz.sh does)")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=address,undefined)
endif()
