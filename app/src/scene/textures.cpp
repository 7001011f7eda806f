// Material textures (docs/scene-format.md, "Textures"): PNG files decoded with libpng, and the
// procedural images of the built-in scenes (seed 001's rose window, sec. 5.3.2, and the rainbow
// quad of its layered-transparency test, sec. 5.3.3), generated here so no image is downloaded.
//
// Why libpng and not stb_image (issue 31): Debian's stb is a 2022 snapshot whose PNG reader passes
// a chunk length of 0xffffffff to a signed byte count and crashes (a segmentation fault before any
// message, seen on corrupted IDAT lengths and on a few flipped bytes). libpng checks every chunk's
// length and CRC, is fuzzed continuously upstream, and is packaged by Debian; stb keeps writing
// PNGs (util/image.cpp). Decoding keeps stb's results: no gamma conversion (values as stored),
// 16-bit samples reduced to their high byte, palettes and low bit depths expanded, grey to RGB.
#include <csetjmp>
#include <cstring>

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

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

namespace {

// What decodePng found: the rows, top-down, RGBA8, and whether the file had alpha.
struct DecodedPng {
    uint32_t width = 0, height = 0;
    bool hasAlpha = false;
    std::vector<uint8_t> rgba;
};

struct PngSource {
    const uint8_t* data;
    size_t size;
    size_t offset;
};

[[noreturn]] void pngError(png_structp png, png_const_charp message) {
    auto* text = static_cast<char*>(png_get_error_ptr(png));
    std::snprintf(text, 256, "%s", message ? message : "unknown libpng error");
    std::longjmp(png_jmpbuf(png), 1);
}

void pngWarning(png_structp, png_const_charp) {}

void pngRead(png_structp png, png_bytep out, size_t count) {
    auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
    if (count > source->size - source->offset) png_error(png, "file ends inside a chunk");
    std::memcpy(out, source->data + source->offset, count);
    source->offset += count;
}

// The chunk layout checked before libpng sees the file: every chunk's length within the PNG limit
// (2^31 - 1) and within the bytes left, up to IEND. libpng checks lengths too, but some of its
// handlers (the APNG chunks Debian patches in) act on a length before finding the file too short:
// fuzzing found an acTL chunk claiming 1.7 GB that kept one busy for over 10 s.
bool chunksFit(const uint8_t* data, size_t size, char* message) {
    size_t offset = 8;
    while (offset < size) {
        if (size - offset < 12) {
            std::snprintf(message, 256, "a chunk header at byte %zu is cut off", offset);
            return false;
        }
        const uint32_t length = uint32_t(data[offset]) << 24 | uint32_t(data[offset + 1]) << 16 |
                                uint32_t(data[offset + 2]) << 8 | uint32_t(data[offset + 3]);
        char kind[5] = {0};
        for (int i = 0; i < 4; ++i) {
            const char c = char(data[offset + 4 + size_t(i)]);
            kind[i] = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ? c : '?';
        }
        if (length > 0x7FFFFFFFu || length > size - offset - 12) {
            std::snprintf(message, 256, "chunk %s at byte %zu claims %u bytes, more than the %zu left", kind, offset, length,
                          size - offset - 12);
            return false;
        }
        offset += 12 + size_t(length);
        if (std::memcmp(kind, "IEND", 4) == 0) return true;
    }
    std::snprintf(message, 256, "no IEND chunk");
    return false;
}

// libpng reports errors by longjmp: no object with a destructor lives in this frame between
// setjmp and the end (the row pointers and pixels are the caller's), so nothing is skipped.
// Returns "" or the problem. The size is checked against kMaxTextureSize before the pixels are
// allocated; the caller's `out.rgba` is allocated here.
const char* decodePng(const uint8_t* data, size_t size, uint64_t maxDecodedBytes, DecodedPng& out, std::vector<png_bytep>& rows,
                      char* message) {
    if (size < 8 || png_sig_cmp(data, 0, 8) != 0) return "not a PNG file (no PNG signature)";
    if (!chunksFit(data, size, message)) return message;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, message, pngError, pngWarning);
    if (!png) return "libpng could not start";
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        return "libpng could not start";
    }
    PngSource source{data, size, 0};
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return message;
    }
    png_set_read_fn(png, &source, pngRead);
    png_set_user_limits(png, kMaxTextureSize, kMaxTextureSize);
    png_set_chunk_malloc_max(png, 8u << 20);   // ancillary chunks (text, profiles): 8 MiB at most
    png_read_info(png, info);
    out.width = png_get_image_width(png, info);
    out.height = png_get_image_height(png, info);
    const int colourType = png_get_color_type(png, info);
    out.hasAlpha = (colourType & PNG_COLOR_MASK_ALPHA) != 0 || png_get_valid(png, info, PNG_INFO_tRNS) != 0;
    png_set_expand(png);   // palette to RGB, grey below 8 bits to 8, tRNS to alpha
    png_set_strip_16(png);
    png_set_gray_to_rgb(png);
    if (!out.hasAlpha) png_set_filler(png, 0xFF, PNG_FILLER_AFTER);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != size_t(out.width) * 4) png_error(png, "unexpected row layout after expansion");
    if (uint64_t(out.width) * uint64_t(out.height) * 4 > maxDecodedBytes) {
        std::snprintf(message, 256, "%u x %u texels decode to %llu bytes, more than the %llu bytes the scene budget leaves",
                      out.width, out.height, static_cast<unsigned long long>(uint64_t(out.width) * out.height * 4),
                      static_cast<unsigned long long>(maxDecodedBytes));
        png_destroy_read_struct(&png, &info, nullptr);
        return message;
    }
    out.rgba.resize(size_t(out.width) * size_t(out.height) * 4);   // at most 8192^2 * 4 (user limits)
    rows.resize(out.height);
    for (uint32_t y = 0; y < out.height; ++y) rows[y] = out.rgba.data() + size_t(y) * size_t(out.width) * 4;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return "";
}

} // namespace

