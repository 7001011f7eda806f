// Plugin loading and hot reload: a good plugin, a wrong ABI version, a missing entry symbol, a
// failing init, a rebuilt library swapped in place (parameter values kept), and GLSL that fails
// to compile on reload (the previous program keeps running).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <algorithm>
#include <fstream>
#include <iterator>
#include <thread>

#include <unistd.h>

#include "plugin/plugin_library.h"
#include "test_support.h"
#include "util/log.h"

using namespace shadowlab;
namespace fs = std::filesystem;

namespace {

const fs::path kTestPlugins = fs::path(SHADOWLAB_BUILD_DIR) / "test_plugins";

bool logContains(const std::string& text) {
    for (const auto& entry : recentLog())
        if (entry.message.find(text) != std::string::npos) return true;
    return false;
}

void writeFile(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
}

// Replaces `target` with `source` and moves its time forward, as a rebuild would.
void replaceLibrary(const fs::path& source, const fs::path& target, int generation) {
    fs::copy_file(source, target, fs::copy_options::overwrite_existing);
    fs::last_write_time(target, fs::file_time_type::clock::now() + std::chrono::seconds(generation));
}

// A private data root (shaders + the test plugin's GLSL) and plugin folder, so tests can edit files.
class PluginSandbox : public ::testing::Test {
protected:
    void SetUp() override {
        root_ = fs::temp_directory_path() / ("shadowlab-test-" + std::to_string(::getpid()) + "-" +
                                             ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(root_);
        fs::create_directories(root_ / "bin");
        fs::copy(fs::path(SHADOWLAB_SOURCE_DIR) / "shaders", root_ / "shaders", fs::copy_options::recursive);
        fs::create_directories(root_ / "app");
        fs::copy(fs::path(SHADOWLAB_SOURCE_DIR) / "app" / "include", root_ / "app" / "include", fs::copy_options::recursive);
        writeFile(shaderFile(), kShader);
        setenv("SHADOWLAB_DATA_DIR", root_.c_str(), 1);
        setenv("SHADOWLAB_PLUGIN_DIR", (root_ / "bin").c_str(), 1);
    }
    void TearDown() override {
        unsetenv("SHADOWLAB_DATA_DIR");
        unsetenv("SHADOWLAB_PLUGIN_DIR");
        fs::remove_all(root_);
    }
    fs::path shaderFile() const { return root_ / "plugins" / "reload_test" / "reload_test.glsl"; }
    fs::path pluginFile() const { return root_ / "bin" / "reload_test.so"; }

    // Renders frames until `done` holds or ~3 s pass (reloads are polled every 100-200 ms).
    template <typename Done>
    bool renderUntil(App& app, Done&& done) {
        for (int i = 0; i < 60; ++i) {
            std::string error;
            EXPECT_TRUE(app.renderFrame("reload_test", error)) << error;
            if (done()) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
        return false;
    }

    static float centreVisibility(App& app) {
        const auto v = test::readTarget(app, MainTarget::Visibility);
        const glm::ivec2 size = app.renderer().size();
        return v[size_t(size.y / 2) * size_t(size.x) + size_t(size.x / 2)].r;
    }

    static constexpr const char* kShader =
        "layout(location = 16) uniform float uLit;\n"
        "vec3 shadowTerm(ShadowInput s) { return vec3(uLit); }\n";
    fs::path root_;
};

} // namespace

TEST(PluginLibrary, LoadsAGoodPluginAndReadsItsDescriptor) {
    std::string error;
    auto library = PluginLibrary::open(kTestPlugins / "reload_v1.so", error);
    ASSERT_TRUE(library) << error;
    EXPECT_EQ(library->info().id, "reload_test");
    EXPECT_EQ(library->info().explanation, "version 1");
    ASSERT_EQ(library->info().params.size(), 2u);
    EXPECT_EQ(library->info().params[0].id, "darkness");
}

TEST(PluginLibrary, RefusesAWrongAbiVersionNamingTheFile) {
    std::string error;
    EXPECT_FALSE(PluginLibrary::open(kTestPlugins / "wrong_abi.so", error));
    EXPECT_NE(error.find("wrong_abi.so"), std::string::npos) << error;
    EXPECT_NE(error.find("ABI version " + std::to_string(SHADOWLAB_ABI_VERSION + 1000) + ".0"), std::string::npos) << error;
    EXPECT_NE(error.find("host expects " + std::to_string(SHADOWLAB_ABI_VERSION) + ".x"), std::string::npos) << error;
}

// The host's built-in techniques own their ids: a library claiming one is refused, named.
TEST(PluginLibrary, ScanRefusesALibraryClaimingAReservedId) {
    const PluginScan scan = scanPlugins(kTestPlugins, {"reload_test"});
    for (const auto& info : scan.techniques) EXPECT_NE(info.id, "reload_test");
    bool named = false;
    for (const auto& error : scan.errors)
        named |= error.find("reload_v1.so: technique id 'reload_test' belongs to the host's built-in technique") != std::string::npos;
    EXPECT_TRUE(named);
}

// CLAP's rule: any minor version of the host's major version loads. A 3.0 entry ends before
// structSize (read nothing past it); a later minor version's longer entry is read as far as known.
TEST(PluginLibrary, LoadsPluginsBuiltForAnyMinorVersionOfAbi3) {
    for (const auto& [file, minor] : {std::pair{"abi3_0.so", 0u}, std::pair{"abi3_9.so", 9u}}) {
        std::string error;
        auto library = PluginLibrary::open(kTestPlugins / file, error);
        ASSERT_TRUE(library) << file << ": " << error;
        EXPECT_EQ(library->abiMinor(), minor) << file;
        EXPECT_EQ(library->info().id, "abi3_test") << file;
        shadowlab::IShadowTechnique* technique = library->entry().create();
        ASSERT_NE(technique, nullptr) << file;
        library->entry().destroy(technique);
    }
    EXPECT_EQ(SHADOWLAB_ABI_ENTRY_VERSION, (2u << 16) | 3u);   // 3.2: kTechniqueNeedsCameraDepth, the adjacency extension
    const shadowlab::PluginEntry current{SHADOWLAB_ABI_ENTRY_VERSION, nullptr, nullptr, nullptr};
    EXPECT_EQ(current.structSize, sizeof(shadowlab::PluginEntry));   // initialised by default
}

TEST(PluginLibrary, RefusesAnAbi2PluginNamingTheFileAndBothVersions) {
    std::string error;
    EXPECT_FALSE(PluginLibrary::open(kTestPlugins / "abi2.so", error));
    EXPECT_NE(error.find("abi2.so"), std::string::npos) << error;
    EXPECT_NE(error.find("plugin ABI version 2.0,"), std::string::npos) << error;
    EXPECT_NE(error.find("host expects 3.x"), std::string::npos) << error;
    EXPECT_EQ(SHADOWLAB_ABI_VERSION, 3u);
}

TEST(PluginLibrary, RefusesALibraryWithoutTheEntrySymbol) {
    std::string error;
    EXPECT_FALSE(PluginLibrary::open(kTestPlugins / "no_entry.so", error));
    EXPECT_NE(error.find("no_entry.so"), std::string::npos) << error;
    EXPECT_NE(error.find("shadowlab_plugin_entry"), std::string::npos) << error;
}

TEST(PluginLibrary, ScanSkipsBadPluginsAndKeepsGoodOnes) {
    const fs::path dir = fs::temp_directory_path() / ("shadowlab-scan-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const char* name : {"reload_v1.so", "wrong_abi.so", "no_entry.so"}) fs::copy_file(kTestPlugins / name, dir / name);
    writeFile(dir / "garbage.so", "not an ELF file");
    const PluginScan scan = scanPlugins(dir);
    ASSERT_EQ(scan.techniques.size(), 1u);
    EXPECT_EQ(scan.techniques[0].id, "reload_test");
    EXPECT_EQ(scan.errors.size(), 3u);
    fs::remove_all(dir);
}

// Scans remember the descriptors of settled libraries (issue 31: a test process scanned the plugin
// folder five times), but never hand back an old descriptor: a rebuilt library is read again, and
// one written within the last two seconds is not remembered at all, since a rewrite within the
// same clock tick could keep its time and size.
TEST(PluginLibrary, ScanReadsALibraryAgainOnceItChanges) {
    const fs::path dir = fs::temp_directory_path() / ("shadowlab-rescan-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path file = dir / "plugin.so";
    auto explanation = [&] {
        const PluginScan scan = scanPlugins(dir);
        return scan.techniques.size() == 1 ? scan.techniques[0].explanation : std::string("(no technique)");
    };
    // Both versions padded to one size (trailing bytes are outside every ELF segment), so that only
    // the time can tell them apart.
    const uintmax_t size = std::max(fs::file_size(kTestPlugins / "reload_v1.so"), fs::file_size(kTestPlugins / "reload_v2.so"));
    auto install = [&](const char* version) {
        fs::copy_file(kTestPlugins / version, file, fs::copy_options::overwrite_existing);
        fs::resize_file(file, size);
    };
    // Settled (an hour old): remembered; replaced by a rebuild (a new time): read again.
    install("reload_v1.so");
    fs::last_write_time(file, fs::file_time_type::clock::now() - std::chrono::hours(1));
    EXPECT_EQ(explanation(), "version 1");
    EXPECT_EQ(explanation(), "version 1");
    install("reload_v2.so");
    EXPECT_EQ(explanation(), "version 2");
    // Fresh: rewritten with the same size and time, as within one clock tick, it is read again.
    install("reload_v1.so");
    const auto fresh = fs::file_time_type::clock::now();
    fs::last_write_time(file, fresh);
    EXPECT_EQ(explanation(), "version 1");
    install("reload_v2.so");
    fs::last_write_time(file, fresh);
    EXPECT_EQ(explanation(), "version 2");
    fs::remove_all(dir);
}

TEST_F(PluginSandbox, InitFailureIsReportedByNameAndTheHostKeepsRunning) {
    fs::copy_file(kTestPlugins / "init_fails.so", root_ / "bin" / "init_fails.so");
    fs::copy_file(kTestPlugins / "reload_v1.so", pluginFile());
    writeFile(root_ / "plugins" / "init_fails" / "none.glsl", "vec3 shadowTerm(ShadowInput s) { return vec3(1.0); }\n");
    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    std::string error;
    EXPECT_FALSE(app->renderFrame("init_fails", error));
    EXPECT_NE(error.find("init_fails.so"), std::string::npos) << error;
    EXPECT_NE(error.find("needs a feature"), std::string::npos) << error;
    EXPECT_TRUE(app->renderFrame("reload_test", error)) << error;
}

// The GL state contract: a technique that leaves every state dirty (in renderShadows and in
// bindMainPass) must not change the host's main pass. Its shadow term is 1, so the frame must be
// exactly `none`'s, pixel for pixel, in the colour and in the G-buffer.
TEST_F(PluginSandbox, DirtyStateLeftByATechniqueDoesNotReachTheMainPass) {
    fs::copy_file(kTestPlugins / "dirty_state.so", root_ / "bin" / "dirty_state.so");
    fs::copy_file(fs::path(SHADOWLAB_BUILD_DIR) / "plugins" / "none.so", root_ / "bin" / "none.so");
    for (const char* id : {"dirty_state", "none"})
        writeFile(root_ / "plugins" / id / "none.glsl", "vec3 shadowTerm(ShadowInput s) { return vec3(1.0); }\n");
    auto app = test::makeHeadlessApp("cube", {96, 64});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("none", error)) << error;
    const auto colour = test::readTarget(*app, MainTarget::Color);
    const auto position = test::readTarget(*app, MainTarget::Position);
    for (int frame = 0; frame < 2; ++frame) {   // a second frame starts from the dirty state too
        ASSERT_TRUE(app->renderFrame("dirty_state", error)) << error;
        EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "the dirty plugin made no GL error";
    }
    const auto dirtyColour = test::readTarget(*app, MainTarget::Color);
    const auto dirtyPosition = test::readTarget(*app, MainTarget::Position);
    ASSERT_EQ(colour.size(), dirtyColour.size());
    size_t differing = 0, drawn = 0;
    for (size_t i = 0; i < colour.size(); ++i) {
        differing += colour[i] != dirtyColour[i] || position[i] != dirtyPosition[i];
        drawn += position[i].w > 0.5f;
    }
    EXPECT_GT(drawn, colour.size() / 4) << "the scene was drawn";
    EXPECT_EQ(differing, 0u) << "pixels changed by state the technique left behind";
}

// docs/plugin-api.md's worked example is a real technique: it loads, shadows the cube where the
// analytic shadow is, and the page shows its files as they are.
TEST_F(PluginSandbox, TheDocumentedExampleTechniqueWorksAndTheDocShowsItVerbatim) {
    const fs::path source = fs::path(SHADOWLAB_SOURCE_DIR) / "tests" / "plugins" / "example";
    fs::copy_file(kTestPlugins / "example.so", root_ / "bin" / "example.so");
    fs::create_directories(root_ / "plugins" / "example");
    for (const char* file : {"example.glsl", "example_shared.h"})
        fs::copy_file(source / file, root_ / "plugins" / "example" / file, fs::copy_options::overwrite_existing);
    auto app = test::makeHeadlessApp("cube", {160, 120});
    ASSERT_TRUE(app);
    const auto visibility = test::renderVisibility(*app, "example");
    const test::GroundClassification ground = test::classifyGround(*app);
    int inside = 0, insideDark = 0, outside = 0, outsideLit = 0;
    for (int y = 0; y < ground.size.y; ++y)
        for (int x = 0; x < ground.size.x; ++x) {
            const size_t i = size_t(y) * size_t(ground.size.x) + size_t(x);
            if (ground.analytic[i] < 0 || ground.nearBoundary(x, y, 2)) continue;
            (ground.analytic[i] == 1 ? inside : outside) += 1;
            (ground.analytic[i] == 1 ? insideDark : outsideLit) += ground.analytic[i] == 1 ? visibility[i].r < 0.1f
                                                                                        : visibility[i].r > 0.9f;
        }
    ASSERT_GT(inside, 100);
    EXPECT_GT(insideDark, inside * 99 / 100);
    EXPECT_GT(outsideLit, outside * 99 / 100);

    std::ifstream docFile(fs::path(SHADOWLAB_SOURCE_DIR) / "docs" / "plugin-api.md");
    const std::string doc((std::istreambuf_iterator<char>(docFile)), std::istreambuf_iterator<char>());
    size_t lines = 0;
    for (const char* file : {"example.cpp", "example_shared.h", "example.glsl"}) {
        std::ifstream in(source / file);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        EXPECT_NE(doc.find(text), std::string::npos) << "docs/plugin-api.md does not show " << file << " as it is";
        lines += size_t(std::count(text.begin(), text.end(), '\n'));
    }
    EXPECT_LT(lines, 60u) << "the worked example stays under 60 lines";
}

TEST_F(PluginSandbox, HotReloadOfARebuiltLibraryKeepsParameterValues) {
    fs::copy_file(kTestPlugins / "reload_v1.so", pluginFile());
    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"darkness=0.2", "samples=9"}, "reload_test", error)) << error;
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
    EXPECT_NEAR(centreVisibility(*app), 0.8f, 0.01f) << "version 1: 1 - darkness";

