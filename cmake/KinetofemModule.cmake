# kinetofem_module(NAME DEPS...) — one library per module folder, built from
# every src/*.cpp of the folder (globbed, so adding a file needs no edit
# here), with include/ as its public include directory.
function(kinetofem_module name)
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(kinetofem_${name} ${sources})
  add_library(kinetofem::${name} ALIAS kinetofem_${name})
  target_include_directories(kinetofem_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(kinetofem_${name} PUBLIC ${ARGN})
endfunction()

# kinetofem_test_dir(DIR LABEL LIBS...) — one GoogleTest executable from every
# *.cpp of DIR, its tests registered with ctest under LABEL.
function(kinetofem_test_dir dir label)
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${dir}/*.cpp)
  if(NOT sources)
    return()
  endif()
  string(REPLACE "/" "_" exe ${dir})
  add_executable(${exe} ${sources})
  target_link_libraries(${exe} PRIVATE ${ARGN} kinetofem_test_support GTest::gtest_main)
  gtest_discover_tests(${exe}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    PROPERTIES LABELS ${label}
    DISCOVERY_TIMEOUT 60)
endfunction()
