// Test plugin whose entry reports an ABI version the host does not speak.
#include <shadowlab/technique.h>

extern "C" __attribute__((visibility("default"))) const shadowlab::PluginEntry* shadowlab_plugin_entry() {
    static const shadowlab::PluginEntry entry{SHADOWLAB_ABI_VERSION + 1000, nullptr, nullptr, nullptr};
    return &entry;
}
