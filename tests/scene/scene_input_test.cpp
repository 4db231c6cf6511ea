// SceneInput: a scene from a file or JSON text with any key overridden before parsing (the Python module's
// overrides, the render job's scene), errors naming the key.
#include "scene/scene_input.h"

#include "common/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace sward;

namespace {

std::string errorOf(const SceneInput& input) {
    try {
        loadSceneInput(input);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

} // namespace

TEST(SceneInput, OverridesReplaceNestedKeysAndCreateMissingObjects) {
    const Scene scene = loadSceneInput(
        {.text = R"({"render": {"resolution": [640, 480], "samples": 4}})",
         .overrides = R"({"render.samples": 1, "sequence.frames": 7, "name": "overridden"})"});
    EXPECT_EQ(scene.render.width, 640u);
    EXPECT_EQ(scene.render.samples, 1u);
    EXPECT_EQ(scene.sequence.frames, 7u);
    EXPECT_EQ(scene.name, "overridden");
    EXPECT_EQ(scene.source, "<scene>");
}

TEST(SceneInput, ArrayElementsAreOverriddenByIndex) {
    const Scene scene = loadSceneInput(
        {.text = R"({"vehicles": [{"path": {"points": [[0, 0], [5, 0]]}, "weight": 2}]})",
         .overrides = R"({"vehicles.0.weight": 3.5})"});
    ASSERT_EQ(scene.actors.vehicles.size(), 1u);
    EXPECT_EQ(scene.actors.vehicles[0].weight, 3.5f);
}

TEST(SceneInput, BadOverridesAreOneErrorNamingTheKey) {
    EXPECT_EQ(errorOf({.text = R"({"vehicles": []})", .overrides = R"({"vehicles.2.weight": 1})"}),
              "overrides: 'vehicles.2.weight': '2' is not an index of an array of 0");
    // Keys missing from the scene are created, so the parser is the one to refuse what they lead to.
    EXPECT_EQ(errorOf({.overrides = R"({"render.samples.x": 1})"}),
              "<built-in>: 'render.samples' must be an integer in [1, 4] (got an object)");
    EXPECT_EQ(errorOf({.text = R"({"render": {"samples": 4}})", .overrides = R"({"render.samples.x": 1})"}),
              "overrides: 'render.samples.x' goes through a value that is not an object");
    EXPECT_EQ(errorOf({.overrides = R"({"render..samples": 1})"}), "overrides: 'render..samples' has an empty part");
    EXPECT_EQ(errorOf({.overrides = "[1]"}), "overrides: must be an object of dotted keys");
    EXPECT_NE(errorOf({.overrides = R"({"render.samples": 3})"}).find("'render.samples'"), std::string::npos);
}

TEST(SceneInput, TheSeedFollowsTheOverrides) {
    const Scene scene = loadSceneInput({.text = "{}", .overrides = R"({"seed": 5})", .seed = 9});
    EXPECT_EQ(scene.seed, 9u);
}

TEST(SceneInput, AFileIsReadLikeLoadScene) {
    const auto path = std::filesystem::temp_directory_path() / ("sward-scene-input-" + std::to_string(::getpid()) + ".json");
    std::ofstream(path) << R"({"name": "from-file", "render": {"samples": 4}})";
    const Scene viaInput = loadSceneInput({.path = path.string(), .overrides = R"({"render.samples": 1})"});
    const Scene viaLoad = loadScene(path.string());
    EXPECT_EQ(viaInput.name, "from-file");
    EXPECT_EQ(viaInput.source, path.string());
    EXPECT_EQ(viaInput.render.samples, 1u);
    EXPECT_EQ(viaLoad.render.samples, 4u);
    std::filesystem::remove(path);
}
