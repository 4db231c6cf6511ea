# Precompiled headers: the heavy system headers a target's files include (nlohmann/json, glm, Vulkan, OpenCV) and the
# standard library's common ones, parsed once per target instead of once per file: parsing them was about half of a
# heavy file's compile time (docs/testing.md, "Build cost"). PRIVATE, so consumers of the installed package and the
# layer rules (no Vulkan header below engine/ and render/) see each file's own includes only.
set(SWARD_PCH_STD <algorithm> <cmath> <cstdint> <filesystem> <functional> <memory> <span> <string> <vector>)

function(sward_precompile target)
  target_precompile_headers(${target} PRIVATE ${SWARD_PCH_STD} ${ARGN})
endfunction()
