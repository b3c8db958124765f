// ColorVideoVDP's fixed figures: the display model, the band layout, the temporal filters, the CSF
// along each band's frequency and the pooling to JOD (docs/method/cvvdp.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "metrics/cvvdp.h"

namespace cbr::metrics {
namespace cvvdp_tables {
#include "metrics/cvvdp_tables.inc"
}  // namespace cvvdp_tables
namespace T = cvvdp_tables;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSafeEps = 1e-5;  // the model's power function: (x + eps)^p - eps^p

// LMS (CIE 2006) from XYZ, and DKL (D65 white) from LMS: the colour space the model works in.
constexpr double kXyzToLms2006[3][3] = {{0.187596268556126, 0.585168649077728, -0.026384263306304},
                                        {-0.133397430663221, 0.405505777260049, 0.034502127690364},
                                        {0.000244379021663, -0.000542995890619, 0.019406849066323}};
constexpr double kLms2006ToDkl[3][3] = {{1.0, 1.0, 0.0}, {1.0, -2.311130179947035, 0.0}, {-1.0, -1.0, 50.977571328718781}};

double safePow(double x, double p) { return std::pow(x + kSafeEps, p) - std::pow(kSafeEps, p); }

const T::NamedDisplay* findNamed(const std::string& name) {
    for (const auto& d : T::kNamedDisplays)
        if (name == d.name) return &d;
    return nullptr;
}

DisplayModel fromNamed(const T::NamedDisplay& d) {
    DisplayModel m;
    m.name = d.name;
    m.width = d.width;
    m.height = d.height;
    m.distance_m = d.distance_m;
    m.diagonal_in = d.diagonal_in;
    m.fov_diagonal_deg = d.fov_diagonal_deg;
    m.peak = d.peak;
    m.contrast = d.contrast;
    m.ambient_lux = d.ambient_lux;
    m.k_refl = d.k_refl;
    return m;
}

[[noreturn]] void badDisplay(const std::string& spec, const std::string& why) {
    throw std::invalid_argument("display '" + spec + "': " + why);
}

double positive(const std::string& spec, const std::string& key, const std::string& value, bool allow_zero = false) {
    size_t used = 0;
    double v = 0;
    try {
        v = std::stod(value, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != value.size() || !std::isfinite(v) || v < 0 || (!allow_zero && v == 0))
        badDisplay(spec, key + "=" + value + " is not a " + (allow_zero ? "number >= 0" : "number > 0"));
    return v;
}

void apply(DisplayModel& m, const std::string& spec, const std::string& key, const std::string& value) {
    if (key == "res") {
        int w = 0, h = 0;
        char x = 0, extra = 0;
        if (std::sscanf(value.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w <= 0 || h <= 0)
            badDisplay(spec, "res=" + value + " is not WIDTHxHEIGHT");
        m.width = w;
        m.height = h;
    } else if (key == "diagonal") {
        m.diagonal_in = positive(spec, key, value);
        m.fov_diagonal_deg = 0;
    } else if (key == "width") {
        const double ar = double(m.width) / m.height;
        m.diagonal_in = positive(spec, key, value) * std::sqrt(1 + 1 / (ar * ar)) / 0.0254;
        m.fov_diagonal_deg = 0;
    } else if (key == "distance") {
        m.distance_m = positive(spec, key, value);
    } else if (key == "fov") {
        m.fov_diagonal_deg = positive(spec, key, value);
        if (m.fov_diagonal_deg >= 180) badDisplay(spec, "fov=" + value + " is not below 180 degrees");
    } else if (key == "peak") {
        m.peak = positive(spec, key, value);
    } else if (key == "contrast") {
        m.contrast = positive(spec, key, value);
    } else if (key == "black") {
        m.contrast = m.peak / positive(spec, key, value);
    } else if (key == "ambient") {
        m.ambient_lux = positive(spec, key, value, true);
    } else if (key == "refl") {
        m.k_refl = positive(spec, key, value, true);
    } else {
        badDisplay(spec, "unknown key '" + key + "'");
    }
}

}  // namespace

double DisplayModel::reflectedLevel() const { return ambient_lux / kPi * k_refl; }

double DisplayModel::luminance(double v) const {
    v = std::clamp(v, 0.0, 1.0);
    const double lin = v > 0.04045 ? std::pow((v + 0.055) / 1.055, 2.4) : v / 12.92;
    return (peak - blackLevel()) * lin + blackLevel() + reflectedLevel();
}

double DisplayModel::ppd() const {
    const double ar = double(width) / height;
    double screen_w = 0;
    if (fov_diagonal_deg > 0) {  // the reference's headset geometry: a screen at `distance` filling the field
        const double distance_px = std::sqrt(double(width) * width + double(height) * height) /
                                   (2.0 * std::tan(fov_diagonal_deg * 0.5 * kPi / 180));
        const double height_deg = std::atan(height / 2.0 / distance_px) * 2 * 180 / kPi;
        const double height_m = 2 * std::tan(height_deg / 2 * kPi / 180) * distance_m;
        screen_w = height_m * ar;
    } else {
        const double height_mm = std::sqrt(std::pow(diagonal_in * 25.4, 2) / (1 + ar * ar));
        screen_w = ar * height_mm / 1000;
    }
    const double pix_deg = 2 * std::atan(0.5 * screen_w / width / distance_m) * 180 / kPi;
    return 1 / pix_deg;
}

std::string DisplayModel::spec() const {
    if (const auto* d = findNamed(name); d && name != "custom") return name;
    std::ostringstream s;
    s.precision(10);
    s << "res=" << width << 'x' << height << ",distance=" << distance_m;
    if (fov_diagonal_deg > 0)
        s << ",fov=" << fov_diagonal_deg;
    else
        s << ",diagonal=" << diagonal_in;
    s << ",peak=" << peak << ",contrast=" << contrast << ",ambient=" << ambient_lux << ",refl=" << k_refl;
    return s.str();
}

std::string DisplayModel::describe() const {
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s: %.4g ppd, peak %.4g cd/m^2, black %.4g cd/m^2, reflected %.4g cd/m^2",
                  name.c_str(), ppd(), peak, blackLevel(), reflectedLevel());
    return buf;
}

DisplayModel parseDisplay(const std::string& spec) {
    if (spec.empty()) badDisplay(spec, "empty");
    DisplayModel m = fromNamed(T::kNamedDisplays[0]);
    std::stringstream in(spec);
    std::string item;
    bool first = true, changed = false;
    while (std::getline(in, item, ',')) {
        const auto eq = item.find('=');
        if (eq == std::string::npos) {
            if (!first) badDisplay(spec, "'" + item + "' is not KEY=VALUE (a name goes first)");
            const auto* d = findNamed(item);
            if (!d) badDisplay(spec, "unknown display '" + item + "'");
            m = fromNamed(*d);
        } else {
            apply(m, spec, item.substr(0, eq), item.substr(eq + 1));
            changed = true;
        }
        first = false;
    }
    if (changed) m.name = "custom";
    if (!std::isfinite(m.ppd()) || m.ppd() <= 0) badDisplay(spec, "the geometry gives no pixels per degree");
    return m;
}

std::vector<std::string> displayNames() {
    std::vector<std::string> v;
    for (const auto& d : T::kNamedDisplays) v.emplace_back(d.name);
    return v;
}

std::string displayDescription(const std::string& name) {
    const auto* d = findNamed(name);
    std::string text = d ? d->description : "";
    while (!text.empty() && (text.back() == ' ' || text.back() == ','))  // the reference's "A mobile phone display, "
        text.pop_back();
    return text;
}

const char* cvvdpModelVersion() { return T::kModelVersion; }

double cvvdpJod(double q) {
    // Linear below q = 0.1 (the reference's choice, so that the map is smooth at 0).
    constexpr double kQt = 0.1;
    if (q <= kQt) return 10 - T::k_jod_a * std::pow(kQt, T::k_jod_exp - 1) * q;
    return 10 - T::k_jod_a * std::pow(q, T::k_jod_exp);
}

double cvvdpQ(double jod) {
    constexpr double kQt = 0.1;
    const double d = 10 - jod;
    const double slope = T::k_jod_a * std::pow(kQt, T::k_jod_exp - 1);
    if (d <= slope * kQt) return d / slope;
    return std::pow(d / T::k_jod_a, 1 / T::k_jod_exp);
}

double cvvdpPoolFrames(const std::vector<double>& frame_q) {
    if (frame_q.empty()) return 0;
    double sum = 0;
    for (double q : frame_q) sum += safePow(q, T::k_beta_t);
    return safePow(sum / double(frame_q.size()), 1 / T::k_beta_t);
}

double cvvdpImageQ(double frame_q) { return frame_q * T::k_image_int; }

const CvvdpParams& cvvdpParams() {
    static const CvvdpParams p = [] {
        CvvdpParams c{};
        c.mask_p = float(T::k_mask_p);
        c.mask_c_gain = float(std::pow(10.0, T::k_mask_c));
        c.d_max_gain = float(std::pow(10.0, T::k_d_max));
        c.sensitivity_gain = float(std::pow(10.0, T::k_sensitivity_correction / 20.0));
        c.image_int = float(T::k_image_int);
        const float ch_gain[4] = {1.f, 1.45f, 1.f, 1.f};  // the mult-mutual model's per-channel contrast gain
        for (int i = 0; i < 4; ++i) {
            c.mask_q[i] = float(T::k_mask_q[i]);
            c.ch_gain[i] = ch_gain[i];
            c.baseband_weight[i] = float(T::k_baseband_weight[i]);
            for (int j = 0; j < 4; ++j) c.xcm[i][j] = float(std::pow(2.0, T::k_xcm_weights[i * 4 + j]));
        }
        c.ch_weight[0] = 1.f;
        c.ch_weight[1] = c.ch_weight[2] = float(T::k_ch_chrom_w);
        c.ch_weight[3] = float(T::k_ch_trans_w);
        // Phase uncertainty: a 13-tap Gaussian of sigma pu_dilate (torchvision's sampling).
        const double sigma = T::k_pu_dilate;
        double sum = 0, k[13];
        for (int i = 0; i < 13; ++i) {
            const double x = -6.0 + i;
            k[i] = std::exp(-0.5 * (x / sigma) * (x / sigma));
            sum += k[i];
        }
        for (int i = 0; i < 13; ++i) c.pu_kernel[i] = float(k[i] / sum);
        c.beta = float(T::k_beta);
        c.beta_sch = float(T::k_beta_sch);
        c.beta_tch = float(T::k_beta_tch);
        c.beta_t = float(T::k_beta_t);
        c.jod_a = T::k_jod_a;
        c.jod_exp = T::k_jod_exp;
        return c;
    }();
    return p;
}

namespace {

// The temporal filters for `fps`: an odd window of frames covering 250 ms, each channel's
// frequency response (sustained: exp(-w^beta / sigma); transient: a band-pass peaking at 5 Hz)
// taken to time by an inverse real DFT and centred.
std::vector<std::array<float, 4>> temporalTaps(double fps) {
    const int n = int(std::ceil(0.250 * fps / 2) * 2) + 1;
    const int n_omega = n / 2 + 1;
    std::vector<std::array<double, 4>> resp(static_cast<size_t>(n_omega));
    for (int k = 0; k < n_omega; ++k) {
        const double w = n_omega == 1 ? 0 : (fps / 2) * k / (n_omega - 1);
        for (int c = 0; c < 3; ++c) resp[size_t(k)][size_t(c)] = std::exp(-std::pow(w, T::k_beta_tf[c]) / T::k_sigma_tf[c]);
        const double d = std::pow(w, T::k_beta_tf[3]) - std::pow(5.0, T::k_beta_tf[3]);
        resp[size_t(k)][3] = std::exp(-d * d / T::k_sigma_tf[3]);
    }
    std::vector<std::array<float, 4>> taps(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
        const int t = i - n / 2;  // centred
        for (int c = 0; c < 4; ++c) {
            double x = resp[0][size_t(c)];
            for (int k = 1; k < n_omega; ++k) x += 2 * resp[size_t(k)][size_t(c)] * std::cos(2 * kPi * k * t / n);
            taps[size_t(i)][size_t(c)] = float(x / n);
        }
    }
    return taps;
}

// log10 S along luminance at spatial frequency rho: the CSF table interpolated linearly in log
// rho (extrapolated past its ends), per luminance row.
std::array<float, 32> csfAlongLuminance(int channel, double rho) {
    static_assert(T::kCsfN == 32);
    std::array<float, 32> out{};
    const double x = std::log10(rho);
    int j = 0;  // the segment [j, j + 1] of log rho holding x, clamped to the table
    while (j < T::kCsfN - 2 && std::log10(T::kCsfRho[j + 1]) < x) ++j;
    const double x0 = std::log10(T::kCsfRho[j]), x1 = std::log10(T::kCsfRho[j + 1]);
    for (int l = 0; l < T::kCsfN; ++l) {
        const double y0 = T::kCsfLogS[channel][l][j], y1 = T::kCsfLogS[channel][l][j + 1];
        out[size_t(l)] = float(y0 + (y1 - y0) / (x1 - x0) * (x - x0));
    }
    return out;
}

}  // namespace

CvvdpModel makeCvvdpModel(int width, int height, const DisplayModel& display, double fps) {
    if (width < 8 || height < 8)
        throw std::invalid_argument("ColorVideoVDP needs frames of at least 8 x 8 pixels, not " + std::to_string(width) +
                                    " x " + std::to_string(height));
    const double ppd = display.ppd();
    if (!std::isfinite(ppd) || ppd <= 0 || !std::isfinite(display.luminance(1.0)) || !std::isfinite(fps))
        throw std::invalid_argument("ColorVideoVDP: display model " + display.spec() + " or frame rate is not finite");
    CvvdpModel m;
    m.width = width;
    m.height = height;
    m.image = fps <= 0;
    m.fps = m.image ? 0 : fps;
    m.channels = m.image ? 3 : 4;
    m.ppd = ppd;
    // Bands: the first at ppd/2, then 0.3228 ppd/2 halving per level, down to 0.2 cpd (at most
    // log2(min size) - 1 levels); the last level is the baseband.
    const int max_levels = int(std::floor(std::log2(std::min(width, height)))) - 1;
    int max_band = max_levels;
    for (int k = 0; k < 15; ++k) {
        const double f = (k == 0 ? 1.0 : 0.3228 * std::pow(2.0, -(k - 1))) * ppd / 2;
        if (f <= 0.2) {
            max_band = k;
            break;
        }
    }
    const int levels = std::clamp(max_band + 1, 0, max_levels);
    m.bands = levels + 1;
    for (int b = 0; b < m.bands; ++b) m.rho.push_back((b == 0 ? 1.0 : 0.3228 * std::pow(2.0, -(b - 1))) * ppd / 2);
    m.rho.back() = 0.1;
    int w = width, h = height;
    for (int b = 0; b < m.bands; ++b) {
        m.band_size.push_back({w, h});
        w = (w + 1) / 2;
        h = (h + 1) / 2;
    }
    if (!m.image) m.taps = temporalTaps(fps);
    // Linear sRGB (cd/m^2) -> XYZ -> LMS 2006 -> DKL, composed in double.
    double lms_rgb[3][3] = {}, dkl_rgb[3][3] = {};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k) lms_rgb[i][j] += kXyzToLms2006[i][k] * T::kSrgbToXyz[k][j];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            for (int k = 0; k < 3; ++k) dkl_rgb[i][j] += kLms2006ToDkl[i][k] * lms_rgb[k][j];
            m.rgb_to_dkl[i][j] = float(dkl_rgb[i][j]);
        }
    for (int v = 0; v < 256; ++v) m.lum_lut[v] = float(display.luminance(float(v) / 255.0f));
    for (int b = 0; b < m.bands; ++b) {
        std::array<std::array<float, 32>, 4> per{};
        for (int c = 0; c < 4; ++c) per[size_t(c)] = csfAlongLuminance(c, m.rho[size_t(b)]);
        m.csf_log_s.push_back(per);
    }
    m.csf_log_l0 = float(std::log10(T::kCsfLuminance[0]));
    m.csf_log_l1 = float(std::log10(T::kCsfLuminance[T::kCsfN - 1]));
    return m;
}

}  // namespace cbr::metrics
