// The window's keys (see keys.h).
#include "ui/keys.h"

#include "gl/gl.h"   // glad before GLFW (unity batches)

#include <GLFW/glfw3.h>

namespace shadowlab {

const std::vector<KeyBinding>& keyBindings() {
    // '?' is Shift and '/' on the keyboards GLFW reports by position; the key alone opens it too.
    static const std::vector<KeyBinding> bindings = {
        {GLFW_KEY_SLASH, "?", KeyAction::Help, "this list of keys (again: close it)"},
        {GLFW_KEY_P, "P", KeyAction::Presenter, "presenter mode: full screen, the caption large, no panel"},
        {GLFW_KEY_F1, "F1", KeyAction::ToggleUi, "hide or show the panel"},
        {GLFW_KEY_H, "H", KeyAction::ToggleUi, "hide or show the panel"},
        {GLFW_KEY_RIGHT, "Right", KeyAction::NextStep, "tour: next step"},
        {GLFW_KEY_PAGE_DOWN, "Page Down", KeyAction::NextStep, "tour: next step"},
        {GLFW_KEY_LEFT, "Left", KeyAction::PreviousStep, "tour: previous step"},
        {GLFW_KEY_PAGE_UP, "Page Up", KeyAction::PreviousStep, "tour: previous step"},
        {GLFW_KEY_HOME, "Home", KeyAction::RestartStep, "tour: restart the step (its path from frame 1)"},
        {GLFW_KEY_SPACE, "Space", KeyAction::PlayPath, "pause or play the camera or light path"},
        {GLFW_KEY_M, "M", KeyAction::Measure, "measure accuracy against the reference (heatmap)"},
        {GLFW_KEY_F12, "F12", KeyAction::Screenshot, "save a screenshot under screenshots/"},
        {GLFW_KEY_F5, "F5", KeyAction::SaveSession, "save the session under sessions/"},
        {GLFW_KEY_W, "W", KeyAction::FlyForward, "fly camera: forward"},
        {GLFW_KEY_S, "S", KeyAction::FlyBack, "fly camera: back"},
        {GLFW_KEY_A, "A", KeyAction::FlyLeft, "fly camera: left"},
        {GLFW_KEY_D, "D", KeyAction::FlyRight, "fly camera: right"},
        {GLFW_KEY_E, "E", KeyAction::FlyUp, "fly camera: up"},
        {GLFW_KEY_Q, "Q", KeyAction::FlyDown, "fly camera: down"},
        {GLFW_KEY_ESCAPE, "Escape", KeyAction::Quit, "quit"},
    };
    return bindings;
}

std::vector<int> keysFor(KeyAction action) {
    std::vector<int> keys;
    for (const KeyBinding& binding : keyBindings())
        if (binding.action == action) keys.push_back(binding.key);
    return keys;
}

std::vector<std::string> keyHelpLines() {
    std::vector<std::string> lines;
    const auto& bindings = keyBindings();
    for (size_t i = 0; i < bindings.size(); ++i) {
        bool seen = false;
        for (size_t j = 0; j < i; ++j) seen |= bindings[j].action == bindings[i].action;
        if (seen) continue;
        std::string names = bindings[i].name;
        for (size_t j = i + 1; j < bindings.size(); ++j)
            if (bindings[j].action == bindings[i].action) names += std::string(" / ") + bindings[j].name;
        lines.push_back(names + ": " + bindings[i].description);
    }
    lines.push_back("left drag: orbit (fly: look); middle drag: pan; wheel: zoom");
    lines.push_back("wipe: drag the round handle on the divider");
    return lines;
}

} // namespace shadowlab
