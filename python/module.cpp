// _sward: the Python bindings of sward (python/sward/__init__.py is the API users see; docs/python.md). Thin: every
// call goes to render/session.h, render/render_job.h, scene/scene_input.h or the readers of io/, and converts
// arrays. sward::Error becomes sward.Error with the message the command-line tools print.
#include "common/error.h"
#include "common/half_float.h"
#include "common/json_reader.h"
#include "dataset/frame_truth.h"
#include "dataset/naming.h"
#include "io/disparity_files.h"
#include "io/image_files.h"
#include "io/image_io.h"
#include "range/range_files.h"
#include "recorder_bindings.h"
#include "render/render_job.h"
#include "render/session.h"
#include "scene/collider_params.h"
#include "scene/scene_input.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>

namespace py = pybind11;
using namespace sward;

namespace {

// A height x width (x channels) numpy array holding a copy of `values`.
template <typename T>
py::array_t<T> image(const std::vector<T>& values, uint32_t width, uint32_t height, uint32_t channels = 1) {
    std::vector<py::ssize_t> shape = {py::ssize_t(height), py::ssize_t(width)};
    if (channels > 1) shape.push_back(channels);
    py::array_t<T> out(shape);
    std::copy(values.begin(), values.end(), out.mutable_data());
    return out;
}

py::array_t<float> colour(const std::vector<uint16_t>& rendered, uint32_t width, uint32_t height) {
    const std::vector<uint16_t> half = colourWithCoverage(rendered);
    std::vector<float> rgba(half.size());
    for (size_t i = 0; i < half.size(); ++i) rgba[i] = halfBitsToFloat(half[i]); // exact
    return image(rgba, width, height, 4);
}

// A range sensor's sweep as the dataset's files hold it (range/range_files.h): per point, in firing order, "xyz"
// (sensor frame), "world", "intensity", "time", "ring", "column", "class", "instance" (and "tile" in a world of several
// tiles); a scanner's "ranges" per angle
// (NaN: no return); a ToF camera's planar "depth" image (+inf: no return).
py::dict rangeDict(const RangeSensorParams& sensor, const RangeScan& scan) {
    py::dict d;
    if (sensor.type == RangeSensorType::TimeOfFlight) {
        d["depth"] = image(tofDepth(sensor, scan), sensor.width, sensor.height);
        return d;
    }
    const py::ssize_t n = py::ssize_t(scan.points.size());
    py::array_t<float> xyz({n, py::ssize_t(3)}), intensity(n), time(n);
    py::array_t<double> world({n, py::ssize_t(3)});
    py::array_t<uint16_t> ring(n), column(n);
    py::array_t<uint8_t> semantic(n);
    py::array_t<uint32_t> instance(n);
    for (py::ssize_t i = 0; i < n; ++i) {
        const RangePoint& p = scan.points[size_t(i)];
        for (int k = 0; k < 3; ++k) xyz.mutable_at(i, k) = p.sensor[k], world.mutable_at(i, k) = p.world[k];
        intensity.mutable_at(i) = p.intensity, time.mutable_at(i) = p.time;
        ring.mutable_at(i) = uint16_t(p.ring), column.mutable_at(i) = uint16_t(p.column);
        semantic.mutable_at(i) = uint8_t(p.label >> gpu::kInstanceBits);
        instance.mutable_at(i) = p.label & ((1u << gpu::kInstanceBits) - 1u);
    }
    d["xyz"] = xyz, d["world"] = world, d["intensity"] = intensity, d["time"] = time;
    d["ring"] = ring, d["column"] = column, d["class"] = semantic, d["instance"] = instance;
    if (scan.tiles) { // a world: instance ids count within a tile (the PLY's tile property)
        py::array_t<uint32_t> tile(n);
        for (py::ssize_t i = 0; i < n; ++i) tile.mutable_at(i) = scan.points[size_t(i)].tile;
        d["tile"] = tile;
    }
    if (sensor.type == RangeSensorType::Scanner) {
        std::vector<float> ranges = scan.ranges;
        for (float& r : ranges) r = r > 0.0f ? r : std::nanf("");
        py::array_t<float> out(py::ssize_t(ranges.size()));
        std::copy(ranges.begin(), ranges.end(), out.mutable_data());
        d["ranges"] = out;
    }
    return d;
}

// The frame as numpy arrays, named and converted as the dataset's files hold them (dataset/frame_truth.h); with
// range sensors, "range": {sensor name: rangeDict}.
py::dict frameDict(const SessionFrame& f, const std::vector<RangeSensorParams>& sensors) {
    const FrameImages& im = f.images;
    const uint32_t w = im.width, h = im.height;
    const FrameTruth truth = frameTruth(im, f.cameras.left.fx, f.baseline);
    std::vector<uint32_t> instance(truth.instance.size());
    for (size_t i = 0; i < instance.size(); ++i) instance[i] = uint32_t(truth.instance[i]);
    py::dict d;
    d["frame"] = f.frame;
    addFrameRecord(d, f); // tick, time, poses, intrinsics, baseline, record
    d["left"] = colour(im.rgbaHalf, w, h);
    d["depth"] = image(im.depth, w, h);
    d["semantic"] = image(truth.semantic, w, h);
    d["instance"] = image(instance, w, h);
    if (!im.tiles.empty()) d["tile"] = image(im.tiles, w, h);
    d["normal"] = image(im.normals, w, h, 3);
    d["preview"] = image(tonemapPreview(im.rgbaHalf, w, h), w, h, 3);
    if (f.baseline > 0.0) {
        d["right"] = colour(im.rightRgbaHalf, w, h);
        d["disparity"] = image(truth.disparity, w, h);
        d["depth_right"] = image(im.rightDepth, w, h);
        d["disparity_right"] = image(truth.rightDisparity, w, h);
        d["normal_right"] = image(im.rightNormals, w, h, 3);
        d["preview_right"] = image(tonemapPreview(im.rightRgbaHalf, w, h), w, h, 3);
    }
    if (im.autoExposure) { // camera.sensor.auto_exposure: as auto_exposure/NNNNNN.json records it
        py::dict exposure;
        exposure["meter"] = im.autoExposure->meter, exposure["factor"] = im.autoExposure->factor;
        d["auto_exposure"] = exposure;
    }
    if (!f.range.empty()) {
        py::dict range;
        for (size_t k = 0; k < f.range.size() && k < sensors.size(); ++k)
            range[py::str(sensors[k].name)] = rangeDict(sensors[k], f.range[k]);
        d["range"] = range;
    }
    return d;
}

std::optional<glm::dvec3> point(const std::optional<std::vector<double>>& v, const char* name) {
    if (!v) return std::nullopt;
    require(v->size() == 3, std::string(name) + " must be 3 numbers x, y, z");
    return glm::dvec3((*v)[0], (*v)[1], (*v)[2]);
}

// An image file as stored: EXR as float32, PNG as uint8 / uint16 (io/image_io.h reads samples normalised). With
// `channel`, that one channel of an EXR.
py::array readImage(const std::string& path, const std::string& channel) {
    ImageData im;
    {
        py::gil_scoped_release release;
        im = channel.empty() ? loadImage(path) : loadExrChannel(path, channel);
    }
    if (im.bitDepth == 32) return image(im.samples, im.width, im.height, im.channels);
    const float scale = im.bitDepth == 16 ? 65535.0f : 255.0f;
    std::vector<uint16_t> values(im.samples.size());
    for (size_t i = 0; i < values.size(); ++i) values[i] = uint16_t(std::lround(im.samples[i] * scale));
    if (im.bitDepth == 16) return image(values, im.width, im.height, im.channels);
    return image(std::vector<uint8_t>(values.begin(), values.end()), im.width, im.height, im.channels);
}

py::array_t<float> readDisparityFile(const std::string& path) {
    DisparityMap map;
    {
        py::gil_scoped_release release;
        map = readDisparity(path);
    }
    return image(map.values, map.width, map.height);
}

py::dict readCalib(const std::string& path) {
    const StereoCalib c = readMiddleburyCalib(path);
    py::dict d;
    d["cam0"] = c.cam0;
    d["cam1"] = c.cam1;
    d["doffs"] = c.doffs;
    d["baseline_mm"] = c.baselineMm;
    d["width"] = c.width;
    d["height"] = c.height;
    d["ndisp"] = c.ndisp;
    d["vmin"] = c.vmin;
    d["vmax"] = c.vmax;
    return d;
}

SceneInput sceneInput(const std::string& path, const std::optional<std::string>& text, const std::string& overrides,
                      std::optional<uint64_t> seed, const std::vector<std::string>& allowAssets) {
    return SceneInput{
        .path = path, .text = text, .overrides = overrides, .seed = seed, .allowedAssetDirs = allowAssets};
}

// Semantic class name -> pixel value (dataset/naming.h); with a scene's category names, each vegetation category's
// value under its name too ("grass" as well as "vegetation category 0"), as classes.json's "scene_name" gives it.
py::dict classNames(const std::vector<std::string>& categoryNames) {
    py::dict classes;
    for (const SemanticClass& c : semanticClasses()) classes[py::str(c.name)] = c.id;
    for (const SemanticClass& c : semanticClasses()) {
        const uint32_t category = c.id - gpu::kSemanticVegetation;
        if (c.id >= gpu::kSemanticVegetation && category < categoryNames.size() &&
            !classes.contains(categoryNames[category]))
            classes[py::str(categoryNames[category])] = c.id;
    }
    return classes;
}

std::vector<std::string> categoryNames(const Session& s) {
    const VegetationParams& vegetation = s.resources().scene.vegetation;
    std::vector<std::string> names;
    for (uint32_t c = 0; c < vegetation.categoryCount; ++c) names.push_back(vegetation.categories[c].name);
    return names;
}

// Ctrl-C (or any signal handler that raises) during a long call: the Python exception, thrown through the C++ core,
// which unwinds as on any failure. Called with the GIL released.
void throwIfInterrupted() {
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
}

// Tick by tick, so that Ctrl-C stops a long step within a tick. With auto-exposure one call: it renders only the
// last W ticks for their meter, where W calls of step(1) would render one frame each.
void stepTicks(Session& s, uint32_t ticks) {
    py::gil_scoped_release release;
    if (s.autoExposed()) return s.step(ticks);
    for (uint32_t i = 0; i < ticks; ++i) {
        s.step(1);
        throwIfInterrupted();
    }
}

std::unique_ptr<Session> openSession(const std::string& path, const std::optional<std::string>& text,
                                     const std::string& overrides, std::optional<uint64_t> seed,
                                     const std::vector<std::string>& allowAssets, const SessionOptions& options) {
    py::gil_scoped_release release;
    return std::make_unique<Session>(loadSceneInput(sceneInput(path, text, overrides, seed, allowAssets)), options);
}

void bindSession(py::module_& m) {
    py::class_<Session>(m, "Session")
        .def(py::init([](const std::string& path, const std::optional<std::string>& text, const std::string& overrides,
                         std::optional<uint64_t> seed, const std::vector<std::string>& allowAssets,
                         const std::string& device, bool validation, bool vegetation, double time) {
            return openSession(path, text, overrides, seed, allowAssets,
                               SessionOptions{device, validation, vegetation, time});
        }))
        .def_property_readonly("frame", &Session::frame)
        .def_property_readonly("width", &Session::width)
        .def_property_readonly("height", &Session::height)
        .def_property_readonly("stereo", [](const Session& s) { return s.resources().scene.camera.rig.stereo(); })
        .def_property_readonly("object_count", [](const Session& s) { return s.resources().scene.objects.size(); })
        .def_property_readonly("device_name", [](const Session& s) { return s.device().name(); })
        .def_property_readonly("validation_messages",
                               [](const Session& s) { return s.device().validationMessageCount(); })
        .def_property_readonly("classes", [](const Session& s) { return classNames(categoryNames(s)); })
        .def("step", &stepTicks)
        .def("render",
             [](Session& s) {
                 SessionFrame f;
                 {
                     py::gil_scoped_release release;
                     f = s.render();
                 }
                 return frameDict(f, s.resources().scene.rangeSensors);
             })
        .def("set_camera",
             [](Session& s, const std::optional<std::vector<double>>& position,
                const std::optional<std::vector<double>>& lookAt,
                std::optional<double> fov) { s.setCamera(point(position, "position"), point(lookAt, "look_at"), fov); })
        .def("set_object_pose", [](Session& s, size_t k, double x, double y,
                                   double heading) { s.setObjectPose(k, glm::dvec2(x, y), heading); })
        .def("set_colliders",
             [](Session& s, const std::string& json) {
                 s.setColliders(parsePlacedColliders(parseJsonText(json, "colliders", "colliders"), "colliders"));
             })
        .def("save_state", &Session::saveState, py::call_guard<py::gil_scoped_release>())
        .def("restore_state", &Session::restoreState, py::call_guard<py::gil_scoped_release>());
}

// `progress(rendered, total)` (Python, may be None) and Ctrl-C, before each frame and at the end of a run; called
// with the GIL released. A handle, not an object: copying the hook then touches no reference count (the caller's
// argument keeps the callable alive for the run).
std::function<void(uint32_t, uint32_t)> progressHook(py::handle progress) {
    return [progress](uint32_t rendered, uint32_t total) {
        throwIfInterrupted();
        if (progress.is_none()) return;
        py::gil_scoped_acquire acquire;
        progress(rendered, total);
    };
}

void writeDataset(const std::string& path, const std::optional<std::string>& text, const std::string& overrides,
                  std::optional<uint64_t> seed, const std::vector<std::string>& allowAssets, const std::string& out,
                  const std::optional<std::string>& frames, const std::optional<std::string>& shard, bool overwrite,
                  const std::string& device, bool validation, bool vegetation, double time,
                  const py::object& progress) {
    RenderJobOptions o = sceneJobOptions(path, text, overrides, seed, allowAssets, vegetation, time);
    o.outDir = out;
    o.frames = frames;
    o.shard = shard;
    o.overwrite = overwrite;
    o.device = device;
    o.validation = validation;
    o.quiet = true;
    o.onProgress = progressHook(progress);
    py::gil_scoped_release release;
    runRenderJob(o);
}

} // namespace

