// libFuzzer target: scene files (see fuzz_inputs.h). OBJ files named by an input resolve in
// tests/fuzz/corpus/obj, or in $SHADOWLAB_FUZZ_OBJ_DIR (for a copy of the binary run elsewhere).
#include <cstdlib>

#include "fuzz_inputs.h"

namespace {
std::filesystem::path objDir = SHADOWLAB_FUZZ_OBJ_DIR;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    shadowlab::fuzz::useFuzzBudget();
    if (const char* dir = std::getenv("SHADOWLAB_FUZZ_OBJ_DIR"); dir && *dir) objDir = dir;
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    shadowlab::fuzz::fuzzScene(data, size, objDir);
    return 0;
}