    replaceLibrary(kTestPlugins / "reload_v2.so", pluginFile(), 2);
    ASSERT_TRUE(renderUntil(*app, [&] { return app->techniques().find("reload_test")->explanation == "version 2"; }))
        << "the rebuilt library was not picked up";
    EXPECT_TRUE(logContains("1 GL object(s) still alive")) << "version 1 leaked a texture; the host must release it";
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
    EXPECT_NEAR(centreVisibility(*app), 0.2f, 0.01f) << "version 2 runs: darkness itself";
    const TechniqueInfo* info = app->techniques().find("reload_test");
    const auto& values = app->params().values(*info);
    ASSERT_EQ(values.size(), 3u);
    EXPECT_DOUBLE_EQ(values[0], 0.2) << "darkness kept";
    EXPECT_DOUBLE_EQ(values[1], 9.0) << "samples kept";
    EXPECT_DOUBLE_EQ(values[2], 1.0) << "new parameter at its default";

    // A broken rebuild (wrong ABI) leaves version 2 running and says why.
    replaceLibrary(kTestPlugins / "wrong_abi.so", pluginFile(), 4);
    ASSERT_TRUE(renderUntil(*app, [&] { return !app->techniques().lastReloadError().empty(); }));
    EXPECT_NE(app->techniques().lastReloadError().find("ABI version"), std::string::npos);
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
    EXPECT_NEAR(centreVisibility(*app), 0.2f, 0.01f);
    EXPECT_EQ(app->techniques().find("reload_test")->explanation, "version 2");
}

