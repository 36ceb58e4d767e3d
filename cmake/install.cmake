# Install rules, the exported CMake package and the Debian packages (CPack). Included by the top
# CMakeLists.txt after every target is defined. Three components:
#   Runtime      bin/treesketch, bin/treesketch-gui (when built)      -> package "treesketch"
#   Development  lib/libtreesketch.a, include/treesketch/, the CMake package -> "treesketch-dev"
#   Python       the module treesketch (when built; its rule is in python/CMakeLists.txt)
#                                                                     -> "python3-treesketch"
include(CMakePackageConfigHelpers)

set(TS_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/treesketch)

install(TARGETS treesketch_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT Runtime)
if(TARGET treesketch_gui)
  install(TARGETS treesketch_gui RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT Runtime)
endif()

install(TARGETS treesketch EXPORT treesketchTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT Development
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/treesketch DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        COMPONENT Development)
install(EXPORT treesketchTargets NAMESPACE treesketch:: DESTINATION ${TS_CMAKE_DIR} COMPONENT Development)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/treesketchConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/treesketchConfig.cmake INSTALL_DESTINATION ${TS_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/treesketchConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)  # 0.x: a new minor may break the API
install(FILES ${PROJECT_BINARY_DIR}/treesketchConfig.cmake ${PROJECT_BINARY_DIR}/treesketchConfigVersion.cmake
        DESTINATION ${TS_CMAKE_DIR} COMPONENT Development)

# ---- Debian packages: `make package` (cpack -G DEB in the build folder) -------------------------
set(CPACK_PACKAGE_NAME treesketch)
set(CPACK_PACKAGE_VENDOR "treesketch")
set(CPACK_PACKAGE_CONTACT "treesketch maintainers <treesketch@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Tree meshes from point clouds, guided by a sketch (CLI, desktop tool, library)")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR DEB)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL Runtime Development)
if(TS_PYTHON)
  list(APPEND CPACK_COMPONENTS_ALL Python)
endif()
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME treesketch)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)  # Depends from the binaries' shared libraries (dpkg-shlibdeps)
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_NAME treesketch-dev)
# The static library's users compile against these headers and link these libraries.
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_DEPENDS
    "libeigen3-dev, libtbb-dev, nlohmann-json3-dev, libembree-dev, libnanoflann-dev, cmake")
set(CPACK_DEBIAN_DEVELOPMENT_PACKAGE_SECTION libdevel)
if(TS_PYTHON)
  # The module is built for one Python minor version (its file name says cpython-3XY).
  set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-treesketch)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
  set(CPACK_DEBIAN_PYTHON_PACKAGE_SHLIBDEPS ON)
  math(EXPR ts_py_next_minor "${Python3_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), \
python3 (<< ${Python3_VERSION_MAJOR}.${ts_py_next_minor}), python3-numpy")
  set(CPACK_COMPONENT_PYTHON_DESCRIPTION "treesketch from Python: clouds, tree models and meshes as NumPy arrays")
endif()
include(CPack)
