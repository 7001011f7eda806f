// The fuzzing harness's entry points, shared by the libFuzzer targets (fuzz_*.cpp, built by
// tests/fuzz/CMakeLists.txt with clang, ASan and UBSan) and by the regression test that replays
// every file in tests/fuzz/regressions and the seed corpus in the ordinary suite
// (tests/test_fuzz_regressions.cpp).
//
// Each feeds one input to a reader and checks what a reader promises: it either succeeds, with a
// result that holds its invariants, or reports the problem in the way it documents (a SceneError,
// or false with a message). Anything else (another exception, a crash, a sanitizer report, a run
// past libFuzzer's -timeout, memory past -rss_limit_mb) is a finding. A broken promise calls
// std::abort() after printing what was broken, so libFuzzer saves the input. Each returns whether
// the input was accepted (the regression test checks that saved "refused-*" inputs stay refused).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace shadowlab::fuzz {

// A small budget, so that inputs at the budget stay fast (the budget's logic is the same).
void useFuzzBudget();

// A scene file: parseScene and checkSceneText must agree (both fail, or both succeed with the same
// counts); a parsed scene holds valid indices, finite transforms and geometry within the budget.
// OBJ files named by the input resolve in `objDir`.
bool fuzzScene(const uint8_t* data, size_t size, const std::filesystem::path& objDir);
// An OBJ file: parseObj either throws SceneError or gives triangles with valid indices and finite,
// unit normals; tinyobjloader never reads differently from what our pre-scan checked.
bool fuzzObj(const uint8_t* data, size_t size);
// A benchmark spec (JSON); if the input is not JSON, its lines are tried as command-line values
// (--sweep, --size, --budget). Nothing may throw; checkBenchSpec runs against a fixed technique list.
bool fuzzBenchSpec(const uint8_t* data, size_t size);
// A guided tour (JSON; a session file when the input is one step object): parseTour/parseTourStep
// and checkTour against a fixed technique list. Errors name "fuzz-tour.json"; an accepted tour
// holds only known techniques and parameters in range, and its steps written back as JSON
// (tourStepJson, a saved session) read back as the same steps.
bool fuzzTour(const uint8_t* data, size_t size);

// A session file (`--session`, the window's "Load session"): parseSessionText, the reader
// loadSession uses, against a fixed technique list. Errors name "fuzz-session.json"; an accepted
// session holds a known technique, a usable camera (scene.h's cameraProblem) and light direction,
// and written back as JSON (what F5 saves) reads back as the same step.
bool fuzzSession(const uint8_t* data, size_t size);

// A camera and light path (scene/camera_path.h) and, read from the same JSON, a stress cases file
// (bench/stress.h): each either parses, with finite keyframes and samples, or fails with a message
// naming the source. A path counts as accepted when a scene with the default camera and a spot
// light would also take every frame of it (pathProblem). Returns whether either accepted it.
bool fuzzPath(const uint8_t* data, size_t size);

// A texture file (PNG, the one image format scenes take): decodePngTexture either gives a texture
// of 1 to kMaxTextureSize texels a side with all its texels, or a SceneError naming the file.
bool fuzzTexture(const uint8_t* data, size_t size);

} // namespace shadowlab::fuzz
