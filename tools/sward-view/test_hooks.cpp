#include "test_hooks.h"

#include "common/error.h"
#include "common/parse_number.h"
#include "scene/scene.h"

#include <GLFW/glfw3.h>

#include <sstream>

namespace sward {

std::vector<std::pair<uint64_t, int>> parsePresses(const std::string& text) {
    std::vector<std::pair<uint64_t, int>> presses;
    std::stringstream list(text);
    for (std::string item; std::getline(list, item, ',');) {
        size_t colon = item.find(':');
        std::string frame = item.substr(0, colon), key = colon == std::string::npos ? "" : item.substr(colon + 1);
        int code = GLFW_KEY_UNKNOWN;
        if (key.size() == 1 && key[0] >= 'a' && key[0] <= 'z')
            code = GLFW_KEY_A + (key[0] - 'a');
        else if (key.size() == 1 && key[0] >= '0' && key[0] <= '9')
            code = GLFW_KEY_0 + (key[0] - '0');
        else if (key == "space")
            code = GLFW_KEY_SPACE;
        else if (key == "f12")
            code = GLFW_KEY_F12;
        else if (key == "f1")
            code = GLFW_KEY_F1;
        else if (key == "esc")
            code = GLFW_KEY_ESCAPE;
        const std::string what = "bad --press item '" + item + "'";
        require(code != GLFW_KEY_UNKNOWN, what + ": expected FRAME:KEY with KEY a-z, 0-9, space, f1, f12 or esc");
        presses.emplace_back(parseUnsigned(frame, 0, UINT32_MAX, what + ": FRAME"), code);
    }
    return presses;
}

TestHooks::TestHooks(const ViewerOptions& options)
    : resizeAt_(options.resizeAt), minimizeAt_(options.minimizeAt), presses_(parsePresses(options.press)) {}

void TestHooks::apply(uint64_t frame, GLFWwindow* window, const std::function<void(int key)>& press) {
    if (resizeAt_ && frame == resizeAt_->first) {
        uint32_t w = 0, h = 0;
        parseResolution(resizeAt_->second, w, h);
        glfwSetWindowSize(window, int(w), int(h));
        resizeAt_.reset();
    }
    for (auto& [at, key] : presses_)
        if (at == frame) {
            press(key);
            at = UINT64_MAX; // once, even if this frame is not presented
        }
    if (minimizeAt_ && frame == *minimizeAt_) glfwIconifyWindow(window);
    if (minimizeAt_ && frame == *minimizeAt_ + 2) {
        glfwRestoreWindow(window);
        minimizeAt_.reset();
    }
}

} // namespace sward
