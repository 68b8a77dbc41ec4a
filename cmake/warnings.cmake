# Warnings for every shadelab target; -Werror when SHADELAB_WERROR is on (CI). Never fast-math.
add_library(shadelab_warnings INTERFACE)
target_compile_options(shadelab_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Wnon-virtual-dtor
  -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wnull-dereference -Wdouble-promotion
  -fno-fast-math)
# GCC 12 reports -Wrestrict false positives inside std::string concatenation at -O3 (GCC bug 105329).
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  target_compile_options(shadelab_warnings INTERFACE -Wno-restrict)
endif()
if(SHADELAB_WERROR)
  target_compile_options(shadelab_warnings INTERFACE -Werror)
endif()

# shadelab_add_tests(<target> SOURCES...): one GoogleTest executable registered with CTest.
function(shadelab_add_tests name)
  if(NOT SHADELAB_BUILD_TESTS)
    return()
  endif()
  add_executable(${name} ${ARGN})
  target_link_libraries(${name} PRIVATE shadelab::shadelab GTest::gtest_main shadelab_warnings)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endfunction()
