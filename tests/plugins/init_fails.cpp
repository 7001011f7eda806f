// Test plugin whose init() fails with a message.
#include <shadowlab/technique.h>

namespace {

class InitFails final : public shadowlab::IShadowTechnique {
public:
    bool init(shadowlab::IHost&, std::string& error) override {
        error = "needs a feature this test pretends is missing";
        return false;
    }
};

const shadowlab::TechniqueDesc kDescriptor{
    .id = "init_fails", .displayName = "Init fails", .category = "baseline", .explanation = "Test plugin.",
    .shadowGlsl = "none.glsl"};

} // namespace

SHADOWLAB_PLUGIN(InitFails, kDescriptor)
