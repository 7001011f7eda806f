// libFuzzer target: camera paths and stress cases files (see fuzz_inputs.h).
#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    shadowlab::fuzz::useFuzzBudget();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    shadowlab::fuzz::fuzzPath(data, size);
    return 0;
}
