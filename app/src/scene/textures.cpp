// Material textures (docs/scene-format.md, "Textures"): PNG files read with stb_image, and the
// procedural images of the built-in scenes (seed 001's rose window, sec. 5.3.2, and the rainbow
// quad of its layered-transparency test, sec. 5.3.3), generated here so no image is downloaded.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO            // files are read through readRegularFile (size-checked)
#define STBI_FAILURE_USERMSG
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <glm/gtc/constants.hpp>

#include "scene/scene.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

uint8_t toByte(float value) { return static_cast<uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f)); }

void setTexel(Texture& texture, int x, int y, glm::vec3 rgb, float alpha) {
    uint8_t* texel = &texture.rgba[(static_cast<size_t>(y) * static_cast<size_t>(texture.width) + static_cast<size_t>(x)) * 4];
    texel[0] = toByte(rgb.r);
    texel[1] = toByte(rgb.g);
    texel[2] = toByte(rgb.b);
    texel[3] = toByte(alpha);
}

Texture blank(const std::string& name, int width, int height) {
    Texture texture;
    texture.name = name;
    texture.width = width;
    texture.height = height;
    texture.rgba.assign(static_cast<size_t>(width) * static_cast<size_t>(height) * 4, 0);
    return texture;
}

glm::vec3 hue(float h) {
    const glm::vec3 k = glm::abs(glm::fract(glm::vec3(h) + glm::vec3(0.0f, 2.0f / 3.0f, 1.0f / 3.0f)) * 6.0f - 3.0f);
    return glm::clamp(k - 1.0f, 0.0f, 1.0f);
}

uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

} // namespace

Texture loadPngTexture(const std::filesystem::path& file, float plainAlpha, uint64_t maxFileBytes) {
    std::string bytes, error;
    if (!readRegularFile(file, maxFileBytes, bytes, error, "texture"))
        throw SceneError(error);
    int width = 0, height = 0, channels = 0;
    if (bytes.size() > size_t(INT32_MAX)) throw SceneError(file.string() + ": texture file too large");
    const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
    if (!stbi_info_from_memory(data, static_cast<int>(bytes.size()), &width, &height, &channels))
        throw SceneError(file.string() + ": not a readable PNG image (" + stbi_failure_reason() + ")");
    if (width < 1 || height < 1 || width > kMaxTextureSize || height > kMaxTextureSize)
        throw SceneError(file.string() + ": " + std::to_string(width) + " x " + std::to_string(height) +
                         " texels; a texture is 1 to " + std::to_string(kMaxTextureSize) + " texels on each side");
    stbi_uc* pixels = stbi_load_from_memory(data, static_cast<int>(bytes.size()), &width, &height, &channels, 4);
    if (!pixels) throw SceneError(file.string() + ": not a readable PNG image (" + stbi_failure_reason() + ")");
    Texture texture = blank(file.string(), width, height);
    // PNG rows run top-down; textures are stored bottom-up (uv (0, 0) at the image's lower left).
    const bool plain = channels == 1 || channels == 3;
    for (int y = 0; y < height; ++y) {
        const stbi_uc* row = pixels + static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width) * 4;
        for (int x = 0; x < width; ++x) {
            const stbi_uc* in = row + static_cast<size_t>(x) * 4;
            uint8_t* out = &texture.rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
            std::copy(in, in + 4, out);
            // An image without alpha: black is opaque (lead, tracery), any other colour is glass
            // of the material's alpha.
            if (plain) out[3] = (in[0] | in[1] | in[2]) == 0 ? 255 : toByte(plainAlpha);
        }
    }
    stbi_image_free(pixels);
    return texture;
}

