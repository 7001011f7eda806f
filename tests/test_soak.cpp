// Soak tests: long runs that must leave no trace. 10,000 headless frames at 64x64 cycling through
// every technique (the light moving, so caches are exercised), with no GL error, and GL object
// counts and resident memory flat after the first full cycle; and 100 hot reloads of a plugin
// library with no growth in GL objects, tracked GPU memory or scratch-folder files.
//
// Written against the App / TechniqueManager API only (renderFrame, techniques(), pollForChanges),
// so a change of the plugin ABI changes nothing here. Figures are printed for the record.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "test_support.h"
#include "util/scratch_dir.h"

using namespace shadowlab;
namespace fs = std::filesystem;

namespace {

// Live GL objects of every kind the host and plugins create, counted by asking glIs* for every
// name below a freshly generated one (Mesa hands out names in increasing order).
struct GlCensus {
    int textures = 0, buffers = 0, framebuffers = 0, vertexArrays = 0, programs = 0, shaders = 0, samplers = 0,
        queries = 0, renderbuffers = 0;
    bool operator==(const GlCensus&) const = default;
    int total() const {
        return textures + buffers + framebuffers + vertexArrays + programs + shaders + samplers + queries + renderbuffers;
    }
};

std::ostream& operator<<(std::ostream& out, const GlCensus& c) {
    return out << "textures " << c.textures << ", buffers " << c.buffers << ", framebuffers " << c.framebuffers
               << ", vertex arrays " << c.vertexArrays << ", programs " << c.programs << ", shaders " << c.shaders
               << ", samplers " << c.samplers << ", queries " << c.queries << ", renderbuffers " << c.renderbuffers;
}

template <typename Create, typename Delete, typename Is>
int countLive(Create create, Delete destroy, Is is) {
    GLuint probe = 0;
    create(&probe);
    int live = 0;
    for (GLuint name = 1; name < probe; ++name) live += is(name) ? 1 : 0;
    destroy(&probe);
    return live;
}

GlCensus census() {
    GlCensus c;
    c.textures = countLive([](GLuint* n) { glCreateTextures(GL_TEXTURE_2D, 1, n); },
                           [](GLuint* n) { glDeleteTextures(1, n); }, [](GLuint n) { return glIsTexture(n); });
    c.buffers = countLive([](GLuint* n) { glCreateBuffers(1, n); }, [](GLuint* n) { glDeleteBuffers(1, n); },
                          [](GLuint n) { return glIsBuffer(n); });
    c.framebuffers = countLive([](GLuint* n) { glCreateFramebuffers(1, n); },
                               [](GLuint* n) { glDeleteFramebuffers(1, n); }, [](GLuint n) { return glIsFramebuffer(n); });
    c.vertexArrays = countLive([](GLuint* n) { glCreateVertexArrays(1, n); },
                               [](GLuint* n) { glDeleteVertexArrays(1, n); }, [](GLuint n) { return glIsVertexArray(n); });
    c.samplers = countLive([](GLuint* n) { glCreateSamplers(1, n); }, [](GLuint* n) { glDeleteSamplers(1, n); },
                           [](GLuint n) { return glIsSampler(n); });
    c.queries = countLive([](GLuint* n) { glCreateQueries(GL_TIMESTAMP, 1, n); }, [](GLuint* n) { glDeleteQueries(1, n); },
                          [](GLuint n) { return glIsQuery(n); });
    c.renderbuffers = countLive([](GLuint* n) { glCreateRenderbuffers(1, n); },
                                [](GLuint* n) { glDeleteRenderbuffers(1, n); }, [](GLuint n) { return glIsRenderbuffer(n); });
    // Programs and shaders share one name space.
    const GLuint probe = glCreateProgram();
    for (GLuint name = 1; name < probe; ++name) {
        c.programs += glIsProgram(name) ? 1 : 0;
        c.shaders += glIsShader(name) ? 1 : 0;
    }
    glDeleteProgram(probe);
    return c;
}

double residentMiB() {
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    statm >> pages >> resident;
    return double(resident) * double(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

size_t trackedBytes(App& app) {
    size_t bytes = 0;
    for (LoadedTechnique* loaded : app.techniques().loadedTechniques()) bytes += loaded->host().gpuBytes();
    return bytes;
}

const char* glErrorName(GLenum error) {
    switch (error) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "a GL error";
    }
}

// Integer parameters (resolutions, kernels, sample counts) at the bottom of their declared range,
// or one step up (doubled) on odd cycles, so every cycle reallocates: llvmpipe draws 64x64 frames
// in a few milliseconds that way instead of ~60 (2048^2 maps). Other parameters keep their defaults.
void setCheapParameters(App& app, const std::string& technique, bool stepUp) {
    const TechniqueInfo* info = app.techniques().find(technique);
    ASSERT_TRUE(info);
    app.params().resetToDefaults(*info);
    std::vector<std::string> sets;
    for (const ParamSpec& p : info->params) {
        if (p.type != ParamType::Int) continue;
        const double value = stepUp ? std::min(p.maxValue, std::max(p.minValue * 2, p.minValue + 1)) : p.minValue;
        sets.push_back(p.id + "=" + formatParamValue(p, value));
    }
    std::string error;
    ASSERT_TRUE(app.applyAssignments(sets, technique, error)) << error;
}

} // namespace

TEST(Soak, TenThousandFramesCyclingEveryTechniqueLeaveNothingBehind) {
    constexpr int kFramesPerTechnique = 25;
    auto app = test::makeHeadlessApp("cube", {64, 64});
    ASSERT_TRUE(app);
    std::vector<std::string> ids;
    for (const auto& t : app->techniques().techniques()) ids.push_back(t.id);
    ASSERT_GE(ids.size(), 10u) << "every plugin and the reference";
    const int cycle = kFramesPerTechnique * int(ids.size());
#if defined(__SANITIZE_ADDRESS__)
    // Resident memory is not checked under AddressSanitizer (below): three snapshots, six cycles
    // (every technique at both settings three times), check the GL objects and tracked memory and
    // give the sanitizers every code path, in 40% of the ten thousand frames (issue 31).
    const int frames = 6 * cycle;
#else
    const int frames = 10000;
#endif
    const glm::vec3 sceneLight = app->light().direction;
    while (glGetError() != GL_NO_ERROR) {
    }

    // Snapshots at the same point of every other cycle (the parameters alternate with the cycle):
    // the first after two cycles, when every technique has run at both settings.
    struct Snapshot {
        int frame;
        GlCensus gl;
        double rssMiB;
        size_t tracked;
    };
    std::vector<Snapshot> snapshots;
    const auto start = std::chrono::steady_clock::now();
    for (int frame = 0; frame < frames; ++frame) {
        const std::string& technique = ids[size_t(frame / kFramesPerTechnique) % ids.size()];
        if (frame % kFramesPerTechnique == 0) setCheapParameters(*app, technique, (frame / cycle) % 2 == 1);
        // The light circles slowly, so techniques refit and the reference retraces.
        const float angle = 0.002f * float(frame);
        app->light().direction = glm::normalize(sceneLight + 0.3f * glm::vec3(std::cos(angle), 0.0f, std::sin(angle)));
        std::string error;
        ASSERT_TRUE(app->renderFrame(technique, error)) << "frame " << frame << ", " << technique << ": " << error;
        const GLenum glError = glGetError();
        ASSERT_EQ(glError, GLenum(GL_NO_ERROR)) << "frame " << frame << ", " << technique << ": " << glErrorName(glError);
        if ((frame + 1) % (2 * cycle) == 0) {
            glFinish();
            snapshots.push_back({frame + 1, census(), residentMiB(), trackedBytes(*app)});
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ASSERT_GE(snapshots.size(), 3u);
    const Snapshot& warm = snapshots.front();
    std::printf("soak: %d frames of %zu techniques at 64x64 in %.1f s (%.2f ms/frame)\n", frames, ids.size(), seconds,
                1000.0 * seconds / frames);
    double peakGrowth = 0.0;
    for (const Snapshot& s : snapshots) {
        std::printf("soak: frame %5d: %d GL objects, RSS %.1f MiB, tracked GPU memory %zu bytes\n", s.frame, s.gl.total(),
                    s.rssMiB, s.tracked);
        EXPECT_EQ(s.gl, warm.gl) << "frame " << s.frame << ": " << s.gl << "; after warm-up: " << warm.gl;
        EXPECT_EQ(s.tracked, warm.tracked) << "frame " << s.frame;
        peakGrowth = std::max(peakGrowth, s.rssMiB - warm.rssMiB);
    }
    std::printf("soak: GL objects after warm-up: %s\n", ::testing::PrintToString(warm.gl).c_str());
    // Resident memory: llvmpipe's and malloc's own churn moves it within a band of about 8 MiB
    // (measured over 40,000 frames: 120-128 MiB, no trend), so the test compares the mean of the
    // first and second halves of the snapshots after warm-up: a leak of 1.5 KiB a frame moves it
    // by 6 MiB. A gross leak fails the peak check (one 64x64 RGBA16F texture a frame is 300 MiB),
    // whose bound leaves room for that churn on top of a large atlas (virtual-sm's 58 MiB grown
    // once and kept): with the suite running beside it the peak reached 18.8 MiB above warm-up
    // with no trend between the halves (issue 30's helper run; 12-13 MiB alone).
    const size_t half = (snapshots.size() - 1) / 2;
    double first = 0.0, second = 0.0;
    for (size_t i = 1; i <= half; ++i) first += snapshots[i].rssMiB / double(half);
    for (size_t i = half + 1; i < snapshots.size(); ++i) second += snapshots[i].rssMiB / double(snapshots.size() - 1 - half);
    std::printf("soak: RSS mean %.1f MiB over the first half, %.1f MiB over the second, peak %.1f MiB above warm-up\n", first,
                second, peakGrowth);
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer keeps freed memory in quarantine (256 MiB) and so grows RSS by design:
    // GL objects and tracked memory are checked above; LeakSanitizer and the Release run see the rest.
    std::printf("soak: RSS not checked under AddressSanitizer\n");
#else
    EXPECT_LT(second - first, 6.0) << "RSS grows: " << first << " MiB, then " << second << " MiB";
    EXPECT_LT(peakGrowth, 32.0) << "RSS grew from " << warm.rssMiB << " MiB";
#endif
}

TEST(Soak, HundredHotReloadsGrowNoGlObjectsNorTrackedMemory) {
    // The reload test plugin in a private plugin folder and data root (as test_plugins.cpp does).
    const fs::path root = fs::temp_directory_path() / ("shadowlab-soak-" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "bin");
    fs::create_directories(root / "plugins" / "reload_test");
    fs::copy(fs::path(SHADOWLAB_SOURCE_DIR) / "shaders", root / "shaders", fs::copy_options::recursive);
    fs::create_directories(root / "app");
    fs::copy(fs::path(SHADOWLAB_SOURCE_DIR) / "app" / "include", root / "app" / "include", fs::copy_options::recursive);
    std::ofstream(root / "plugins" / "reload_test" / "reload_test.glsl")
        << "layout(location = 16) uniform float uLit;\nvec3 shadowTerm(ShadowInput s) { return vec3(uLit); }\n";
    const fs::path testPlugins = fs::path(SHADOWLAB_BUILD_DIR) / "test_plugins";
    const fs::path library = root / "bin" / "reload_test.so";
    fs::copy_file(testPlugins / "reload_v1.so", library);
    setenv("SHADOWLAB_DATA_DIR", root.c_str(), 1);
    setenv("SHADOWLAB_PLUGIN_DIR", (root / "bin").c_str(), 1);
    auto app = test::makeHeadlessApp("cube", {64, 64});
    ASSERT_TRUE(app);

    auto reload = [&](int generation) {
        // As a rebuild: new bytes (v1 and v2 alternate), a newer time; two polls that agree.
        fs::copy_file(testPlugins / (generation % 2 ? "reload_v2.so" : "reload_v1.so"), library,
                      fs::copy_options::overwrite_existing);
        fs::last_write_time(library, fs::file_time_type::clock::now() + std::chrono::seconds(generation));
        std::vector<std::string> reloaded;
        for (int poll = 0; poll < 3 && reloaded.empty(); ++poll)
            reloaded = app->techniques().pollForChanges(app->params(), std::chrono::milliseconds(0));
        return reloaded.size() == 1;
    };
    auto scratchFiles = [] {
        std::string error;
        const fs::path dir = scratchDir(error);
        size_t files = 0;
        for (const auto& item : fs::directory_iterator(dir)) files += item.path().extension() == ".so" ? 1 : 0;
        return files;
    };
    std::string error;
    ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;   // loaded: now it can be reloaded
    const auto start = std::chrono::steady_clock::now();
    GlCensus before;
    size_t trackedBefore = 0, filesBefore = 0;
    double rssBefore = 0.0;
    for (int generation = 1; generation <= 102; ++generation) {
        ASSERT_TRUE(reload(generation)) << "reload " << generation << ": " << app->techniques().lastReloadError();
        for (int frame = 0; frame < 2; ++frame) ASSERT_TRUE(app->renderFrame("reload_test", error)) << error;
        ASSERT_EQ(glGetError(), GLenum(GL_NO_ERROR)) << "reload " << generation;
        if (generation == 2) {   // both versions have run once
            glFinish();
            before = census();
            trackedBefore = trackedBytes(*app);
            filesBefore = scratchFiles();
            rssBefore = residentMiB();
        }
    }
    glFinish();
    const GlCensus after = census();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("reload soak: 100 reloads in %.1f s; GL objects %d -> %d, tracked bytes %zu -> %zu, plugin copies %zu -> %zu, "
                "RSS %.1f -> %.1f MiB\n",
                seconds, before.total(), after.total(), trackedBefore, trackedBytes(*app), filesBefore, scratchFiles(),
                rssBefore, residentMiB());
    EXPECT_EQ(after, before) << before << " before, " << after << " after";
    EXPECT_EQ(trackedBytes(*app), trackedBefore);
    EXPECT_EQ(scratchFiles(), filesBefore) << "each replaced library's copy is removed";
    app.reset();
    unsetenv("SHADOWLAB_DATA_DIR");
    unsetenv("SHADOWLAB_PLUGIN_DIR");
    fs::remove_all(root);
}
