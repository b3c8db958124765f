// `cbrbench score REFERENCE IMAGE` (score_image.h): the suite's metrics on two saved images.
#include "harness/score/score_image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "harness/base/exit_codes.h"
#include "harness/jobs/options.h"
#include "metrics/cvvdp.h"
#include "metrics/flip.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "settings/table.h"

namespace cbr::harness {

int scoreImages(const std::string& ref_file, const std::string& img_file, const std::string& crop, double flip_ppd,
                float exposure, const std::string& display) {
    cbr::harness::checkFlipPpd(flip_ppd);
    settings::Tunables tune;
    settings::setText(*settings::find("display"), tune, display);
    tune.flip_ppd = flip_ppd;
    auto ref_in = cbr::metrics::readDisplayImage(ref_file, exposure);
    auto img_in = cbr::metrics::readDisplayImage(img_file, exposure);
    const auto& ref = ref_in.image;
    const auto& img = img_in.image;
    if (ref.width != img.width || ref.height != img.height)
        throw std::invalid_argument(img_file + ": " + std::to_string(img.width) + "x" + std::to_string(img.height) +
                                    "; expected the reference's size " + std::to_string(ref.width) + "x" +
                                    std::to_string(ref.height));
    int x = 0, y = 0, w = ref.width, h = ref.height;
    if (!crop.empty() && (std::sscanf(crop.c_str(), "%d,%d,%d,%d", &x, &y, &w, &h) != 4 || x < 0 || y < 0 || w < 11 ||
                          h < 11 || x + w > ref.width || y + h > ref.height))
        throw std::invalid_argument("--crop " + crop + ": expected X,Y,W,H inside the image, W and H at least 11");
    size_t stride = size_t(ref.width) * 4, offset = size_t(y) * stride + size_t(x) * 4;
    auto a = cbr::metrics::fromRgba8(ref.pixels.data() + offset, w, h, stride);
    auto b = cbr::metrics::fromRgba8(img.pixels.data() + offset, w, h, stride);
    double psnr = cbr::metrics::psnr(a, b);
    auto s = cbr::metrics::ssim(a, b);
    auto f = cbr::metrics::flip(a, b, settings::flipPpd(tune));
    // ColorVideoVDP reads the 8-bit display values; the crop as its own tightly packed image.
    std::vector<uint8_t> ra(size_t(w) * size_t(h) * 4), rb(ra.size());
    for (int row = 0; row < h; ++row) {
        const size_t from = offset + size_t(row) * stride, to = size_t(row) * size_t(w) * 4;
        std::copy_n(ref.pixels.data() + from, size_t(w) * 4, ra.data() + to);
        std::copy_n(img.pixels.data() + from, size_t(w) * 4, rb.data() + to);
    }
    cbr::metrics::CvvdpTracker cvvdp(w, h, tune.display, 0.0);
    const double jod = cbr::metrics::cvvdpJod(cbr::metrics::cvvdpImageQ(cvvdp.addRgba8(ra.data(), rb.data()).q));
    std::printf("psnr_db %s\nssim %.6f\nssim_luma %.6f\ncvvdp_jod %.4f\nflip_mean %.6f\nflip_q1 %.6f\nflip_median "
                "%.6f\nflip_q3 %.6f\n",
                std::isinf(psnr) ? "inf" : std::to_string(psnr).c_str(), s.ssim, s.luma_ssim, jod, f.mean, f.q1,
                f.median, f.q3);
    for (const auto* in : {&ref_in, &img_in})
        if (!in->conversion.empty()) std::printf("note %s\n", in->conversion.c_str());
    return kExitDone;
}

}  // namespace cbr::harness
