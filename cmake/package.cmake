# The installed C++ package: `cmake --install` puts the headers, the static libraries, a CMake package
# (find_package(shadelab 0.1 REQUIRED), target shadelab::shadelab, one shadelab::<module> per module) and a
# pkg-config file under the prefix; the CLI goes to bin/ and the Python module to the prefix's
# site-packages (python/CMakeLists.txt). Nothing here lists modules or headers: the library targets are
# the ones src/shadelab/CMakeLists.txt defines, the headers are found per module folder at install time,
# so a new module or header installs without an edit here. docs/design.md, "The installed package".
include(CMakePackageConfigHelpers)

# Every library target of src/shadelab (static modules, header-only INTERFACE modules, the bundle).
get_property(shadelab_dir_targets DIRECTORY ${PROJECT_SOURCE_DIR}/src/shadelab PROPERTY BUILDSYSTEM_TARGETS)
set(SHADELAB_LIBRARY_TARGETS)
foreach(t ${shadelab_dir_targets})
  get_target_property(type ${t} TYPE)
  if(type STREQUAL "STATIC_LIBRARY" OR type STREQUAL "INTERFACE_LIBRARY")
    list(APPEND SHADELAB_LIBRARY_TARGETS ${t})
    # shadelab_brdf is shadelab::brdf outside; the bundle shadelab is shadelab::shadelab.
    string(REGEX REPLACE "^shadelab_" "" export_name ${t})
    set_target_properties(${t} PROPERTIES EXPORT_NAME ${export_name})
  endif()
  if(type STREQUAL "STATIC_LIBRARY")
    # Position-independent, so the static libraries link into the Python extension (a shared object) and
    # into other projects' shared libraries. -fno-semantic-interposition keeps GCC inlining the library's
    # own functions as it does without -fPIC (nothing interposes symbols of a static library).
    set_target_properties(${t} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_compile_options(${t} PRIVATE $<$<CXX_COMPILER_ID:GNU>:-fno-semantic-interposition>)
  endif()
endforeach()

install(TARGETS ${SHADELAB_LIBRARY_TARGETS} EXPORT shadelabTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT devel)
install(EXPORT shadelabTargets NAMESPACE shadelab:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/shadelab
  COMPONENT devel)

# Headers, per module folder, as include/shadelab/<module>/<file>: every header and kernel source (*.sl),
# without tests and test helpers. The folders are read when installing, not when configuring.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/shadelab/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/shadelab
  COMPONENT devel
  FILES_MATCHING PATTERN "*.h" PATTERN "*.hpp" PATTERN "*.inl" PATTERN "*.sl"
  PATTERN "*_test.*" EXCLUDE PATTERN "test_*" EXCLUDE)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/shadelabConfig.cmake.in
  ${PROJECT_BINARY_DIR}/package/shadelabConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/shadelab)
# 0.x: a request for 0.1 accepts 0.1.*, not 0.2 (the API may change between minor versions before 1.0).
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/shadelabConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/shadelabConfig.cmake
  ${PROJECT_BINARY_DIR}/package/shadelabConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/shadelab COMPONENT devel)

# pkg-config: -l flags in link order (a module before the modules it links to), found by walking the
# link graph from the bundle, so a new module appears in the right place.
set(shadelab_pc_order)
function(shadelab_pc_visit t)
  get_property(seen GLOBAL PROPERTY shadelab_pc_seen)
  if(t IN_LIST seen)
    return()
  endif()
  set_property(GLOBAL APPEND PROPERTY shadelab_pc_seen ${t})
  get_target_property(deps ${t} INTERFACE_LINK_LIBRARIES)
  foreach(d ${deps})
    if(d IN_LIST SHADELAB_LIBRARY_TARGETS)
      shadelab_pc_visit(${d})
    endif()
  endforeach()
  get_target_property(type ${t} TYPE)
  if(type STREQUAL "STATIC_LIBRARY")
    set_property(GLOBAL APPEND PROPERTY shadelab_pc_postorder ${t})
  endif()
endfunction()
shadelab_pc_visit(shadelab)
get_property(postorder GLOBAL PROPERTY shadelab_pc_postorder)
list(REVERSE postorder)
set(SHADELAB_PC_LIBS)
foreach(t ${postorder})
  string(APPEND SHADELAB_PC_LIBS " -l${t}")
endforeach()
# The prefix relative to the .pc file, so `cmake --install --prefix P` and moving the tree both work.
set(pc_dir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
string(REGEX REPLACE "[^/]+" ".." SHADELAB_PC_PREFIX_FROM_PCDIR ${pc_dir})
configure_file(${PROJECT_SOURCE_DIR}/cmake/shadelab.pc.in ${PROJECT_BINARY_DIR}/package/shadelab.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/shadelab.pc DESTINATION ${pc_dir} COMPONENT devel)

if(TARGET shadelab_cli)
  install(TARGETS shadelab_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
  # The OpenColorIO config of the built-in views (docs/color.md): --view OCIO:<prefix>/share/shadelab/ocio/shadelab.ocio:sRGB:AgX
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/share/ocio/ DESTINATION ${CMAKE_INSTALL_DATADIR}/shadelab/ocio COMPONENT cli)
endif()

# Everything `cmake --install` copies, and nothing else (no tests, benchmarks or WebAssembly): the target
# scripts/run.sh builds, so that the README's install step works after its main command (issue 39: the CLI
# alone left the Python module and libshadelab_envmap.a unbuilt, and the install failed on them).
set(shadelab_installable_targets ${SHADELAB_LIBRARY_TARGETS})
foreach(t shadelab_cli shadelab_python)
  if(TARGET ${t})
    list(APPEND shadelab_installable_targets ${t})
  endif()
endforeach()
add_custom_target(shadelab_installable DEPENDS ${shadelab_installable_targets})

# The test: install into a temporary prefix, build an outside project against it with find_package and
# with pkg-config, run both, and import the installed Python module (cmake/package_test.cmake).
if(SHADELAB_BUILD_TESTS)
  set(package_test_python "")
  if(TARGET shadelab_python)
    set(package_test_python ${Python_EXECUTABLE})
  endif()
  add_test(NAME package.install_and_consume
    COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
      -DWORK_DIR=${PROJECT_BINARY_DIR}/package_test -DGENERATOR=${CMAKE_GENERATOR}
      -DCXX=${CMAKE_CXX_COMPILER} "-DCXX_FLAGS=${CMAKE_CXX_FLAGS}" -DPRELOAD=${SHADELAB_SANITIZER_PRELOAD}
      -DPYTHON=${package_test_python} -DPYTHON_DIR=${SHADELAB_PYTHON_INSTALL_DIR}
      -P ${PROJECT_SOURCE_DIR}/cmake/package_test.cmake)
  set_tests_properties(package.install_and_consume PROPERTIES TIMEOUT 600)
endif()