PYBIND11_MODULE(_sward, m) {
    m.doc() = "sward's C++ core; use the sward package (docs/python.md)";
    m.attr("__version__") = SWARD_VERSION; // CMakeLists.txt's project() version, the package's (setup.py)
    py::register_exception<Error>(m, "Error", PyExc_RuntimeError);
    bindSession(m);
    bindRecorder(m);
    m.def("write_dataset", &writeDataset);
    m.def("read_image", &readImage, py::arg("path"), py::arg("channel") = "");
    m.def("image_channels", &exrChannelNames);
    m.def("read_disparity", &readDisparityFile);
    m.def("read_calib", &readCalib);
    m.def("frame_file", [](const std::string& folder, uint32_t frame, const std::string& extension) {
        return frameFile(folder.c_str(), frame, extension.c_str());
    });
    m.def("frame_number", &frameNumber);
    py::dict names;
    for (auto [key, value] : {std::pair{"left", kLeftFolder},
                              {"right", kRightFolder},
                              {"depth", kDepthFolder},
                              {"disparity", kDisparityFolder},
                              {"semantic", kSemanticFolder},
                              {"instance", kInstanceFolder},
                              {"normal", kNormalFolder},
                              {"depth_right", kDepthRightFolder},
                              {"disparity_right", kDisparityRightFolder},
                              {"normal_right", kNormalRightFolder},
                              {"preview", kPreviewFolder},
                              {"preview_right", kPreviewRightFolder},
                              {"calib", kCalibFile},
                              {"frame_log", kFrameLogFile},
                              {"manifest", kManifestFile},
                              {"dataset", kDatasetFile},
                              {"classes", kClassesFile},
                              {"range", kRangeFolder}})
        names[key] = value;
    m.attr("NAMES") = names;
    m.attr("SEMANTIC_CLASSES") = classNames({});
}
