// libFuzzer target: session files, `--session` and "Load session" (see fuzz_inputs.h).
#include "fuzz_inputs.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    shadowlab::fuzz::useFuzzBudget();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    shadowlab::fuzz::fuzzSession(data, size);
    return 0;
}
