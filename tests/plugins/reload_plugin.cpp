// Test plugin built twice (TEST_PLUGIN_VERSION 1 and 2) for the hot-reload test. Version 2 adds
// a parameter, changes its explanation and its shadow term, so the test can tell which one runs.
#include <glad/gl.h>
#include <shadowlab/technique.h>

namespace {

using namespace shadowlab;

const ParamDesc kParams[] = {
    {"darkness", "darkness", ParamType::Float, 0, 1, 0.5, "", "Shadow term everywhere is 1 - darkness.", nullptr},
    {"samples", "samples", ParamType::Int, 1, 64, 4, "", "Unused; kept across reloads.", nullptr},
#if TEST_PLUGIN_VERSION == 2
    {"added_in_v2", "added in v2", ParamType::Bool, 0, 1, 1, "", "A parameter only version 2 has.", nullptr},
#endif
};

const TechniqueDesc kDescriptor{
    .id = "reload_test",
    .displayName = "Reload test",
    .category = "baseline",
#if TEST_PLUGIN_VERSION == 2
    .explanation = "version 2",
#else
    .explanation = "version 1",
#endif
    .shadowGlsl = "reload_test.glsl",
    .params = kParams,
    .paramCount = sizeof(kParams) / sizeof(kParams[0]),
};

class ReloadTest final : public IShadowTechnique {
public:
    bool init(IHost& host, std::string& error) override {
        host_ = &host;
        if (!gladLoadGL(host.glLoader())) {
            error = "no GL";
            return false;
        }
        // A tracked allocation that shutdown() deliberately forgets in version 1, so the test can
        // check that the host releases leftovers.
        texture_ = host.createTexture({.internalFormat = GL_R8, .width = 4, .height = 4, .label = "test texture"});
        return true;
    }
    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        // Version 2 inverts the meaning, so a rendered pixel says which version ran.
#if TEST_PLUGIN_VERSION == 2
        glUniform1f(16, params.asFloat(0));
#else
        glUniform1f(16, 1.0f - params.asFloat(0));
#endif
    }
    void shutdown() override {
#if TEST_PLUGIN_VERSION == 2
        host_->destroyTexture(texture_);
#endif
    }

private:
    IHost* host_ = nullptr;
    uint32_t texture_ = 0;
};

} // namespace

SHADOWLAB_PLUGIN(ReloadTest, kDescriptor)
