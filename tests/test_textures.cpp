// PNG textures through libpng (issue 31): every colour type and bit depth read as stb_image read
// them (values as stored, 16-bit reduced to the high byte, black of an image without alpha opaque),
// corrupt files refused with a message naming the file instead of a crash, and the decoded size
// checked against the scene budget before the pixels are allocated.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene/scene.h"

namespace fs = std::filesystem;
using namespace shadowlab;

namespace {

const fs::path kSeeds = fs::path(SHADOWLAB_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "texture";
const fs::path kCrashers = fs::path(SHADOWLAB_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / "texture";

// Texel (x, row) of the PNG as written by tools/make_png_seeds.py (rows top-down), as RGBA.
glm::ivec4 texel(const Texture& texture, int x, int pngRow) {
    const int y = texture.height - 1 - pngRow;   // stored bottom-up
    const uint8_t* t = &texture.rgba[(size_t(y) * size_t(texture.width) + size_t(x)) * 4];
    return {t[0], t[1], t[2], t[3]};
}

} // namespace

TEST(Textures, EveryColourTypeAndBitDepthReadsAsStored) {
    const float plainAlpha = 0.5f;   // glass alpha of images without alpha: 128
    auto load = [&](const char* name) { return loadPngTexture(kSeeds / name, plainAlpha, 1 << 20); };
    for (const char* name : {"grey1.png", "grey2.png", "grey4.png", "grey8.png", "grey16.png"}) {
        const Texture t = load(name);
        ASSERT_EQ(t.width, 3) << name;
        ASSERT_EQ(t.height, 2) << name;
        EXPECT_EQ(texel(t, 0, 0), glm::ivec4(0, 0, 0, 255)) << name;        // black: opaque
        EXPECT_EQ(texel(t, 1, 0), glm::ivec4(255, 255, 255, 128)) << name;  // white: glass
    }
    EXPECT_EQ(texel(load("grey4.png"), 2, 0), glm::ivec4(119, 119, 119, 128));   // 7 of 15, scaled as stb does
    EXPECT_EQ(texel(load("grey16.png"), 2, 0), glm::ivec4(127, 127, 127, 128));  // 32767: the high byte
    EXPECT_EQ(texel(load("rgb8.png"), 2, 1), glm::ivec4(127, 63, 31, 128));
    EXPECT_EQ(texel(load("rgb16.png"), 2, 1), glm::ivec4(127, 63, 31, 128));
    EXPECT_EQ(texel(load("rgb8.png"), 0, 1), glm::ivec4(0, 0, 0, 255));
    EXPECT_EQ(texel(load("rgba8.png"), 1, 0), glm::ivec4(0, 255, 0, 127));       // its own alpha, black or not
    EXPECT_EQ(texel(load("rgba16.png"), 0, 1), glm::ivec4(0, 0, 0, 255));
    EXPECT_EQ(texel(load("rgba16.png"), 2, 1), glm::ivec4(127, 63, 31, 85));
    EXPECT_EQ(texel(load("greyalpha8.png"), 2, 0), glm::ivec4(85, 85, 85, 0));
    EXPECT_EQ(texel(load("greyalpha16.png"), 1, 0), glm::ivec4(255, 255, 255, 127));
    EXPECT_EQ(texel(load("palette8.png"), 1, 0), glm::ivec4(0, 255, 0, 128));
    EXPECT_EQ(texel(load("palette1.png"), 0, 1), glm::ivec4(0, 255, 0, 128));
    EXPECT_EQ(texel(load("palette8-trns.png"), 1, 0), glm::ivec4(0, 255, 0, 128));   // tRNS: alpha 128
    EXPECT_EQ(texel(load("palette8-trns.png"), 2, 1), glm::ivec4(0, 0, 0, 255));     // index 3, no tRNS entry
    EXPECT_EQ(texel(load("rgb8-interlaced.png"), 2, 1), glm::ivec4(9, 8, 7, 128));
}

TEST(Textures, CorruptFilesAreRefusedNamingTheFile) {
    int files = 0;
    for (const auto& entry : fs::directory_iterator(kCrashers)) {
        ++files;
        try {
            loadPngTexture(entry.path(), 0.5f, 1 << 20);
            ADD_FAILURE() << entry.path() << " was accepted";
        } catch (const SceneError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(entry.path().string() + ": not a readable PNG image (", 0), 0u) << e.what();
        }
    }
    EXPECT_GE(files, 2);
    EXPECT_THROW(decodePngTexture("not a png at all", "x.png", 0.5f), SceneError);
    EXPECT_THROW(decodePngTexture("", "x.png", 0.5f), SceneError);
}

// A 3 x 2 image decodes to 24 bytes: refused when the budget leaves 23, before allocating.
TEST(Textures, TheDecodedSizeIsCheckedAgainstTheBudgetFirst) {
    std::ifstream in(kSeeds / "rgb8.png", std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    EXPECT_NO_THROW(decodePngTexture(bytes.str(), "rgb8.png", 0.5f, 24));
    try {
        decodePngTexture(bytes.str(), "rgb8.png", 0.5f, 23);
        ADD_FAILURE() << "accepted over the budget";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("3 x 2 texels decode to 24 bytes, more than the 23 bytes"), std::string::npos) << e.what();
    }
}
