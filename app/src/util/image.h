// PNG output (stb_image_write). Rows are given bottom-up, as glReadPixels returns them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace shadowlab {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 4;
    std::vector<uint8_t> pixels;   // bottom-up rows
};

bool writePng(const std::filesystem::path& path, const Image& image, std::string& error);

} // namespace shadowlab
