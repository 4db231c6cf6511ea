#include "input.h"

#include "common/error.h"

#include <GLFW/glfw3.h>

namespace sward {

void applyKey(int key, PanelState& panel, bool& uiVisible, GLFWwindow* window) {
    switch (key) {
    case GLFW_KEY_ESCAPE:
        glfwSetWindowShouldClose(window, GLFW_TRUE);
        break;
    case GLFW_KEY_F:
        panel.toggleDrive = true;
        break;
    case GLFW_KEY_SPACE:
        panel.paused = !panel.paused;
        break;
    case GLFW_KEY_N:
        panel.step = true;
        break;
    case GLFW_KEY_F12:
    case GLFW_KEY_P:
        panel.screenshot = true;
        break;
    case GLFW_KEY_R:
        panel.reload = true;
        break;
    case GLFW_KEY_H:
        uiVisible = !uiVisible;
        break;
    case GLFW_KEY_F1:
        toggleKeysHelp(panel, uiVisible);
        break;
    case GLFW_KEY_M:
        panel.msaa = !panel.msaa;
        break;
    case GLFW_KEY_1:
        panel.lodColors = !panel.lodColors;
        break;
    case GLFW_KEY_2:
        panel.activeFields = !panel.activeFields;
        break;
    case GLFW_KEY_3:
        panel.updatedPlants = !panel.updatedPlants;
        break;
    case GLFW_KEY_4:
        panel.clusterBounds = !panel.clusterBounds;
        break;
    case GLFW_KEY_5:
        panel.colliders = !panel.colliders;
        break;
    default:
        break;
    }
}

void toggleKeysHelp(PanelState& panel, bool& uiVisible) {
    panel.keysHelp = !panel.keysHelp;
    uiVisible = uiVisible || panel.keysHelp; // the list is drawn with the panel
}

void enableOverlays(PanelState& panel, const std::string& overlays) {
    for (std::string item; const char c : overlays + ",") {
        if (c != ',') {
            item += c;
            continue;
        }
        if (item == "lod")
            panel.lodColors = true;
        else if (item == "active-fields")
            panel.activeFields = true;
        else if (item == "updated-plants")
            panel.updatedPlants = true;
        else if (item == "clusters")
            panel.clusterBounds = true;
        else if (item == "colliders")
            panel.colliders = true;
        else if (!item.empty())
            throw Error("unknown overlay '" + item + "' (use lod, active-fields, updated-plants, clusters, colliders)");
        item.clear();
    }
}

FlyInput FlyControls::read(GLFWwindow* window, bool keys, bool panelHasMouse) {
    auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS; };
    // Mouse look while the right button is held (or the left one outside the panel).
    bool wantLook = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS ||
                    (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS && !panelHasMouse);
    glm::dvec2 cursor;
    glfwGetCursorPos(window, &cursor.x, &cursor.y);
    FlyInput input;
    if (wantLook && looking_) input.turn = cursor - lastCursor_;
    looking_ = wantLook;
    lastCursor_ = cursor;
    if (keys) {
        input.move.y = (down(GLFW_KEY_W) ? 1.0 : 0.0) - (down(GLFW_KEY_S) ? 1.0 : 0.0);
        input.move.x = (down(GLFW_KEY_D) ? 1.0 : 0.0) - (down(GLFW_KEY_A) ? 1.0 : 0.0);
        input.move.z = (down(GLFW_KEY_E) ? 1.0 : 0.0) - (down(GLFW_KEY_Q) ? 1.0 : 0.0);
        input.fast = down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT);
    }
    return input;
}

double FlyControls::takeScroll() {
    double notches = scroll_;
    scroll_ = 0.0;
    return notches;
}

} // namespace sward
