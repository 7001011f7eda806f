// Test plugin: a shared library without the shadowlab entry symbol.
extern "C" __attribute__((visibility("default"))) int not_a_shadowlab_plugin() { return 42; }
