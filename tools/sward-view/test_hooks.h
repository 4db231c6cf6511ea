// TestHooks: the viewer's scripted actions for headless tests (--resize-at, --minimize-at, --press). They go
// through the same code paths a user's actions take: GLFW window calls and the key handler.
#pragma once

#include "viewer.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

struct GLFWwindow;

namespace sward {

// "FRAME:KEY,..." -> (frame, GLFW key) pairs. KEY: a-z, 0-9, space, f12 or esc; throws sward::Error otherwise.
std::vector<std::pair<uint64_t, int>> parsePresses(const std::string& text);

class TestHooks {
public:
    // Throws sward::Error for a bad --press list.
    explicit TestHooks(const ViewerOptions& options);
    // Does what is due at `frame`: resizes, minimises or restores `window` and presses keys through `press`.
    // Each action happens once, even if the frame is then not presented.
    void apply(uint64_t frame, GLFWwindow* window, const std::function<void(int key)>& press);

private:
    std::optional<std::pair<uint32_t, std::string>> resizeAt_;
    std::optional<uint32_t> minimizeAt_;
    std::vector<std::pair<uint64_t, int>> presses_;
};

} // namespace sward
