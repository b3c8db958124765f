// Full-reference quality metrics: PSNR and SSIM (Wang et al. 2004), as in docs/method/measurement.md.
#pragma once

#include "metrics/image.h"

namespace cbr::metrics {

// Mean squared error over all pixels and channels. Throws std::invalid_argument
// when the shapes differ, the image is empty, has other than 1 or 3 channels, data
// does not hold width * height * channels values, or a value is NaN or infinite
// (the same checks guard psnr, ssim and ssimMap).
double mse(const Image& a, const Image& b);

// PSNR = 10 log10(1 / mse) for [0,1] data; +infinity when mse == 0 (identical images).
// Throws std::invalid_argument for a negative, NaN or infinite mse.
double psnrFromMse(double mse);
double psnr(const Image& a, const Image& b);

struct SsimResult {
    double ssim = 0;  // plain mean of per-channel SSIM (scikit-image channel_axis convention)
    double luma_ssim = 0;  // SSIM of BT.709 luma, reported besides, labelled;
                           // equal to ssim for one-channel inputs
};

// Wang et al. 2004 exactly: Gaussian 11x11 window, sigma 1.5, K1 0.01, K2 0.03, L 1,
// population variances; map averaged over the valid region (5-pixel border excluded);
// no downsampling. Matches skimage.metrics.structural_similarity(gaussian_weights=True,
// sigma=1.5, use_sample_covariance=False, data_range=1) to better than 1e-6.
// Images smaller than 11x11 throw std::invalid_argument.
SsimResult ssim(const Image& a, const Image& b);

// Per-pixel SSIM map (channel-mean for RGB), same size as the inputs; the 5-pixel
// border (kSsimBorder pixels, outside the valid region) is set to 1.0.
Image ssimMap(const Image& a, const Image& b);
constexpr int kSsimBorder = 5;

}  // namespace cbr::metrics
