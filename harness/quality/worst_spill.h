// The CPU scorer's worst frames on disk while the run goes on (in the run's temporary
// directory), read back one at a time when worst/ is written: meanwhile the run holds none of
// their images, as the device scorer keeps its own on the device.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

namespace cbr::harness {

using SpilledImage = std::shared_ptr<const std::vector<uint8_t>>;

// Writes the images (a null or empty one as empty) to `file`, replacing it. Throws
// std::runtime_error naming the file when it cannot be written.
void spillImages(const std::filesystem::path& file, const std::vector<SpilledImage>& images);

// The images spillImages wrote, in order (null for an empty one); the file is removed. Throws
// std::runtime_error naming the file when it cannot be read or holds other than `count` images.
std::vector<SpilledImage> readSpilledImages(const std::filesystem::path& file, size_t count);

}  // namespace cbr::harness
