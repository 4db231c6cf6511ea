// The optional components a build of sward may leave out (CMake options SWARD_WITH_GDAL, SWARD_WITH_EMBREE,
// SWARD_WITH_OPENCV; docs/release.md, "A lean build"). This is the one place that knows which were built: a left-out
// component's code is replaced by a stub translation unit (io/raster_file_absent.cpp, range/ray_scene_absent.cpp,
// tools/sward-eval/absent.cpp) whose entry points throw requireComponent's error, and the scene parser asks here
// before anything is rendered or written.
#pragma once

#include <string>

namespace sward {

enum class Component {
    Gdal,   // rasters GDAL reads (io/raster_file.h): GeoTIFF and other heightmaps, land-cover maps
    Embree, // the range sensors' ray casting (range/ray_scene.h)
    OpenCv, // the evaluations of sward-eval (eval/)
};

// True when this build has the component.
bool hasComponent(Component component);

// Throws one sward::Error when the component is left out: "<what> needs GDAL, which this build of sward leaves out
// (SWARD_WITH_GDAL=OFF)"; `what` names the input that needs it ("scene.json: 'range_sensors'").
void requireComponent(Component component, const std::string& what);

} // namespace sward
