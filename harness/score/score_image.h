// `cbrbench score REFERENCE IMAGE`: the suite's metrics on saved images (any format
// OpenImageIO reads), so any number a run reports can be recomputed.
#pragma once

#include <string>

namespace cbr::harness {

// Prints PSNR, SSIM (colour and luma), ColorVideoVDP's JOD (the pair as an image, on `display`:
// a --display spec) and FLIP's mean and quartiles (flip_ppd 0: the display's), one per line;
// `crop` "X,Y,W,H" or "" for the whole image. Bad input throws std::invalid_argument (one line).
int scoreImages(const std::string& ref_file, const std::string& img_file, const std::string& crop, double flip_ppd,
                float exposure, const std::string& display = "standard_4k");

}  // namespace cbr::harness
