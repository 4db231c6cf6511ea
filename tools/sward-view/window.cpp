#include "window.h"

#include "common/error.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>

namespace sward {

namespace {

// GLFW is a process-wide library: initialised once per viewer run, errors turned into one-line messages.
std::string lastGlfwError;
bool glfwReady = false;

} // namespace

GlfwLibrary::GlfwLibrary() {
    // Until GLFW is up its errors become part of our one error line; afterwards they are logged.
    glfwSetErrorCallback([](int code, const char* text) {
        lastGlfwError = text;
        if (glfwReady) std::fprintf(stderr, "sward: GLFW error %d: %s\n", code, text);
    });
    const bool ok = glfwInit() == GLFW_TRUE; // before the message is built: it quotes GLFW's error
    require(ok, "cannot open a window: " + lastGlfwError + " (no display? headless, run it inside xvfb-run)");
    glfwReady = true;
    require(glfwVulkanSupported() == GLFW_TRUE, "GLFW found no Vulkan loader with window-system support");
}

GlfwLibrary::~GlfwLibrary() {
    glfwReady = false;
    glfwTerminate();
}

Window::Window(uint32_t width, uint32_t height, const std::string& title) {
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    handle = glfwCreateWindow(int(width), int(height), title.c_str(), nullptr, nullptr);
    require(handle != nullptr, "could not create a " + std::to_string(width) + "x" + std::to_string(height) + " window");
}

Window::~Window() { glfwDestroyWindow(handle); }

VkExtent2D Window::framebufferExtent() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(handle, &w, &h);
    return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
}

DeviceOptions windowDeviceOptions(const std::string& deviceFilter, bool validation, GLFWwindow* window) {
    DeviceOptions d{.deviceFilter = deviceFilter, .validation = validation || DeviceOptions{}.validation};
    uint32_t count = 0;
    const char** extensions = glfwGetRequiredInstanceExtensions(&count);
    require(extensions != nullptr, "GLFW cannot present Vulkan images on this display");
    d.instanceExtensions.assign(extensions, extensions + count);
    d.createSurface = [window](VkInstance instance) {
        VkSurfaceKHR surface = VK_NULL_HANDLE;
        VK_CHECK(glfwCreateWindowSurface(instance, window, nullptr, &surface));
        return surface;
    };
    return d;
}

} // namespace sward
