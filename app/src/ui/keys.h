// The window's keys, declared once: the key callback's dispatch (Ui::draw), the fly camera's
// held keys (the frame loop) and the help overlay (`?`) all read this table, so the overlay lists
// exactly the keys that work.
#pragma once

#include <string>
#include <vector>

namespace shadowlab {

enum class KeyAction {
    Screenshot, ToggleUi, Measure, SaveSession, Quit, Presenter, Help, PlayPath,
    NextStep, PreviousStep, RestartStep,
    FlyForward, FlyBack, FlyLeft, FlyRight, FlyUp, FlyDown,   // held, read every frame in fly mode
};

struct KeyBinding {
    int key;                  // GLFW_KEY_*
    const char* name;         // as the overlay shows it ("Page Down", "?")
    KeyAction action;
    const char* description;  // what it does, for the overlay
};

// Every binding, in the order the overlay lists them (several keys may share an action).
const std::vector<KeyBinding>& keyBindings();
// The bindings' keys for one action (the fly camera's held keys).
std::vector<int> keysFor(KeyAction action);
// The help overlay's lines: "name: description", one per action, keys of one action joined
// with " / ", and the mouse's (drag, wheel) after them.
std::vector<std::string> keyHelpLines();

} // namespace shadowlab
