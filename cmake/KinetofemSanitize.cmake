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
  # No -g: the sanitizers' and libFuzzer's reports need line tables only (the
  # build type's -gline-tables-only); full debug info cost 30 % more compile
  # time and 3.6x larger objects to link.
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

# KINETOFEM_UBSAN_SKIP: UndefinedBehaviorSanitizer checks left out (clang's names,
# comma-separated, given as -fno-sanitize= after the -fsanitize options above so
# that they win; default: none). scripts/configure-instrumented.sh leaves out
# alignment, object-size and pointer-overflow in the test suite's tree (why: there).
set(KINETOFEM_UBSAN_SKIP "" CACHE STRING "UBSan checks left out of a sanitizer or fuzz build")
if(KINETOFEM_UBSAN_SKIP AND (KINETOFEM_SANITIZE OR KINETOFEM_BUILD_FUZZ))
  add_compile_options(-fno-sanitize=${KINETOFEM_UBSAN_SKIP})
endif()
