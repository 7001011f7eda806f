// Test plugin built as an ABI 2 plugin was: its entry reports version 2, which this host
// (ABI 3) must refuse before calling anything else, naming the file and both versions.
#include <shadowlab/technique.h>

extern "C" __attribute__((visibility("default"))) const shadowlab::PluginEntry* shadowlab_plugin_entry() {
    static const shadowlab::PluginEntry entry{2u, nullptr, nullptr, nullptr};
    return &entry;
}
