// The fuzzing harness's inputs replayed in the ordinary suite (Release, no sanitizer needed to
// run): every saved regression (tests/fuzz/regressions/<kind>/) and every seed (assets/scenes,
// assets/bench, tests/fuzz/corpus) goes through the same entry points as the libFuzzer targets,
// which abort on a broken promise. Regressions named refused-* must stay refused, accepted-* must
// load; that is what each was saved for (the crashers and hangs, and the fuzzer's).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <sstream>

#include "fuzz/fuzz_inputs.h"
#include "scene/scene.h"

namespace fs = std::filesystem;
using namespace shadowlab;

namespace {

const fs::path kSource = SHADOWLAB_SOURCE_DIR;
const fs::path kFuzz = kSource / "tests" / "fuzz";

std::string readAll(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Replays every file of `dirs` through `fuzz`; returns how many there were.
int replay(const std::vector<fs::path>& dirs, const std::function<bool(const std::string&)>& fuzz) {
    const SceneBudget saved = sceneBudget();
    fuzz::useFuzzBudget();
    int files = 0;
    for (const fs::path& dir : dirs) {
        std::vector<fs::path> inputs;
        for (const auto& item : fs::directory_iterator(dir))
            if (item.is_regular_file()) inputs.push_back(item.path());
        std::sort(inputs.begin(), inputs.end());
        for (const fs::path& input : inputs) {
            SCOPED_TRACE(input.string());
            const bool accepted = fuzz(readAll(input));
            const std::string name = input.filename().string();
            if (name.rfind("refused-", 0) == 0) {
                EXPECT_FALSE(accepted) << name << " must be refused";
            }
            if (name.rfind("accepted-", 0) == 0) {
                EXPECT_TRUE(accepted) << name << " must load";
            }
            ++files;
        }
    }
    setSceneBudget(saved);
    return files;
}

const uint8_t* bytes(const std::string& text) { return reinterpret_cast<const uint8_t*>(text.data()); }

} // namespace

TEST(FuzzRegressions, SceneInputsReplayCleanly) {
    const int regressions = replay({kFuzz / "regressions" / "scene"}, [](const std::string& text) {
        return fuzz::fuzzScene(bytes(text), text.size(), kFuzz / "corpus" / "obj");
    });
    EXPECT_GE(regressions, 10);
    replay({kSource / "assets" / "scenes", kFuzz / "corpus" / "scene"}, [](const std::string& text) {
        EXPECT_TRUE(fuzz::fuzzScene(bytes(text), text.size(), kFuzz / "corpus" / "obj")) << "a seed that does not load";
        return true;
    });
}

TEST(FuzzRegressions, ObjInputsReplayCleanly) {
    EXPECT_GE(replay({kFuzz / "regressions" / "obj"}, [](const std::string& text) { return fuzz::fuzzObj(bytes(text), text.size()); }), 4);
    replay({kFuzz / "corpus" / "obj"}, [](const std::string& text) {
        EXPECT_TRUE(fuzz::fuzzObj(bytes(text), text.size())) << "a seed that does not load";
        return true;
    });
}

TEST(FuzzRegressions, BenchSpecInputsReplayCleanly) {
    EXPECT_GE(replay({kFuzz / "regressions" / "bench"},
                     [](const std::string& text) { return fuzz::fuzzBenchSpec(bytes(text), text.size()); }),
              8);
    replay({kSource / "assets" / "bench"}, [](const std::string& text) {
        return fuzz::fuzzBenchSpec(bytes(text), text.size());   // they name techniques the harness lacks
    });
    replay({kFuzz / "corpus" / "bench"}, [](const std::string& text) {
        // JSON seeds are valid specs; text seeds are command-line values of several kinds at once.
        const bool accepted = fuzz::fuzzBenchSpec(bytes(text), text.size());
        if (!text.empty() && (text[0] == '{' || text[0] == '[')) {
            EXPECT_TRUE(accepted) << "a seed that is refused";
        }
        return true;
    });
}

TEST(FuzzRegressions, TourInputsReplayCleanly) {
    EXPECT_GE(replay({kFuzz / "regressions" / "tour"}, [](const std::string& text) { return fuzz::fuzzTour(bytes(text), text.size()); }),
              8);
    replay({kSource / "assets" / "tours"}, [](const std::string& text) {
        return fuzz::fuzzTour(bytes(text), text.size());   // they name techniques the harness lacks
    });
    replay({kFuzz / "corpus" / "tour"}, [](const std::string& text) {
        EXPECT_TRUE(fuzz::fuzzTour(bytes(text), text.size())) << "a seed that is refused";
        return true;
    });
}

// Texture files (issue 31): the two crashers of stb_image (an IDAT length of 0xffffffff, flipped
// bytes) stay refused with a message; every seed (each colour type and bit depth) decodes.
TEST(FuzzRegressions, TextureInputsReplayCleanly) {
    EXPECT_GE(replay({kFuzz / "regressions" / "texture"}, [](const std::string& text) { return fuzz::fuzzTexture(bytes(text), text.size()); }), 2);
    EXPECT_GE(replay({kFuzz / "corpus" / "texture"}, [](const std::string& text) {
                  EXPECT_TRUE(fuzz::fuzzTexture(bytes(text), text.size())) << "a seed that is refused";
                  return true;
              }),
              17);
}

// Session files (issue 31): the reader --session uses, with its own seeds and regressions.
TEST(FuzzRegressions, SessionInputsReplayCleanly) {
    EXPECT_GE(replay({kFuzz / "regressions" / "session"},
                     [](const std::string& text) { return fuzz::fuzzSession(bytes(text), text.size()); }),
              8);
    EXPECT_GE(replay({kFuzz / "corpus" / "session"}, [](const std::string& text) {
                  EXPECT_TRUE(fuzz::fuzzSession(bytes(text), text.size())) << "a seed that is refused";
                  return true;
              }),
              3);
}

TEST(FuzzRegressions, PathInputsReplayCleanly) {
    EXPECT_GE(replay({kFuzz / "regressions" / "path"}, [](const std::string& text) { return fuzz::fuzzPath(bytes(text), text.size()); }), 7);
    replay({kFuzz / "corpus" / "path", kSource / "assets" / "stress"}, [](const std::string& text) {
        EXPECT_TRUE(fuzz::fuzzPath(bytes(text), text.size())) << "a seed that is refused";
        return true;
    });
}
