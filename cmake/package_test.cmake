# CTest package.install_and_consume (cmake -P): installs the build tree into a temporary prefix, then
#  1. configures, builds and runs cmake/consumer (find_package(shadelab 0.1 REQUIRED), shadelab::shadelab);
#  2. builds the same program with the flags of the installed pkg-config file and runs it;
#  3. imports the installed Python module with the prefix's site-packages on PYTHONPATH (when built);
#  4. runs the installed CLI; checks the headers are there and the tests' files are not.
# Arguments: BUILD_DIR SOURCE_DIR WORK_DIR GENERATOR CXX [CXX_FLAGS] [PRELOAD] [PYTHON PYTHON_DIR]. CXX_FLAGS are
# the build's (sanitizer flags must reach the consumer too); PRELOAD the sanitizer runtimes for Python.
cmake_minimum_required(VERSION 3.25)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "package test: ${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# Headers per module folder, without tests.
foreach(header shadelab/brdf/registry.h shadelab/core/vec.h shadelab/render/path_tracer.h
    shadelab/envmap/base/cubemap.h shadelab/envmap/diffuse/sh.h shadelab/envmap/specular/prefilter_ggx.h)
  if(NOT EXISTS ${prefix}/include/${header})
    message(FATAL_ERROR "package test: ${prefix}/include/${header} was not installed")
  endif()
endforeach()
file(GLOB_RECURSE test_files ${prefix}/include/*_test.* ${prefix}/include/*/test_*)
if(test_files)
  message(FATAL_ERROR "package test: test files were installed: ${test_files}")
endif()

# 1. find_package.
run("configure the consumer" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/cmake/consumer -B ${WORK_DIR}/consumer
    -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${prefix}
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}")
run("build the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/consumer)
run("run the consumer" ${WORK_DIR}/consumer/shadelab_consumer ${WORK_DIR})
if(NOT run_output MATCHES "shadelab consumer ok")
  message(FATAL_ERROR "package test: the consumer printed: ${run_output}")
endif()
message(STATUS "find_package: ${run_output}")

# 2. pkg-config.
find_program(PKG_CONFIG pkg-config REQUIRED)
file(GLOB pc_file ${prefix}/lib*/pkgconfig/shadelab.pc ${prefix}/lib/*/pkgconfig/shadelab.pc)
if(NOT pc_file)
  message(FATAL_ERROR "package test: no shadelab.pc under ${prefix}")
endif()
get_filename_component(pc_dir ${pc_file} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pc_dir})
run("pkg-config" ${PKG_CONFIG} --cflags --libs shadelab)
string(STRIP "${run_output}" pc_flags)
separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
separate_arguments(build_flags UNIX_COMMAND "${CXX_FLAGS}")
run("build with pkg-config flags" ${CXX} -std=c++20 -O1 ${build_flags} ${SOURCE_DIR}/cmake/consumer/main.cpp ${pc_flags}
    -o ${WORK_DIR}/consumer_pc)
run("run the pkg-config build" ${WORK_DIR}/consumer_pc ${WORK_DIR})
message(STATUS "pkg-config: ${run_output}")

# 3. Python.
if(PYTHON)
  set(ENV{PYTHONPATH} ${prefix}/${PYTHON_DIR})
  if(PRELOAD)
    set(ENV{LD_PRELOAD} ${PRELOAD})
    set(ENV{ASAN_OPTIONS} detect_leaks=0)
  endif()
  # A script file: the code's semicolons would split a command-line argument into a CMake list.
  file(WRITE ${WORK_DIR}/import_test.py [[
import sys
import shadelab
assert shadelab.__file__.startswith(sys.argv[1]), shadelab.__file__
albedo = shadelab.Brdf("lambert", kd=1).albedo(0.0)[1]
assert abs(albedo - 1.0) < 1e-9, albedo
print(shadelab.__file__, albedo)
]])
  run("import the installed module" ${PYTHON} ${WORK_DIR}/import_test.py ${prefix})
  message(STATUS "python: ${run_output}")
endif()

# 4. The CLI.
run("the installed CLI" ${prefix}/bin/shadelab --version)
message(STATUS "cli: ${run_output}")
file(REMOVE_RECURSE ${WORK_DIR})
