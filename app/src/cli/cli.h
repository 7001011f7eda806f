// The command line, one file per command (app/src/cli/<command>.cpp). Each command declares its
// own options on the parser and runs when it was given; main() parses and dispatches:
//   shadowlab                 the main job (window.cpp): the window if a display exists, else the
//                             report (every technique rendered to out/images, timings, charts)
//   shadowlab list [--json]   techniques and their parameters (no GL needed)
//   shadowlab render ...      one frame headless to a PNG (a path's frames, a comparison, a probe)
//   shadowlab eval | bench | stress | report | tour | reload-latency
// Exit codes: 0 success, 1 failure of the machine (no GL, ...), 2 bad input (with a message).
// Every input is checked before the first frame.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "groundtruth/groundtruth.h"
#include "plugin/plugin_library.h"
#include "ui/session.h"

namespace shadowlab {
class App;
}

namespace shadowlab::cli {

constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

// Options every command takes (scene, technique, output).
struct CommonOptions {
    std::string scene;
    std::vector<std::string> sceneParams;
    std::string technique;
    std::string backend;
    std::string size = "1280x720";
    std::vector<std::string> sets;
    std::string lightDirection;
    std::string lightSize;      // text: checked against the scene's light type once it is known
    int msaa = 0;
    std::string depthPrepass;   // auto | on | off (or 1/0); empty: not given (host.depth_prepass's default)
    int translucentLayers = 4;
    std::string referenceDevice = "cpu";
    std::string budget;
    bool quiet = false;
};
void addCommonOptions(CLI::App& cmd, CommonOptions& o);
std::optional<double> lightSizeOption(const CommonOptions& common);
// Logs `error` and returns `code`.
int fail(const std::string& error, int code);
// The technique a command runs (empty: the first found) and every --set on it, checked against
// the techniques' descriptors before the App starts: a refused option costs no GL context (0.3 s
// in Release, 1.2 s under ASan). The App checks them again where it applies them (0: fine).
int techniqueOptionsProblem(const std::string& technique, const std::vector<std::string>& sets);
// Creates the App headless (or windowed) and reports errors with the right exit code (0: started).
int startApp(App& app, const CommonOptions& common, bool windowed);
// The rules every command's options follow, checked once for all of them (main.cpp):
//   - no option takes an empty value (`--scene ''`, `--techniques ''`): an empty value would read
//     as "unset" or "all" (CLI11 validator on every option that takes a value);
//   - `--set` and `--scene-param` name each key once (the last would win unseen);
//   - a common option the command does not use is refused (Command::unusedCommonOptions).
void requireNonEmptyValues(CLI::App& app);
int repeatedKeyProblem(const CommonOptions& common);
// A comma-separated option's items (util/strings.h's splitList: an empty item is an error naming
// `option`); "" (the option not given) gives no items.
bool optionList(const std::string& text, const std::string& option, std::vector<std::string>& items, std::string& error);
// An output checked before the first frame: `file` can be created or written (its folder is
// created), or, with `folder`, the folder can be created and a file written in it. Exit 2 with
// `option` and the reason otherwise; a write that fails later (a full disk) is still exit 1.
bool outputProblem(const std::string& option, const std::filesystem::path& path, bool folder, std::string& error);

// What the classroom window is asked to do (the main job with a display, or offscreen; render's
// comparisons and probes are slides of it).
struct WindowOptions {
    int smokeFrames = 0;
    int frames = 0;
    std::string screenshot;
    std::string compare;
    std::string compareLayout = "side-by-side";
    double wipe = 0.5;
    double uiScale = 1.0;
    bool hideUi = false;
    bool presenter = false;
    std::string exportFile;      // --export: the run's frames as a .gif, .mp4 or .webm
    std::string playPath;        // --play-path: a path played from the start (the panel's "Paths")
    double pathSpeed = 1.0;
    bool measure = false;
    std::string measureReference = "auto";   // the reference of "Measure accuracy": auto (each technique's own) | hard | soft
    int measureSamples = 64;                 // its rays per pixel when soft
    std::string screenshotDir = "screenshots";
    std::string tour;            // a built-in tour's name or a tour file
    int tourStep = 1;            // from 1
    std::string session;         // a session file applied at the start
    std::string sessionDir = "sessions";
    std::string probe;           // X,Y: the kernel view's pixel, in the view's pixels from its top left
};
// "X,Y": two whole numbers, pixels from the top left.
bool parseProbe(const std::string& text, glm::ivec2& pixel);
// Checks the window options against each other and the techniques; fills `out` (0: fine).
int windowOptionsProblem(App& app, const WindowOptions& w, const std::string& technique, InteractiveOptions& out);

// The techniques as their descriptors say, without GL (list, and checking tours and sessions
// before anything is created), the host's built-in reference included.
std::vector<TechniqueInfo> describedTechniques();
// --reference: hard | soft | both | auto (hard for hard techniques, both for filtered and soft).
bool referenceModes(const std::string& text, const TechniqueInfo& info, std::vector<ReferenceOptions::Mode>& modes,
                    std::string& error);
// The report: a sweep measured, charted and written up into `outDir` (the default spec for the
// renderer when `specFile` is empty). Without a display this is the main job.
// `outOption` names the folder's option in messages (the main job's is --out-dir);
// `overlapAccuracy`: BenchSpec::overlapAccuracy for every spec.
int runReport(const CommonOptions& common, const std::string& specFile, const std::string& outDir,
              const std::string& outOption = "--out", bool overlapAccuracy = true);

// One subcommand: declare() adds it and its options to the parser, run() runs it once parsed.
class Command {
public:
    virtual ~Command() = default;
    virtual CLI::App* declare(CLI::App& cli) = 0;
    virtual int run(const CommonOptions& common) = 0;
    // The common options (addCommonOptions) this command has no use for, each with what to use
    // instead: given anyway, they are refused (exit 2) rather than silently ignored.
    struct Unused {
        std::string option, instead;
    };
    virtual std::vector<Unused> unusedCommonOptions() const { return {}; }
};
// Exit 2 naming the first common option given to `command` that it does not use.
int unusedOptionProblem(const CLI::App& parser, const std::string& command, const std::vector<Command::Unused>& unused);
std::unique_ptr<Command> listCommand();
std::unique_ptr<Command> renderCommand();
std::unique_ptr<Command> evalCommand();
std::unique_ptr<Command> benchCommand();
std::unique_ptr<Command> stressCommand();
std::unique_ptr<Command> reportCommand();
std::unique_ptr<Command> tourCommand();
std::unique_ptr<Command> reloadLatencyCommand();

// The main job, when no subcommand is given: its options are the window's (group "Window") and
// the headless report's folder.
class MainJob {
public:
    void declare(CLI::App& cli);
    int run(const CommonOptions& common, const CLI::App& cli);

private:
    WindowOptions window_;
    std::string outDir_ = "out";
};

} // namespace shadowlab::cli
