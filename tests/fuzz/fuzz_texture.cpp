// libFuzzer target: texture files, PNG of every colour type and bit depth (see fuzz_inputs.h).
#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    shadowlab::fuzz::fuzzTexture(data, size);
    return 0;
}