TEST_F(PluginSandbox, ShaderThatFailsOnReloadLeavesTheOldProgramRunning) {
    fs::copy_file(kTestPlugins / "reload_v1.so", pluginFile());
    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"darkness=0.3"}, "reload_test", error)) << error;
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
    EXPECT_NEAR(centreVisibility(*app), 0.7f, 0.01f);

    writeFile(shaderFile(), "vec3 shadowTerm(ShadowInput s) { return vec3(uLit) +; }\n");
    fs::last_write_time(shaderFile(), fs::file_time_type::clock::now() + std::chrono::seconds(2));
    ASSERT_TRUE(renderUntil(*app, [&] { return !app->shaders().lastReloadError().empty(); }));
    EXPECT_NE(app->shaders().lastReloadError().find("reload_test.glsl:1"), std::string::npos)
        << "error names the file and line: " << app->shaders().lastReloadError();
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
    EXPECT_NEAR(centreVisibility(*app), 0.7f, 0.01f) << "old program still draws";

    writeFile(shaderFile(), "vec3 shadowTerm(ShadowInput s) { return vec3(0.25); }\n");
    fs::last_write_time(shaderFile(), fs::file_time_type::clock::now() + std::chrono::seconds(4));
    ASSERT_TRUE(renderUntil(*app, [&] { return app->shaders().lastReloadError().empty(); }));
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
    EXPECT_NEAR(centreVisibility(*app), 0.25f, 0.01f) << "fixed shader took over";
}

