# Debian splits OpenCV into per-module -dev packages; only the full libopencv-dev (40+ extra packages)
# ships OpenCVConfig.cmake. We need five modules, so we find them directly.
find_path(OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
add_library(sward_opencv INTERFACE)
target_include_directories(sward_opencv SYSTEM INTERFACE ${OPENCV_INCLUDE_DIR})
foreach(module core imgproc imgcodecs features2d calib3d video)
  find_library(OPENCV_${module}_LIBRARY opencv_${module} REQUIRED)
  target_link_libraries(sward_opencv INTERFACE ${OPENCV_${module}_LIBRARY})
endforeach()
