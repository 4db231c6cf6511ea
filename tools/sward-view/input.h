// Input: what the user's keys and mouse do in the viewer. Key presses (typed or injected by TestHooks) toggle
// panel settings and raise its one-shot requests; held keys and the mouse move the fly camera. The rover's
// arrow keys are read by RoverControl, once per simulation tick.
#pragma once

#include "fly_camera.h"
#include "ui.h"

#include <glm/glm.hpp>

#include <string>

struct GLFWwindow;

namespace sward {

// One key press (GLFW key code): Esc closes `window`, H toggles `uiVisible`, the others edit `panel`.
void applyKey(int key, PanelState& panel, bool& uiVisible, GLFWwindow* window);
// F1 or a typed '?': shows or hides the keys window (and shows the panel with it).
void toggleKeysHelp(PanelState& panel, bool& uiVisible);
// --overlay "lod,active-fields,...": switches those overlays on in `panel`; throws sward::Error for an unknown one.
void enableOverlays(PanelState& panel, const std::string& overlays);

// The fly camera's input: WASD / Q E / shift and mouse look (the cursor's motion while a button is held).
class FlyControls {
public:
    // This frame's input from `window`: keys only when `keys`; the left button looks only when not
    // `panelHasMouse` (the right one always).
    FlyInput read(GLFWwindow* window, bool keys, bool panelHasMouse);
    // Scroll-wheel notches since the last takeScroll() (the GLFW scroll callback adds them).
    void addScroll(double notches) { scroll_ += notches; }
    double takeScroll();

private:
    bool looking_ = false;
    glm::dvec2 lastCursor_{0.0};
    double scroll_ = 0.0;
};

} // namespace sward
