# `cmake --install build --prefix P`: the CMake package of sward (docs/architecture.md, "The installed package").
#   P/include/sward/<layer>/*.h     headers by layer, included as "engine/context.h" (P/include/sward is the one
#                                   include directory, as the source root is in the tree); shaders/shared/ as shared/
#   P/lib/libsward_<layer>.a        the layer libraries; sward_engine carries the compiled shaders
#   P/lib/cmake/sward/              swardConfig.cmake, swardConfigVersion.cmake, swardTargets.cmake
#   P/bin/sward-*                   the tools (rpath $ORIGIN/../lib: the release archive's bundled libraries)
#   P/lib/python3/dist-packages/sward  the Python module (python/CMakeLists.txt)
#   P/share/sward/examples/         the example scenes, with the example worlds' generated data (examples/)
#   P/share/sward/bench/reference/  sward-bench suite's cross-check reference (bench/reference/)
#   P/share/doc/sward/              README.md, docs/, third_party_notes.md
# Two components: Runtime (tools, examples, docs; with the Python module, which python/ installs, the release archive
# of cmake/Package.cmake) and Development (headers, static libraries, the CMake package), which the archive leaves out.
# A program uses it with find_package(sward) and target_link_libraries(app sward::render): each layer is exported
# as sward::<layer> with its dependencies on the layers below and on Debian's packages (swardConfig.cmake finds
# them). The libraries are static, so their private dependencies are exported as link-only ones.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(SWARD_LAYERS common io world vegetation interaction scene dataset eval range engine render)
set(SWARD_EXPORTED_HELPERS sward_gpu_layout sward_opencv sward_options)
if(NOT SWARD_WITH_OPENCV) # no eval/ layer; OpenCV, if found at all, serves the tests only
  list(REMOVE_ITEM SWARD_LAYERS eval)
  list(REMOVE_ITEM SWARD_EXPORTED_HELPERS sward_opencv)
endif()
set(SWARD_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/sward)

foreach(layer ${SWARD_LAYERS})
  set_target_properties(sward_${layer} PROPERTIES EXPORT_NAME ${layer})
  install(DIRECTORY ${layer}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sward/${layer} COMPONENT Development
          FILES_MATCHING PATTERN "*.h")
endforeach()
install(DIRECTORY shaders/shared/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/sward/shared COMPONENT Development
        FILES_MATCHING PATTERN "*.h")
# Interface helpers the static libraries name in their link interfaces: the GPU layout headers, OpenCV's modules
# (cmake/OpenCVModules.cmake) and sward's warning / sanitizer options (only their link options reach a consumer).
set_target_properties(sward_gpu_layout PROPERTIES EXPORT_NAME gpu_layout)
if(TARGET sward_opencv)
  set_target_properties(sward_opencv PROPERTIES EXPORT_NAME opencv)
endif()
set_target_properties(sward_options PROPERTIES EXPORT_NAME options)

list(TRANSFORM SWARD_LAYERS PREPEND sward_ OUTPUT_VARIABLE SWARD_LAYER_TARGETS)
install(TARGETS ${SWARD_LAYER_TARGETS} ${SWARD_EXPORTED_HELPERS}
        EXPORT swardTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT Development)
set(SWARD_TOOLS sward-render sward-eval sward-export sward-view sward-bench sward-atlas sward-rover)
install(TARGETS ${SWARD_TOOLS} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT Runtime)
# The shard-manifest merge (docs/scale-out.md), beside the tools under its own name: P/bin/merge-manifests.py.
install(PROGRAMS tools/merge-manifests.py DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT Runtime)
install(EXPORT swardTargets NAMESPACE sward:: DESTINATION ${SWARD_CMAKE_DIR} COMPONENT Development)

# The examples as the build leaves them in <build>/examples: the scene files of the source tree, and the example
# worlds' generated ground meshes and rasters beside their scenes (examples/CMakeLists.txt). host-app is a program's
# source (docs/integration.md), shipped as it is.
install(DIRECTORY examples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/sward/examples COMPONENT Runtime
        REGEX "examples/CMakeLists\\.txt$" EXCLUDE)
install(DIRECTORY ${CMAKE_BINARY_DIR}/examples/gis ${CMAKE_BINARY_DIR}/examples/hills ${CMAKE_BINARY_DIR}/examples/tracks
        DESTINATION ${CMAKE_INSTALL_DATADIR}/sward/examples COMPONENT Runtime)
# The reference images of sward-bench suite's cross-check (bench/reference/README.md), where the installed
# sward-bench looks for them: P/share/sward/bench/reference/.
install(DIRECTORY bench/reference/ DESTINATION ${CMAKE_INSTALL_DATADIR}/sward/bench/reference COMPONENT Runtime)
install(FILES README.md third_party_notes.md DESTINATION ${CMAKE_INSTALL_DOCDIR} COMPONENT Runtime)
install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs COMPONENT Runtime)

configure_package_config_file(cmake/swardConfig.cmake.in ${CMAKE_BINARY_DIR}/swardConfig.cmake
                              INSTALL_DESTINATION ${SWARD_CMAKE_DIR})
# 0.x: a minor version may change the API, so only the same minor version is compatible.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/swardConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/swardConfig.cmake ${CMAKE_BINARY_DIR}/swardConfigVersion.cmake
        DESTINATION ${SWARD_CMAKE_DIR} COMPONENT Development)
