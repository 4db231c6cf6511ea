// The viewer's window: GLFW (initialised once per viewer run) and the Vulkan device options that let the
// device present into it.
#pragma once

#include "engine/context.h"

#include <cstdint>
#include <string>

struct GLFWwindow;

namespace sward {

// GLFW for the lifetime of this object. Throws sward::Error (quoting GLFW's reason) when no window can be
// opened, e.g. without a display.
struct GlfwLibrary {
    GlfwLibrary();
    ~GlfwLibrary();
    GlfwLibrary(const GlfwLibrary&) = delete;
    GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

struct Window {
    GLFWwindow* handle = nullptr;
    Window(uint32_t width, uint32_t height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;
    // The framebuffer size in pixels (0 x 0 while minimised).
    VkExtent2D framebufferExtent() const;
};

// Device options for device name substring `deviceFilter` that add GLFW's instance extensions and create the
// surface of `window`; validation is on when `validation` is or the default (SWARD_VALIDATION) asks for it.
DeviceOptions windowDeviceOptions(const std::string& deviceFilter, bool validation, GLFWwindow* window);

} // namespace sward
