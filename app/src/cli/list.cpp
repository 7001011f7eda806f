// `shadowlab list [--json]`: techniques and their parameters, from their descriptors (no GL).
#include "cli/cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app.h"
#include "bench/bench.h"
#include "bench/path_run.h"
#include "bench/report.h"
#include "bench/stress.h"
#include "groundtruth/reference_technique.h"
#include "render/render_limits.h"
#include "ui/session.h"
#include "ui/tour.h"
#include "bench/tour_pages.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/stats.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab::cli {
namespace {

int commandList(bool json) {
    PluginScan scan = scanPlugins(pluginDir(), {referenceDescriptor().id});
    for (const auto& error : scan.errors) logWarning("skipped plugin: " + error);
    scan.techniques.push_back(copyDescriptor(referenceDescriptor(), {}));   // built into the host
    if (json) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& t : scan.techniques) {
            nlohmann::json params = nlohmann::json::array();
            for (const auto& p : t.params) {
                static const char* types[] = {"float", "int", "bool", "enum"};
                nlohmann::json item = {{"id", p.id}, {"label", p.label}, {"type", types[int(p.type)]},
                                       {"min", p.minValue}, {"max", p.maxValue}, {"default", p.defaultValue},
                                       {"unit", p.unit}, {"help", p.help}};
                if (p.type == ParamType::Enum) item["values"] = p.enumLabels;
                params.push_back(item);
            }
            nlohmann::json item = {{"id", t.id}, {"name", t.displayName}, {"category", t.category},
                                   {"explanation", t.explanation}, {"library", t.library.string()}, {"parameters", params}};
            if (t.debugViewsDeclared) item["debugViews"] = t.debugViews;
            out.push_back(item);
        }
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    for (const auto& t : scan.techniques) {
        std::cout << t.id << "  (" << t.category << ")  " << t.displayName << "\n";
        for (const auto& p : t.params)
            std::cout << "    " << p.id << " = " << formatParamValue(p, p.defaultValue) << "   ["
                      << formatParamValue(p, p.minValue) << " .. " << formatParamValue(p, p.maxValue) << "] "
                      << p.unit << "  " << p.help.substr(0, p.help.find('.') + 1) << "\n";
    }
    std::cout << "scenes: ";
    for (const auto& name : builtinSceneNames()) std::cout << name << " ";
    std::cout << "\n";
    return 0;
}

class ListCommand final : public Command {
public:
    CLI::App* declare(CLI::App& cli) override {
        auto* list = cli.add_subcommand("list", "list techniques and their parameters");
        list->add_flag("--json", json_, "machine-readable output");
        return list;
    }
    int run(const CommonOptions&) override { return commandList(json_); }
    std::vector<Unused> unusedCommonOptions() const override {
        std::vector<Unused> unused;
        for (const char* option : {"--scene", "--scene-param", "--light-dir", "--light-size", "--technique", "--set", "--backend",
                                   "--size", "--msaa", "--depth-prepass", "--translucent-layers", "--reference-device", "--budget"})
            unused.push_back({option, "it lists the techniques' descriptors and the built-in scenes, and draws nothing"});
        return unused;
    }

private:
    bool json_ = false;
};

} // namespace

std::unique_ptr<Command> listCommand() { return std::make_unique<ListCommand>(); }

} // namespace shadowlab::cli
