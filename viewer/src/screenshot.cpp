#include "screenshot.h"

#include <stb_image_write.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "gl.h"

namespace cyclone::viewer {

void writeScreenshot(const std::string &path, int width, int height) {
    const std::size_t row = static_cast<std::size_t>(width) * 3;
    std::vector<unsigned char> pixels(row * static_cast<std::size_t>(height));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
    // GL's rows run bottom to top, PNG's top to bottom.
    std::vector<unsigned char> flipped(pixels.size());
    for (int y = 0; y < height; ++y) {
        std::memcpy(&flipped[static_cast<std::size_t>(y) * row],
                    &pixels[static_cast<std::size_t>(height - 1 - y) * row], row);
    }
    const std::string temporary = path + ".part";
    if (stbi_write_png(temporary.c_str(), width, height, 3, flipped.data(), static_cast<int>(row)) == 0) {
        std::remove(temporary.c_str());
        throw std::runtime_error(path + ": cannot write the screenshot");
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        std::remove(temporary.c_str());
        throw std::runtime_error(path + ": cannot write the screenshot (rename failed)");
    }
}

}  // namespace cyclone::viewer