namespace {

std::string readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeBytes(const fs::path& file, const std::string& bytes, int generation) {
    std::ofstream(file, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
    fs::last_write_time(file, fs::file_time_type::clock::now() + std::chrono::seconds(generation));
}

int countLog(const std::string& text) {
    int n = 0;
    for (const auto& entry : recentLog()) n += entry.message.find(text) != std::string::npos;
    return n;
}

} // namespace

// A rebuild caught mid-write, with the linker pausing longer than two polls: first half the
// library, then all of it with the ELF header still zero (GNU ld writes it last), then the
// finished file. The host waits, reports nothing, and loads the finished file. The old poll
// loaded whatever two polls agreed on and logged "file too short" and "invalid ELF header"
// before every successful rebuild.
TEST_F(PluginSandbox, ALibraryStillBeingWrittenIsWaitedForNotReported) {
    fs::copy_file(kTestPlugins / "reload_v1.so", pluginFile());
    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
    const int failuresBefore = countLog("hot reload failed");
    const std::string v2 = readBytes(kTestPlugins / "reload_v2.so");
    ASSERT_GT(v2.size(), 4096u);
    auto renderFor = [&](std::chrono::milliseconds duration) {
        const auto end = std::chrono::steady_clock::now() + duration;
        while (std::chrono::steady_clock::now() < end) {
            ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
    };
    writeBytes(pluginFile(), v2.substr(0, v2.size() / 2), 2);
    renderFor(std::chrono::milliseconds(500));
    EXPECT_EQ(app->techniques().lastReloadError(), "") << "half a library is a build in progress, not a failure";
    std::string headerless = v2;
    std::fill(headerless.begin(), headerless.begin() + 64, '\0');
    writeBytes(pluginFile(), headerless, 3);
    renderFor(std::chrono::milliseconds(500));
    EXPECT_EQ(app->techniques().lastReloadError(), "") << "no ELF header yet is a build in progress, not a failure";
    EXPECT_EQ(app->techniques().find("reload_test")->explanation, "version 1") << "the running version stays meanwhile";

    writeBytes(pluginFile(), v2, 4);
    ASSERT_TRUE(renderUntil(*app, [&] { return app->techniques().find("reload_test")->explanation == "version 2"; }))
        << "the finished library was not loaded";
    EXPECT_EQ(app->techniques().lastReloadError(), "");
    EXPECT_EQ(countLog("hot reload failed"), failuresBefore) << "no red line before a successful rebuild";
}

// A library that stays incomplete (a build that died while linking) is reported once it has
// stayed unchanged for the settle time, naming what is missing; the running version stays.
TEST_F(PluginSandbox, ALibraryThatStaysIncompleteIsReportedOnceSettled) {
    fs::copy_file(kTestPlugins / "reload_v1.so", pluginFile());
    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
    const std::string v2 = readBytes(kTestPlugins / "reload_v2.so");
    writeBytes(pluginFile(), v2.substr(0, v2.size() / 3), 2);
    const auto start = std::chrono::steady_clock::now();
    ASSERT_TRUE(renderUntil(*app, [&] { return !app->techniques().lastReloadError().empty(); }));
    EXPECT_GE(std::chrono::steady_clock::now() - start, TechniqueManager::kReloadSettle);
    EXPECT_NE(app->techniques().lastReloadError().find("incomplete ELF image"), std::string::npos)
        << app->techniques().lastReloadError();
    EXPECT_NE(app->techniques().lastReloadError().find("reload_test.so"), std::string::npos) << "names the file";
    EXPECT_EQ(app->techniques().find("reload_test")->explanation, "version 1");
}

TEST(PluginLibrary, IncompleteElfImageTellsAFinishedLibraryFromAPartialOne) {
    const fs::path good = kTestPlugins / "reload_v1.so";
    EXPECT_EQ(incompleteElfImage(good), "");
    const fs::path partial = fs::temp_directory_path() / ("shadowlab-partial-" + std::to_string(::getpid()) + ".so");
    const std::string bytes = readBytes(good);
    for (const size_t length : {size_t(10), size_t(64), bytes.size() / 2, bytes.size() - 1}) {
        writeBytes(partial, bytes.substr(0, length), 0);
        EXPECT_NE(incompleteElfImage(partial).find("incomplete ELF image"), std::string::npos) << length << " bytes";
    }
    fs::remove(partial);
}
