#include "recorder_bindings.h"

#include "render/episode_recorder.h"
#include "scene/scene_input.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace sward {

namespace {

// A JSON value as the Python value json.loads gives (dicts, lists, floats, ints, str, None).
py::object pythonValue(const nlohmann::json& value) {
    return py::module_::import("json").attr("loads")(value.dump());
}

// A row-major 4x4 of frames.jsonl as a float64 numpy array (JSON keeps every double exactly).
py::array_t<double> matrix(const nlohmann::json& rows) {
    py::array_t<double> out({4, 4});
    for (py::ssize_t i = 0; i < 4; ++i)
        for (py::ssize_t j = 0; j < 4; ++j) out.mutable_at(i, j) = rows.at(size_t(i)).at(size_t(j)).get<double>();
    return out;
}

std::unique_ptr<EpisodeRecorder> openRecorder(Session& session, const std::string& path,
                                              const std::optional<std::string>& text, const std::string& overrides,
                                              std::optional<uint64_t> seed, const std::vector<std::string>& allowAssets,
                                              bool vegetation, double time, const std::string& out, bool overwrite) {
    const RenderJobOptions source = sceneJobOptions(path, text, overrides, seed, allowAssets, vegetation, time);
    py::gil_scoped_release release;
    return std::make_unique<EpisodeRecorder>(session, source, out, overwrite);
}

py::dict vehicleDict(const VehicleState& state) {
    py::dict d;
    d["position"] = py::make_tuple(state.position.x, state.position.y);
    d["heading_deg"] = state.headingDegrees;
    d["speed"] = state.speed;
    return d;
}

} // namespace

RenderJobOptions sceneJobOptions(const std::string& path, const std::optional<std::string>& text,
                                 const std::string& overrides, std::optional<uint64_t> seed,
                                 const std::vector<std::string>& allowAssets, bool vegetation, double time) {
    RenderJobOptions o;
    o.scenePath = path;
    o.sceneText = text;
    o.overrides = overrides;
    o.seed = seed;
    o.allowAssets = allowAssets;
    o.noVegetation = !vegetation;
    o.time = time;
    return o;
}

void addFrameRecord(py::dict& d, const SessionFrame& frame) {
    const nlohmann::json& record = frame.record;
    d["tick"] = record.at("tick").get<uint64_t>();
    d["time"] = record.at("time").get<double>();
    d["left_pose"] = matrix(record.at("left_pose"));
    if (record.contains("right_pose")) {
        d["right_pose"] = matrix(record.at("right_pose"));
        d["baseline"] = record.at("baseline").get<double>();
    }
    d["intrinsics"] = pythonValue(record.at("intrinsics"));
    d["record"] = pythonValue(record);
}

void bindRecorder(py::module_& m) {
    py::class_<EpisodeRecorder>(m, "EpisodeRecorder")
        .def(py::init(&openRecorder), py::keep_alive<1, 2>()) // the session lives as long as its recorder
        .def("close", &EpisodeRecorder::close, py::call_guard<py::gil_scoped_release>())
        .def_property_readonly("closed", &EpisodeRecorder::closed)
        .def_property_readonly("frames", &EpisodeRecorder::frames)
        .def_property_readonly("out", &EpisodeRecorder::outDir);
    m.def("reset",
          [](Session& session, bool restart, const std::string& path, const std::optional<std::string>& text,
             const std::string& overrides, std::optional<uint64_t> seed, const std::vector<std::string>& allowAssets) {
              py::gil_scoped_release release;
              if (restart) return session.reset();
              session.reset(loadSceneInput(SceneInput{
                  .path = path, .text = text, .overrides = overrides, .seed = seed, .allowedAssetDirs = allowAssets}));
          });
    m.def("set_weather", [](Session& session, const std::string& key, const std::string& json) {
        session.setWeather(key, nlohmann::json::parse(json));
    });
    m.def("drive", [](Session& session, size_t vehicle, double throttle, double steer, double brake) {
        return vehicleDict(
            session.drive(vehicle, VehicleCommand{.throttle = throttle, .steer = steer, .brake = brake}));
    });
}

} // namespace sward
