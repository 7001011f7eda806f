// Test plugin built as an ABI 3.0 plugin was: its entry is the 3.0 layout (no structSize after
// destroy) and reports a bare 3. A 3.1 host must load it, reading nothing past destroy.
// With ABI3_FUTURE_MINOR it instead reports 3.9 with a longer entry, which the host must also load.
#include <shadowlab/technique.h>

namespace {

class Abi30Technique final : public shadowlab::IShadowTechnique {};

const shadowlab::TechniqueDesc kDescriptor{
    .structSize = offsetof(shadowlab::TechniqueDesc, translucencyModel),   // a 3.0-era descriptor too
    .id = "abi3_test", .displayName = "ABI 3.0 test", .category = "baseline",
    .explanation = "Test plugin with a 3.0 entry.", .shadowGlsl = "none.glsl"};

const shadowlab::TechniqueDesc* describe() { return &kDescriptor; }
shadowlab::IShadowTechnique* create() { return new Abi30Technique(); }
void destroy(shadowlab::IShadowTechnique* technique) { delete technique; }

#ifdef ABI3_FUTURE_MINOR
// A later minor version appends fields after structSize.
struct FutureEntry {
    shadowlab::PluginEntry base;
    uint64_t laterField;
};
const FutureEntry kEntry{{(9u << 16) | 3u, describe, create, destroy, sizeof(FutureEntry)}, 42};
#else
// The entry exactly as ABI 3.0 declared it.
struct EntryV30 {
    uint32_t abiVersion;
    const shadowlab::TechniqueDesc* (*describe)();
    shadowlab::IShadowTechnique* (*create)();
    void (*destroy)(shadowlab::IShadowTechnique*);
};
const EntryV30 kEntry{3u, describe, create, destroy};
#endif

} // namespace

extern "C" __attribute__((visibility("default"))) const void* shadowlab_plugin_entry() { return &kEntry; }
