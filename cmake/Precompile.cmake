# Precompiled headers: the heavy system headers a target's files include (nlohmann/json, glm, Vulkan, OpenCV) and the
# standard library's common ones, parsed once per target instead of once per file: parsing them was about half of a
# heavy file's compile time (docs/testing.md, "Build cost"). PRIVATE, so consumers of the installed package and the
# layer rules (no Vulkan header below engine/ and render/) see each file's own includes only.
set(SWARD_PCH_STD <algorithm> <cmath> <cstdint> <filesystem> <functional> <memory> <span> <string> <vector>)

function(sward_precompile target)
  # GCC 12 with optimisation reports false -Wstringop-overflow errors in std::string code reached through a
  # precompiled header (the family of the -Wrestrict false positive in CMakeLists.txt). There only targets compiled
  # at -O0 (the tests' header, tests/CMakeLists.txt) are precompiled; the clang sanitizer build precompiles everything.
  get_target_property(options ${target} COMPILE_OPTIONS)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND NOT "-O0" IN_LIST options AND NOT CMAKE_BUILD_TYPE STREQUAL "Debug")
    return()
  endif()
  target_precompile_headers(${target} PRIVATE ${SWARD_PCH_STD} ${ARGN})
endfunction()
