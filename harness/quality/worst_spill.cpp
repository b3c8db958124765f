// Worst frames' images spilled to the run's temporary directory (worst_spill.h).
#include "harness/quality/worst_spill.h"

#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

namespace cbr::harness {

// Each image as its byte count (8 bytes, host order: the file lives only as long as the run)
// and its bytes.
void spillImages(const std::filesystem::path& file, const std::vector<SpilledImage>& images) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    for (const auto& image : images) {
        const uint64_t size = image ? image->size() : 0;
        out.write(reinterpret_cast<const char*>(&size), sizeof size);
        if (size) out.write(reinterpret_cast<const char*>(image->data()), std::streamsize(size));
    }
    out.close();
    if (!out) throw std::runtime_error(file.string() + ": could not write a worst frame's images (disk full?)");
}

std::vector<SpilledImage> readSpilledImages(const std::filesystem::path& file, size_t count) {
    std::vector<SpilledImage> images;
    {
        std::ifstream in(file, std::ios::binary);
        for (size_t i = 0; in && i < count; ++i) {
            uint64_t size = 0;
            if (!in.read(reinterpret_cast<char*>(&size), sizeof size)) break;
            if (size == 0) {
                images.push_back(nullptr);
                continue;
            }
            auto bytes = std::make_shared<std::vector<uint8_t>>(size_t(size));
            if (!in.read(reinterpret_cast<char*>(bytes->data()), std::streamsize(size))) break;
            images.push_back(std::move(bytes));
        }
    }
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
    if (images.size() != count)
        throw std::runtime_error(file.string() + ": a worst frame's spilled images could not be read back (" +
                                 std::to_string(images.size()) + " of " + std::to_string(count) + ")");
    return images;
}

}  // namespace cbr::harness
