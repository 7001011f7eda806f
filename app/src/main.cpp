// shadowlab: the command line. main() declares the options every command shares, lets each
// command (app/src/cli/<command>.cpp) declare its own, parses, and runs the one given, or the main
// job (cli/window.cpp) when none is. Exit codes: 0 success, 1 failure of the machine (no GL, ...),
// 2 bad input (with a message naming the option or file), 130 stopped by Ctrl-C (what was done
// is written; util/progress.h). Every input is checked before the first
// frame; whatever still escapes as an exception is reported by main()'s last-resort handler,
// never by std::terminate.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/cli.h"
#include "scene/scene.h"
#include "util/log.h"
#include "util/progress.h"
#include "util/text_file.h"

using namespace shadowlab;
using namespace shadowlab::cli;

namespace {

int run(int argc, char** argv) {
    CLI::App parser{"shadowlab: real-time shadow techniques as plugins, measured for speed and accuracy"};
    parser.fallthrough();
    parser.require_subcommand(0, 1);
    CommonOptions common;
    addCommonOptions(parser, common);
    MainJob mainJob;
    mainJob.declare(parser);
    std::vector<std::unique_ptr<Command>> commands;
    for (auto make : {listCommand, renderCommand, benchCommand, stressCommand, reportCommand, tourCommand,
                      reloadLatencyCommand, evalCommand})
        commands.push_back(make());
    std::vector<CLI::App*> subcommands;
    for (const auto& command : commands) subcommands.push_back(command->declare(parser));
    requireNonEmptyValues(parser);

    try {
        parser.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = parser.exit(e);
        return code == 0 ? 0 : kExitBadInput;
    }
    if (!common.budget.empty()) {
        SceneBudget budget = sceneBudget();
        std::string error;
        if (!parseSceneBudget(common.budget, budget, error)) return fail(error, kExitBadInput);
        setSceneBudget(budget);
    }
    if (int code = repeatedKeyProblem(common)) return code;
    for (size_t i = 0; i < commands.size(); ++i) {
        if (!*subcommands[i]) continue;
        if (int code = unusedOptionProblem(parser, subcommands[i]->get_name(), commands[i]->unusedCommonOptions())) return code;
        return commands[i]->run(common);
    }
    return mainJob.run(common, parser);
}

} // namespace

int main(int argc, char** argv) {
    // The last resort: every input is checked where it is read, but an exception that still
    // escapes is reported as an error naming what it says, never std::terminate (exit 134).
    catchInterrupts();   // Ctrl-C stops long phases cleanly (util/progress.h)
    int code = 0;
    try {
        code = run(argc, argv);
    } catch (const Interrupted& e) {
        logError(e.what());   // a phase with nothing partial to write (generating a scene)
        code = kExitInterrupted;
    } catch (const SceneError& e) {
        logError(e.what());
        code = kExitBadInput;
    } catch (const std::bad_alloc&) {
        logError("out of memory (lower the scene or output size, or the --budget; docs/scene-format.md, \"Limits\")");
        code = kExitFailure;
    } catch (const std::exception& e) {
        logError(std::string("unexpected error: ") + e.what());
        code = kExitBadInput;
    } catch (...) {
        logError("unexpected error (an exception of unknown type)");
        code = kExitBadInput;
    }
    // A command stopped by Ctrl-C has written what it had (its message says what): the exit code
    // says it was interrupted, whatever failure the stop looked like to the command.
    if (interrupted() && code != 0) code = kExitInterrupted;
    // Output lost to a full disk or /dev/full is a failure, not a success.
    std::string error;
    if (!flushStandardOutput(error)) {
        std::fprintf(stderr, "shadowlab: %s\n", error.c_str());
        if (code == 0) code = kExitFailure;
    }
    return code;
}
