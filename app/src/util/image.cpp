// PNG writer: flips GL's bottom-up rows, creates the output folder when needed, and checks the write.
#include "util/image.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBIW_WINDOWS_UTF8
#include <stb_image_write.h>

#include "util/text_file.h"

namespace shadowlab {

bool writePng(const std::filesystem::path& path, const Image& image, std::string& error) {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels)) {
        error = path.string() + ": image has no pixels to write";
        return false;
    }
    // Encoded in memory, then written with every byte checked: stb's own file writer ignores
    // write errors, so a full disk (or --out /dev/full) would pass for success.
    std::string png;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
    };
    const int stride = image.width * image.channels;
    // Start at the last row with a negative stride: top-down order without a copy.
    const uint8_t* lastRow = image.pixels.data() + size_t(stride) * size_t(image.height - 1);
    if (!stbi_write_png_to_func(append, &png, image.width, image.height, image.channels, lastRow, -stride)) {
        error = path.string() + ": cannot encode PNG";
        return false;
    }
    return writeWholeFile(path, png, error);
}

} // namespace shadowlab