// A rose window after seed 001's Strasbourg test image (Fig. 5.3.2.A): black tracery (opaque)
// around many coloured glass cells (alpha `alpha`), with coarse detail (rings of 8, 16 and 32
// cells, a central rosette) and fine detail (thin leading lines inside the outer cells, small
// foiled roundels). Black outside the window's circle.
Texture makeRoseWindowTexture(int size, uint32_t seed, float alpha) {
    Texture texture = blank("procedural:rose-window", size, size);
    const glm::vec3 palette[] = {{0.10f, 0.20f, 0.85f}, {0.85f, 0.10f, 0.10f}, {0.95f, 0.75f, 0.15f},
                                 {0.15f, 0.65f, 0.25f}, {0.55f, 0.15f, 0.70f}, {0.20f, 0.60f, 0.90f},
                                 {0.90f, 0.45f, 0.10f}, {0.85f, 0.85f, 0.80f}};
    constexpr int kPaletteSize = 8;
    const float pi = glm::pi<float>();
    const float texel = 2.0f / static_cast<float>(size);
    const float lead = std::max(0.012f, 1.2f * texel);   // tracery at least a texel wide
    const float fine = std::max(0.004f, 0.8f * texel);   // leading of the small panes
    // Ring boundaries (radius) and cells per ring.
    const float rings[] = {0.0f, 0.16f, 0.42f, 0.70f, 0.95f};
    const int sectors[] = {1, 8, 16, 32};
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::vec2 p{(static_cast<float>(x) + 0.5f) * texel - 1.0f, (static_cast<float>(y) + 0.5f) * texel - 1.0f};
            const float r = glm::length(p);
            float angle = std::atan2(p.y, p.x);
            if (angle < 0.0f) angle += 2.0f * pi;
            if (r >= rings[4]) {
                setTexel(texture, x, y, glm::vec3(0.0f), 1.0f);
                continue;
            }
            int ring = 0;
            while (ring < 3 && r >= rings[ring + 1]) ++ring;
            bool tracery = std::abs(r - rings[ring]) < lead || std::abs(r - rings[ring + 1]) < lead;
            const float sectorAngle = 2.0f * pi / static_cast<float>(sectors[ring]);
            const int sector = std::min(sectors[ring] - 1, static_cast<int>(angle / sectorAngle));
            const float local = angle - (static_cast<float>(sector) + 0.5f) * sectorAngle; // from the cell's mid-line
            if (ring > 0 && std::abs(std::abs(local) - 0.5f * sectorAngle) * r < lead) tracery = true; // radial mullions
            uint32_t cell = hash32(seed * 977u + static_cast<uint32_t>(ring) * 131u + static_cast<uint32_t>(sector));
            if (ring == 0) {
                // Central rosette: six petals around a disc.
                const float petal = 0.11f + 0.04f * std::cos(6.0f * angle);
                if (std::abs(r - petal) < lead * 0.8f || std::abs(r - 0.05f) < lead * 0.8f) tracery = true;
                cell = hash32(seed * 977u + (r < 0.05f ? 7u : r < petal ? 3u : 5u));
            } else {
                // A roundel in the middle of each cell: a foiled circle of other glass.
                const float mid = 0.5f * (rings[ring] + rings[ring + 1]);
                const glm::vec2 centre = mid * glm::vec2(std::cos(angle - local), std::sin(angle - local));
                const float roundel = 0.3f * std::min(rings[ring + 1] - rings[ring], sectorAngle * mid);
                const float d = glm::length(p - centre);
                const float foil = roundel * (1.0f + 0.15f * std::cos(4.0f * std::atan2(p.y - centre.y, p.x - centre.x)));
                if (std::abs(d - foil) < lead * 0.7f) tracery = true;
                if (d < foil) cell = hash32(cell + 0x51u);
                // Fine leading in the outer ring: small panes on a grid turned with the cell.
                if (ring == 3 && d >= foil) {
                    const glm::vec2 q{r * std::cos(local), r * std::sin(local)};
                    const float pane = 0.035f;
                    const glm::vec2 f = glm::abs(glm::fract(q / pane) - 0.5f) * pane;
                    if (std::min(0.5f * pane - f.x, 0.5f * pane - f.y) < fine) tracery = true;
                    cell = hash32(cell + static_cast<uint32_t>(std::floor(q.x / pane)) * 13u +
                                  static_cast<uint32_t>(std::floor(q.y / pane + 100.0f)));
                }
            }
            if (tracery) {
                setTexel(texture, x, y, glm::vec3(0.0f), 1.0f);
                continue;
            }
            // Brightness varies per pane a little, as hand-made glass does.
            const glm::vec3 colour = palette[cell % kPaletteSize] * (0.8f + 0.2f * static_cast<float>((cell >> 8) % 5) / 4.0f);
            setTexel(texture, x, y, colour, alpha);
        }
    return texture;
}

// Hue bands across u (red to violet), every texel glass of alpha `alpha`.
Texture makeRainbowTexture(int size, float alpha) {
    Texture texture = blank("procedural:rainbow", size, 1);
    for (int x = 0; x < size; ++x)
        setTexel(texture, x, 0, hue(0.8f * (static_cast<float>(x) + 0.5f) / static_cast<float>(size)), alpha);
    return texture;
}

// Square cells of two colours: `a` where (x + y) is even, else `b` (both with alpha).
Texture makeCheckerTexture(int size, glm::vec4 a, glm::vec4 b) {
    Texture texture = blank("procedural:checker", size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::vec4 c = (x + y) % 2 == 0 ? a : b;
            setTexel(texture, x, y, glm::vec3(c), c.a);
        }
    return texture;
}

} // namespace shadowlab
