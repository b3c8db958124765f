// LDR-FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG 2020).
#pragma once

#include "metrics/image.h"

namespace cbr::metrics {

// The paper's default observer: 0.7 m from a 0.7 m wide monitor of 3840 pixels,
// ppd = 0.7 * (3840 / 0.7) * pi / 180 = 67.02. NVIDIA's tool prints it rounded to 67 but
// computes with this value, so the default here is the unrounded one too.
inline constexpr double kFlipDefaultPpd = 0.7 * (3840.0 / 0.7) * (3.14159265358979323846 / 180.0);

struct FlipResult {
    Image map;          // one channel, the per-pixel FLIP error (0 = no visible difference)
    double mean = 0;    // mean of the map
    // Weighted quartiles as NVIDIA's tool defines them: each pixel weighted by its own
    // error, the smallest error e (pixels sorted ascending) at which the running sum of
    // errors first exceeds p times their total; 0 for an all-zero map.
    double q1 = 0;      // p = 0.25
    double median = 0;  // p = 0.5
    double q3 = 0;      // p = 0.75
};

// LDR-FLIP between two display-referred sRGB images in [0,1] (1 or 3 channels; one channel
// is read as grey), at `ppd` pixels per degree of visual angle. Single precision inside,
// as the tool; it reproduces the tool's means and weighted quartiles to about 1e-6.
// Throws std::invalid_argument for shapes that differ, empty or malformed images, a NaN or
// infinite value, or a ppd that is not finite and > 0.
FlipResult flip(const Image& reference, const Image& test, double ppd = kFlipDefaultPpd);

}  // namespace cbr::metrics
