// ColorVideoVDP (Mantiuk, Hammou, Hanji, "ColorVideoVDP: A visual difference predictor for image,
// video and display distortions", ACM TOG 43(4), 2024): a full-reference video metric in JOD
// (just-objectionable differences; 10 = identical, one JOD less = 75% of viewers prefer the
// better). What is computed, the units and where this departs from the reference:
// docs/method/cvvdp.md. The calibrated figures: cvvdp_tables.inc (scripts/cvvdp-tables).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "metrics/image.h"

namespace cbr::metrics {

// How the frames are seen: the display's size, distance and light (ColorVideoVDP's display
// model: an sRGB display of `peak` cd/m^2 with black peak/contrast, plus the ambient light its
// screen reflects).
struct DisplayModel {
    std::string name = "standard_4k";  // a named model, or "custom" once a field was changed
    int width = 3840, height = 2160;   // the display's pixels
    double distance_m = 0.7472;        // viewing distance
    double diagonal_in = 30;           // screen diagonal (0: given by fov_diagonal_deg)
    double fov_diagonal_deg = 0;       // field of view along the diagonal (headsets; 0: not given)
    double peak = 200;                 // peak luminance, cd/m^2
    double contrast = 1000;            // peak / black level
    double ambient_lux = 250;          // illuminance on the screen
    double k_refl = 0.005;             // the screen's reflectivity

    double ppd() const;  // pixels per degree at the centre of the screen
    double blackLevel() const { return peak / contrast; }
    double reflectedLevel() const;  // ambient_lux / pi * k_refl
    // Luminance (cd/m^2) of an sRGB channel value v in [0, 1] on this display.
    double luminance(double v) const;
    // The spec parseDisplay() reads back to this model, and one line for people.
    std::string spec() const;
    std::string describe() const;
};

// "NAME" (displayNames()), or NAME followed by ",KEY=VALUE" overrides, or KEY=VALUE pairs alone
// (over standard_4k). Keys: res=WxH, diagonal=INCHES, width=METRES (screen width; sets the
// diagonal), distance=METRES, fov=DEGREES (diagonal field of view), peak=CD/M2, contrast=RATIO,
// black=CD/M2, ambient=LUX, refl=FRACTION. Throws std::invalid_argument naming what is wrong (the
// settings table's --display row adds what is accepted).
DisplayModel parseDisplay(const std::string& spec);
std::vector<std::string> displayNames();
std::string displayDescription(const std::string& name);  // "" for an unknown name

// Sequence figures: per-frame values q (the frame's differences pooled over bands and channels)
// pool over frames to the sequence's q, which maps to JOD. An image (one frame scored as an image)
// is scaled by the model's image-integration factor instead.
const char* cvvdpModelVersion();  // the calibrated parameters' version, e.g. "0.5.6"
double cvvdpJod(double q);
double cvvdpQ(double jod);  // the inverse of cvvdpJod (jod <= 10)
double cvvdpPoolFrames(const std::vector<double>& frame_q);
double cvvdpImageQ(double frame_q);

struct CvvdpFrame {
    double q = 0;     // this frame's pooled difference
    double jod = 10;  // cvvdpJod(q): the JOD a sequence of such frames would get
    // Per-pixel difference, 1 - JOD/10 of the reconstructed difference pyramid (0: none; not clamped:
    // strong flicker passes 1), on request.
    std::optional<Image> map;
};

// The model's fixed figures for frames of one size on one display at one frame rate: what the
// CPU tracker and the device scorer both use.
struct CvvdpModel {
    int width = 0, height = 0;
    double fps = 0;             // 0: image mode
    bool image = false;         // no temporal channels (3 channels, not 4)
    int channels = 4;           // Y sustained, RG, YV[, Y transient]
    double ppd = 0;
    int bands = 0;              // Laplacian bands, the last the baseband
    std::vector<double> rho;    // cycles per degree of each band (the baseband's 0.1)
    std::vector<std::array<int, 2>> band_size;  // width, height of each level
    // Temporal filters: taps[channel][k], k over the window's frames oldest first.
    std::vector<std::array<float, 4>> taps;
    float rgb_to_dkl[3][3] = {};  // linear display RGB (cd/m^2) to DKL (achromatic, RG, YV)
    float lum_lut[256] = {};      // display luminance of each 8-bit sRGB value
    // log10 sensitivity along luminance (kCsfN points at csfLogLuminance()) for each band and
    // channel, the CSF's interpolation along rho done: [band][channel][luminance].
    std::vector<std::array<std::array<float, 32>, 4>> csf_log_s;
    float csf_log_l0 = 0, csf_log_l1 = 0;  // log10 of the CSF table's first and last luminance
    int filterFrames() const { return int(taps.size()); }
};
CvvdpModel makeCvvdpModel(int width, int height, const DisplayModel& display, double fps);

// Named constants of the model (cvvdp_tables.inc), for the device scorer.
struct CvvdpParams {
    float mask_p, mask_c_gain, d_max_gain, sensitivity_gain, image_int;
    float mask_q[4], xcm[4][4], ch_gain[4], ch_weight[4], baseband_weight[4];
    float pu_kernel[13];
    float beta, beta_sch, beta_tch, beta_t;
    double jod_a, jod_exp;  // cvvdpJod's figures (above q = 0.1: 10 - jod_a q^jod_exp)
};
const CvvdpParams& cvvdpParams();

// Feeds one variant's frames in order against the reference's; keeps the temporal filter's
// window (filterFrames() frames of each, 6 bytes a pixel each) and nothing else between frames.
class CvvdpTracker {
public:
    // fps <= 0: image mode (for a single frame). Throws std::invalid_argument for frames smaller
    // than 8 x 8 or a display model that is not finite.
    CvvdpTracker(int width, int height, const DisplayModel& display, double fps);
    ~CvvdpTracker();
    // Tightly packed 8-bit RGBA (row stride 4 * width, alpha ignored), sRGB encoded.
    CvvdpFrame addRgba8(const uint8_t* reference, const uint8_t* test, bool want_map = false);
    const CvvdpModel& model() const;
    size_t stateBytes() const;  // the window's bytes

private:
    struct State;
    std::unique_ptr<State> s_;
};

}  // namespace cbr::metrics
