// Test plugin whose init() fails with a message.
#include <shadowlab/technique.h>

namespace {

class InitFails final : public shadowlab::IShadowTechnique {
public:
    bool init(shadowlab::IHost&, std::string& error) override {
        error = "needs a feature this test pretends is missing";
        return false;
    }
    void renderShadows(const shadowlab::ParamValues&) override {}
    void bindMainPass(uint32_t, const shadowlab::ParamValues&) override {}
    void shutdown() override {}
};

const shadowlab::TechniqueDesc kDescriptor{"init_fails", "Init fails", "baseline", "Test plugin.", "none.glsl", nullptr, 0};

} // namespace

SHADOWLAB_PLUGIN(InitFails, kDescriptor)