Texture decodePngTexture(const std::string& bytes, const std::string& name, float plainAlpha, uint64_t maxDecodedBytes) {
    DecodedPng png;
    std::vector<png_bytep> rows;
    char message[256] = {0};
    const char* problem =
        decodePng(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), maxDecodedBytes, png, rows, message);
    if (problem[0] != '\0') {
        const std::string text = problem;
        if (text.find("exceeds user limit") != std::string::npos || text.find("Image width") != std::string::npos ||
            text.find("Image height") != std::string::npos)
            throw SceneError(name + ": not a usable PNG image (" + text + "); a texture is 1 to " +
                             std::to_string(kMaxTextureSize) + " texels on each side");
        throw SceneError(name + ": not a readable PNG image (" + text + ")");
    }
    if (png.width < 1 || png.height < 1)
        throw SceneError(name + ": " + std::to_string(png.width) + " x " + std::to_string(png.height) +
                         " texels; a texture is 1 to " + std::to_string(kMaxTextureSize) + " texels on each side");
    const int width = int(png.width), height = int(png.height);
    Texture texture = blank(name, width, height);
    // PNG rows run top-down; textures are stored bottom-up (uv (0, 0) at the image's lower left).
    for (int y = 0; y < height; ++y) {
        const uint8_t* row = png.rgba.data() + static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width) * 4;
        for (int x = 0; x < width; ++x) {
            const uint8_t* in = row + static_cast<size_t>(x) * 4;
            uint8_t* out = &texture.rgba[(static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4];
            std::copy(in, in + 4, out);
            // An image without alpha: black is opaque (lead, tracery), any other colour is glass
            // of the material's alpha.
            if (!png.hasAlpha) out[3] = (in[0] | in[1] | in[2]) == 0 ? 255 : toByte(plainAlpha);
        }
    }
    return texture;
}

Texture loadPngTexture(const std::filesystem::path& file, float plainAlpha, uint64_t maxFileBytes, uint64_t maxDecodedBytes) {
    std::string bytes, error;
    if (!readRegularFile(file, maxFileBytes, bytes, error, "texture")) throw SceneError(error);
    return decodePngTexture(bytes, file.string(), plainAlpha, maxDecodedBytes);
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
