// GL context backends: names and the default choice, and for each headless backend (OSMesa, EGL) a
// real 4.5 core context that clears an FBO and reads the colour back, created repeatedly in one
// process. GLFW runs only where a display is present (xvfb-run -a works).
#include <glad/gl.h>

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <vector>

#include "backend/backend.h"

namespace shadowlab {
namespace {

// Sets (or unsets, with nullptr) an environment variable for one scope.
class ScopedEnv {
public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old, hadOld_ = true;
        if (value != nullptr) {
            setenv(name, value, 1);
        } else {
            unsetenv(name);
        }
    }
    ~ScopedEnv() {
        if (hadOld_) {
            setenv(name_.c_str(), old_.c_str(), 1);
        } else {
            unsetenv(name_.c_str());
        }
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    std::string name_;
    std::string old_;
    bool hadOld_ = false;
};

bool hasDisplay() {
    const char* display = std::getenv("DISPLAY");
    return display != nullptr && display[0] != '\0';
}

// Loads glad from the backend and checks what every backend promises: GL 4.5, core profile.
void expectCore45(const GlBackend& backend) {
    const int version = gladLoadGL(backend.loader());
    ASSERT_NE(version, 0) << "gladLoadGL failed with " << backend.description();
    EXPECT_GE(GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version), 45);
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_NE(profile & GL_CONTEXT_CORE_PROFILE_BIT, 0);
    std::printf("[   info   ] %s: GL_VERSION %s, GL_RENDERER %s\n", backendName(backend.kind()),
                reinterpret_cast<const char*>(glGetString(GL_VERSION)),
                reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    std::printf("[   info   ] description: %s\n", backend.description().c_str());
}

// Clears an RGBA8 FBO (the host never relies on a default framebuffer) and reads it back.
void expectClearReadsBack(glm::ivec2 size) {
    GLuint texture = 0, framebuffer = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA8, size.x, size.y);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
    ASSERT_EQ(glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER),
              static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));

    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, size.x, size.y);
    glClearColor(0.25f, 0.5f, 0.75f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    std::vector<unsigned char> pixels(static_cast<size_t>(size.x * size.y) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

    const int expected[4] = {64, 128, 191, 255}; // 0.25, 0.5, 0.75, 1.0 in unorm8 (+-1 for rounding)
    int wrong = 0;
    for (size_t i = 0; i < pixels.size(); ++i)
        wrong += std::abs(pixels[i] - expected[i % 4]) > 1;
    EXPECT_EQ(wrong, 0) << "first pixel " << int(pixels[0]) << "," << int(pixels[1]) << "," << int(pixels[2])
                        << "," << int(pixels[3]);

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &texture);
}

// A headless backend whose library is not installed is skipped (a GPU box without OSMesa, a CI
// image without libEGL); any other failure is a failure.
bool libraryMissing(const std::string& error) { return error.find("not found") != std::string::npos; }

TEST(BackendNames, RoundTrip) {
    for (BackendKind kind : {BackendKind::Glfw, BackendKind::Egl, BackendKind::OSMesa}) {
        EXPECT_EQ(parseBackend(backendName(kind)), kind);
    }
    EXPECT_EQ(parseBackend("glfw"), BackendKind::Glfw);
    EXPECT_EQ(parseBackend("egl"), BackendKind::Egl);
    EXPECT_EQ(parseBackend("osmesa"), BackendKind::OSMesa);
    EXPECT_FALSE(parseBackend("vulkan").has_value());
    EXPECT_FALSE(parseBackend("").has_value());
}

TEST(BackendNames, DefaultFollowsDisplay) {
    {
        ScopedEnv display("DISPLAY", nullptr), wayland("WAYLAND_DISPLAY", nullptr);
        EXPECT_EQ(defaultBackend(), BackendKind::Egl);
    }
    {
        ScopedEnv display("DISPLAY", ""), wayland("WAYLAND_DISPLAY", "");
        EXPECT_EQ(defaultBackend(), BackendKind::Egl);
    }
    {
        ScopedEnv display("DISPLAY", ":0"), wayland("WAYLAND_DISPLAY", nullptr);
        EXPECT_EQ(defaultBackend(), BackendKind::Glfw);
    }
    {
        ScopedEnv display("DISPLAY", nullptr), wayland("WAYLAND_DISPLAY", "wayland-0");
        EXPECT_EQ(defaultBackend(), BackendKind::Glfw);
    }
}

