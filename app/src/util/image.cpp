// PNG writer: flips GL's bottom-up rows and creates the output folder when needed.
#include "util/image.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBIW_WINDOWS_UTF8
#include <stb_image_write.h>

#include <system_error>

namespace shadowlab {

bool writePng(const std::filesystem::path& path, const Image& image, std::string& error) {
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels)) {
        error = path.string() + ": image has no pixels to write";
        return false;
    }
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    const int stride = image.width * image.channels;
    // Start at the last row with a negative stride: top-down order without a copy.
    const uint8_t* lastRow = image.pixels.data() + size_t(stride) * size_t(image.height - 1);
    if (!stbi_write_png(path.c_str(), image.width, image.height, image.channels, lastRow, -stride)) {
        error = path.string() + ": cannot write PNG (" + (ec ? ec.message() : "check the folder exists and is writable") + ")";
        return false;
    }
    return true;
}

} // namespace shadowlab
