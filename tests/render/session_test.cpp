// Session (the Python module's engine): frames are a function of the frame number whatever way the session got
// there, state files continue bitwise, and program errors are one clear message.
#include "render/session.h"

#include "gpu_test.h"
#include "scene/collider_params.h"
#include "scene/scene_input.h"

#include <gtest/gtest.h>

using namespace sward;

namespace {

Scene smallScene() {
    return loadSceneInput({.path = std::string(SWARD_TEST_DATA_DIR) + "/dataset_scene.json",
                           .overrides = R"({"render.resolution": [96, 64], "render.samples": 1})"});
}

} // namespace

TEST(Session, AStepThenARenderEqualsRenderingEveryFrame) {
    Session rendered(smallScene(), SessionOptions{.validation = true});
    rendered.render();
    const SessionFrame second = rendered.render();
    Session stepped(smallScene(), SessionOptions{.validation = true});
    stepped.step(1);
    const SessionFrame again = stepped.render();
    EXPECT_EQ(second.frame, 1u);
    EXPECT_EQ(again.frame, 1u);
    EXPECT_EQ(second.images.rgbaHalf, again.images.rgbaHalf);
    EXPECT_EQ(second.images.labels, again.images.labels);
    EXPECT_EQ(rendered.device().validationMessageCount(), 0u);
}

TEST(Session, ErrorsNameTheCallAndLeaveTheSessionUsable) {
    Session session(smallScene(), SessionOptions{.validation = true});
    try {
        session.setObjectPose(0, glm::dvec2(0.0), 0.0);
        FAIL() << "posed an object the scene does not have";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "set_object_pose: no object 0 (the scene has 0)");
    }
    EXPECT_THROW(session.setCamera(glm::dvec3(50, 50, 2), glm::dvec3(50, 50, 2), std::nullopt), Error);
    session.setColliders(parsePlacedColliders(nlohmann::json::parse(R"([{"centre": [50, 51, 0]}])"), "colliders"));
    EXPECT_EQ(session.render().frame, 0u); // the refused camera left the scene's in place
}