TEST(Backend, RejectsEmptySize) {
    std::string error;
    EXPECT_EQ(createBackend(BackendKind::OSMesa, {0, 48}, "x", false, error), nullptr);
    EXPECT_NE(error.find("size"), std::string::npos) << error;
}

class HeadlessBackend : public ::testing::TestWithParam<BackendKind> {};

TEST_P(HeadlessBackend, Core45ContextClearsFramebuffer) {
    const glm::ivec2 size{64, 48};
    std::string error;
    auto backend = createBackend(GetParam(), size, "shadowlab test", false, error);
    if (!backend && libraryMissing(error)) GTEST_SKIP() << error;
    ASSERT_NE(backend, nullptr) << error;
    EXPECT_EQ(backend->kind(), GetParam());
    EXPECT_EQ(backend->framebufferSize(), size);
    EXPECT_EQ(backend->window(), nullptr);
    EXPECT_FALSE(backend->shouldClose());
    EXPECT_FALSE(backend->description().empty());
    expectCore45(*backend);
    expectClearReadsBack(size);
}

TEST_P(HeadlessBackend, CreatesTwiceInOneProcess) {
    for (int round = 0; round < 2; ++round) {
        std::string error;
        auto backend = createBackend(GetParam(), {32, 16}, "shadowlab test", false, error);
        if (!backend && libraryMissing(error)) GTEST_SKIP() << error;
        ASSERT_NE(backend, nullptr) << "round " << round << ": " << error;
        ASSERT_NE(gladLoadGL(backend->loader()), 0);
        expectClearReadsBack({32, 16});
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, HeadlessBackend, ::testing::Values(BackendKind::OSMesa, BackendKind::Egl),
                         [](const ::testing::TestParamInfo<BackendKind>& info) {
                             return std::string(backendName(info.param));
                         });

// Both headless backends, one after the other, in one process (the host may fall back from EGL
// to OSMesa; tests create all kinds).
TEST(Backend, SwitchesBetweenHeadlessBackends) {
    for (BackendKind kind : {BackendKind::Egl, BackendKind::OSMesa, BackendKind::Egl}) {
        std::string error;
        auto backend = createBackend(kind, {16, 16}, "shadowlab test", false, error);
        if (!backend && libraryMissing(error)) GTEST_SKIP() << error;
        ASSERT_NE(backend, nullptr) << error;
        ASSERT_NE(gladLoadGL(backend->loader()), 0);
        expectClearReadsBack({16, 16});
    }
}

TEST(GlfwBackend, HiddenWindow) {
    if (!hasDisplay()) GTEST_SKIP() << "no DISPLAY (run under xvfb-run -a)";
    std::string error;
    auto backend = createBackend(BackendKind::Glfw, {64, 48}, "shadowlab test", false, error);
    ASSERT_NE(backend, nullptr) << error;
    EXPECT_EQ(backend->kind(), BackendKind::Glfw);
    EXPECT_NE(backend->window(), nullptr);
    const glm::ivec2 size = backend->framebufferSize();
    EXPECT_GT(size.x, 0);
    EXPECT_GT(size.y, 0);
    expectCore45(*backend);
    expectClearReadsBack({64, 48});
    backend->pollEvents();
    backend->swapBuffers();
    EXPECT_FALSE(backend->shouldClose());
}

TEST(GlfwBackend, NoDisplayIsAnErrorNotACrash) {
    ScopedEnv display("DISPLAY", nullptr), wayland("WAYLAND_DISPLAY", nullptr);
    std::string error;
    auto backend = createBackend(BackendKind::Glfw, {64, 48}, "shadowlab test", false, error);
    EXPECT_EQ(backend, nullptr);
    EXPECT_EQ(error.rfind("GLFW backend: ", 0), 0u) << error;
    EXPECT_GT(error.size(), std::string("GLFW backend: glfwInit failed: ").size())
            << "GLFW's own text is missing: " << error;
}

} // namespace
} // namespace shadowlab
