#include "common/optional_components.h"

#include "common/error.h"

// common/CMakeLists.txt defines these as 0 or 1 for this file only, from the CMake options.
#if !defined(SWARD_WITH_GDAL) || !defined(SWARD_WITH_EMBREE) || !defined(SWARD_WITH_OPENCV)
#error "common/optional_components.cpp is compiled with SWARD_WITH_GDAL, SWARD_WITH_EMBREE and SWARD_WITH_OPENCV"
#endif

namespace sward {

namespace {

struct ComponentInfo {
    const char* name;   // as users know it
    const char* option; // the CMake option that leaves it out
    bool built;
};

ComponentInfo infoOf(Component component) {
    switch (component) {
    case Component::Gdal:
        return {"GDAL", "SWARD_WITH_GDAL", SWARD_WITH_GDAL != 0};
    case Component::Embree:
        return {"Embree", "SWARD_WITH_EMBREE", SWARD_WITH_EMBREE != 0};
    case Component::OpenCv:
        return {"OpenCV", "SWARD_WITH_OPENCV", SWARD_WITH_OPENCV != 0};
    }
    throw Error("unknown optional component");
}

} // namespace

bool hasComponent(Component component) {
    return infoOf(component).built;
}

void requireComponent(Component component, const std::string& what) {
    const ComponentInfo info = infoOf(component);
    if (!info.built)
        throw Error(what + " needs " + info.name + ", which this build of sward leaves out (" + info.option + "=OFF)");
}

} // namespace sward
