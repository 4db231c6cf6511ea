# The relocatable release (docs/release.md; issue 49): `./sward.sh package`, or `cpack` in the build folder, writes
# sward-<version>-linux-x86_64.tar.gz. It holds the Runtime component of cmake/Install.cmake (tools, examples, docs)
# and the Python module, and cmake/BundleRuntime.cmake copies into its lib/ every shared library those binaries load,
# but the ones the target machine must bring: the C library family (glibc's libc, libm, libpthread, libdl, librt,
# libresolv, ld-linux), libstdc++ / libgcc_s, and the Vulkan loader with the GPU driver behind it.
#
# Why not bundle libstdc++ / libgcc_s: the Vulkan driver is loaded into the same process and one soname is loaded
# once. Mesa's drivers link LLVM, built with the target's own (newer) GCC; a bundled Debian 12 libstdc++ would be the
# one they get and they would fail to load ("GLIBCXX_3.4.3x not found"), leaving no device; a libstdc++ is
# backward compatible, so the target's own serves sward too. What sward needs of it (GLIBCXX_3.4.30, GCC 12) every
# distribution with glibc >= 2.36 has (glibc 2.36 and GCC 12 are both of 2022). Measured in a Debian 13 root
# (SUITE=trixie tools/release-check.sh): with Debian 12's libstdc++ in lib/, Mesa 25's lavapipe does not load
# ("GLIBCXX_3.4.31 not found (required by libz3.so.4)") and sward-render fails; without it, it renders.
#
# The binaries find the bundled libraries by their rpath, $ORIGIN/../lib (the tools) or $ORIGIN/../../.. (the
# Python module in lib/python3/dist-packages/sward/), written as DT_RPATH (--disable-new-dtags), not DT_RUNPATH:
# the bundled libraries' own dependencies (GDAL's PROJ, GEOS, ...) are then found there too, since the loader
# searches the DT_RPATH of every object on the chain that loaded a library, while a DT_RUNPATH serves only the
# object's own direct dependencies. Debian's libraries stay unmodified (no patchelf). A DT_RPATH is searched before
# LD_LIBRARY_PATH: to use the machine's copy of a bundled library, delete it from lib/. In `cmake --install`
# prefixes the rpath names P/lib: sward's static libraries, and whatever else is there (/usr/local/lib).
#
# The build tree's binaries are linked with the same rpath (BUILD_WITH_INSTALL_RPATH): the tools' is the build's
# lib/ (sward's static libraries only, so nothing is found there), the module's the build folder's parent. A
# separate build rpath would end in ':' (CMake adds a separator, and pads to the install rpath's length, so that
# `cmake --install` can rewrite it in place), and the loader reads an empty entry as the current directory: a
# build-tree binary would load libraries from wherever it is run.
foreach(target ${SWARD_TOOLS})
  set_target_properties(${target} PROPERTIES INSTALL_RPATH "\$ORIGIN/../${CMAKE_INSTALL_LIBDIR}"
                                             BUILD_WITH_INSTALL_RPATH ON)
  target_link_options(${target} PRIVATE -Wl,--disable-new-dtags)
endforeach()
if(TARGET sward_python)
  set_target_properties(sward_python PROPERTIES INSTALL_RPATH "\$ORIGIN/../../.." BUILD_WITH_INSTALL_RPATH ON)
  target_link_options(sward_python PRIVATE -Wl,--disable-new-dtags)
endif()

set(CPACK_PACKAGE_NAME sward)
set(CPACK_PACKAGE_VENDOR sward)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Interactive ground vegetation for synthetic stereo datasets")
set(CPACK_PACKAGE_FILE_NAME sward-${PROJECT_VERSION}-linux-${CMAKE_SYSTEM_PROCESSOR})
set(CPACK_GENERATOR TGZ)
set(CPACK_INCLUDE_TOPLEVEL_DIRECTORY ON)
# The Runtime component and the Python module (python/ installs it without a component: "Unspecified"), installed
# into one staging folder as one monolithic package: a component archive would pack only the files the install
# rules listed, not the libraries cmake/BundleRuntime.cmake adds. The Development component (headers, static
# libraries, the CMake package, 32 MB) is of no use without Debian's -dev packages, so it stays out.
set(CPACK_INSTALL_CMAKE_PROJECTS "${CMAKE_BINARY_DIR};sward;Runtime;/" "${CMAKE_BINARY_DIR};sward;Unspecified;/")
set(CPACK_STRIP_FILES ON)
set(CPACK_PRE_BUILD_SCRIPTS ${PROJECT_SOURCE_DIR}/cmake/BundleRuntime.cmake)
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/package)
include(CPack)
