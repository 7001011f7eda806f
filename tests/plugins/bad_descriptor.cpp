// Test plugins with broken descriptors, one per BAD_CASE_* definition (tests/plugins/CMakeLists.txt
// builds each as bad_<case>.so). The host must refuse each with a message naming the file and the
// problem, and never read past what the descriptor declares (`list` must not crash).
#include <shadowlab/technique.h>

#include <limits>

namespace {

using namespace shadowlab;

class Nothing final : public IShadowTechnique {
public:
};

#if defined(BAD_CASE_null_param_id)
const ParamDesc kParams[] = {{nullptr, "x", ParamType::Float, 0, 1, 0.5, "", "", nullptr}};
#elif defined(BAD_CASE_nan_default)
const ParamDesc kParams[] = {{"x", "x", ParamType::Float, 0, 1, std::numeric_limits<double>::quiet_NaN(), "", "", nullptr}};
#elif defined(BAD_CASE_enum_mismatch)
const ParamDesc kParams[] = {{"mode", "mode", ParamType::Enum, 0, 3, 0, "", "", "a|b"}};
#elif defined(BAD_CASE_unknown_type)
const ParamDesc kParams[] = {{"x", "x", static_cast<ParamType>(7), 0, 1, 0, "", "", nullptr}};
#elif defined(BAD_CASE_duplicate_param)
const ParamDesc kParams[] = {{"x", "x", ParamType::Float, 0, 1, 0, "", "", nullptr},
                             {"x", "x again", ParamType::Float, 0, 1, 0, "", "", nullptr}};
#else
const ParamDesc kParams[] = {{"x", "x", ParamType::Float, 0, 1, 0.5, "", "", nullptr}};
#endif

#if defined(BAD_CASE_huge_param_count)
constexpr uint32_t kParamCount = 100000000;   // one parameter declared, 1e8 claimed
#else
constexpr uint32_t kParamCount = sizeof(kParams) / sizeof(kParams[0]);
#endif

#if defined(BAD_CASE_dotted_id)
constexpr const char* kId = "bad.dotted";
#elif defined(BAD_CASE_duplicate_a) || defined(BAD_CASE_duplicate_b)
constexpr const char* kId = "duplicate_test";
#elif defined(BAD_CASE_create_null)
constexpr const char* kId = "create_null";
#else
constexpr const char* kId = "bad_descriptor";
#endif

const TechniqueDesc kDescriptor{.structSize = sizeof(TechniqueDesc),
                                .id = kId,
                                .displayName = "Broken",
                                .category = "baseline",
                                .explanation = "Test plugin.",
                                .shadowGlsl = "none.glsl",
                                .params = kParams,
                                .paramCount = kParamCount};

} // namespace

#if defined(BAD_CASE_create_null)
extern "C" __attribute__((visibility("default"))) const shadowlab::PluginEntry* shadowlab_plugin_entry() {
    static const shadowlab::PluginEntry entry{
        SHADOWLAB_ABI_VERSION, []() -> const shadowlab::TechniqueDesc* { return &kDescriptor; },
        []() -> shadowlab::IShadowTechnique* { return nullptr; },
        [](shadowlab::IShadowTechnique* technique) { delete technique; }};
    return &entry;
}
#else
SHADOWLAB_PLUGIN(Nothing, kDescriptor)
#endif
