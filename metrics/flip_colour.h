// Internal to cbr_metrics' FLIP (flip.cpp): colour constants, the sRGB decode of display
// images (8-bit codes or doubles) to YCxCz, and float math that vectorises.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>

#include "metrics/image.h"

// Everything here is inlined into flip.cpp's tile loop (its AVX2 clone included), and built
// with flip.cpp's options (metrics/CMakeLists.txt): no FMA contraction, no errno.
namespace cbr::metrics::flip_detail {

// Linear sRGB <-> CIE XYZ with the D65 white, in the tool's single-precision values.
constexpr float kWhite[3] = {0.950428545f, 1.0f, 1.088900371f};
constexpr float kInvWhite[3] = {1.052156925f, 1.0f, 0.918357670f};
constexpr float kRgbToXyz[3][3] = {
    {10135552.0f / 24577794.0f, 8788810.0f / 24577794.0f, 4435075.0f / 24577794.0f},
    {2613072.0f / 12288897.0f, 8788810.0f / 12288897.0f, 887015.0f / 12288897.0f},
    {1425312.0f / 73733382.0f, 8788810.0f / 73733382.0f, 70074185.0f / 73733382.0f}};
constexpr float kXyzToRgb[3][3] = {{3.241003275f, -1.537398934f, -0.498615861f},
                                   {-0.969224334f, 1.875930071f, 0.041554224f},
                                   {0.055639423f, -0.204011202f, 1.057148933f}};
// sRGB transfer, decoded in single precision as the tool does.
inline float srgbToLinear(float s) { return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f); }

// Display images hold 8-bit code values v / 255: a table lookup replaces the power.
struct DecodeTable {
    std::array<double, 256> code{};   // k / 255, as fromRgba8 writes it
    std::array<float, 256> linear{};  // srgbToLinear(float(k) / 255)
    DecodeTable() {
        for (int k = 0; k < 256; ++k) {
            code[size_t(k)] = k / 255.0;
            linear[size_t(k)] = srgbToLinear(float(k) / 255.0f);
        }
    }
};

// One display value to linear RGB. Values outside [0,1] are clamped (as the tool clamps the
// decoded image); NaN and infinities set `bad`.
inline float decode(const DecodeTable& t, double v, bool& bad) {
    if (!(v >= 0.0 && v <= 1.0)) {
        if (!std::isfinite(v)) {
            bad = true;
            return 0.0f;
        }
        v = v < 0.0 ? 0.0 : 1.0;
    }
    const int k = int(v * 255.0 + 0.5);
    return t.code[size_t(k)] == v ? t.linear[size_t(k)] : srgbToLinear(float(v));
}

// Linear RGB to YCxCz: Y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn).
[[gnu::always_inline]] inline void linearToYCxCz(float r, float g, float b, float& py, float& pcx, float& pcz) {
    const float X = (kRgbToXyz[0][0] * r + kRgbToXyz[0][1] * g + kRgbToXyz[0][2] * b) * kInvWhite[0];
    const float Y = (kRgbToXyz[1][0] * r + kRgbToXyz[1][1] * g + kRgbToXyz[1][2] * b) * kInvWhite[1];
    const float Z = (kRgbToXyz[2][0] * r + kRgbToXyz[2][1] * g + kRgbToXyz[2][2] * b) * kInvWhite[2];
    py = 116.0f * Y - 16.0f;
    pcx = 500.0f * (X - Y);
    pcz = 200.0f * (Y - Z);
}

// One image as the tiles read it: its 8-bit codes when every value is one (checked codes of
// an Image, or RGBA8 bytes as read back), else its doubles.
struct Source {
    const Image* image = nullptr;    // read when codes is null
    const uint8_t* codes = nullptr;  // k for each value k / 255, or null
    int width = 0, height = 0;
    int channels = 3;                // 1: grey
    int stride = 3;                  // codes per pixel: channels, or 4 for RGBA8 (alpha ignored)
};

// Columns [first, first + count) of row yy, all inside the image, to YCxCz: codes through
// the table without branches (vectorised with gathers), doubles through decode().
[[gnu::always_inline]] inline bool spanToYCxCz(const DecodeTable& table, const Source& source, int yy, int first,
                                               int count, float* __restrict py, float* __restrict pcx,
                                               float* __restrict pcz) {
    const int c = source.channels;
    const size_t pixel = size_t(yy) * source.width + size_t(first);
    if (!source.codes) {
        bool bad = false;
        const double* in = source.image->data.data() + pixel * c;
        for (int i = 0; i < count; ++i) {
            const double* p = in + size_t(i) * c;
            const float r = decode(table, p[0], bad);
            const float g = c == 3 ? decode(table, p[1], bad) : r;
            const float b = c == 3 ? decode(table, p[2], bad) : r;
            linearToYCxCz(r, g, b, py[i], pcx[i], pcz[i]);
        }
        return !bad;
    }
    const uint8_t* __restrict in = source.codes + pixel * source.stride;
    const float* __restrict linear = table.linear.data();
    if (c == 1) {
        for (int i = 0; i < count; ++i) {
            const float v = linear[in[i]];
            linearToYCxCz(v, v, v, py[i], pcx[i], pcz[i]);
        }
    } else if (source.stride == 4) {
        for (int i = 0; i < count; ++i)
            linearToYCxCz(linear[in[4 * i]], linear[in[4 * i + 1]], linear[in[4 * i + 2]], py[i], pcx[i], pcz[i]);
    } else {
        for (int i = 0; i < count; ++i)
            linearToYCxCz(linear[in[3 * i]], linear[in[3 * i + 1]], linear[in[3 * i + 2]], py[i], pcx[i], pcz[i]);
    }
    return true;
}

// Row yy of an sRGB image, columns first .. first + count - 1 clamped to the image (the
// paper's filters see the border pixels repeated), to YCxCz. Returns false for a NaN or
// infinite value.
[[gnu::always_inline]] inline bool toYCxCz(const DecodeTable& table, const Source& source, int yy, int first,
                                           int count, float* py, float* pcx, float* pcz) {
    const int lo = std::max(first, 0), hi = std::min(first + count, source.width);
    const bool ok = spanToYCxCz(table, source, yy, lo, hi - lo, py + (lo - first), pcx + (lo - first),
                                pcz + (lo - first));
    for (int i = 0; i < lo - first; ++i) {
        py[i] = py[lo - first];
        pcx[i] = pcx[lo - first];
        pcz[i] = pcz[lo - first];
    }
    for (int i = hi - first; i < count; ++i) {
        py[i] = py[hi - 1 - first];
        pcx[i] = pcx[hi - 1 - first];
        pcz[i] = pcz[hi - 1 - first];
    }
    return ok;
}

// t^(1/3) for t > 0: a first guess from the float's bits (the exponent divided by 3, within
// a few per cent) and two Halley steps (cubic convergence), all of it vectorisable.
[[gnu::always_inline]] inline float cubeRoot(float t) {
    const int32_t bits = std::bit_cast<int32_t>(t);
    float y = std::bit_cast<float>(int32_t(float(bits) * (1.0f / 3.0f)) + 0x2A555555);
    for (int i = 0; i < 2; ++i) {
        const float y3 = y * y * y;
        y = y * (y3 + 2.0f * t) / (2.0f * y3 + t);
    }
    return y;
}

// 2^y to about 2 ulp: y = n + f with n an integer (rounded by the 1.5 * 2^23 trick, which
// plain vector adds perform) and |f| <= 1/2, 2^f by its Taylor series to degree 7 (error
// below 1e-8), 2^n put into the exponent bits. Below 2^-126 the result is 0.
[[gnu::always_inline]] inline float exp2Approx(float y) {
    constexpr float kRound = 12582912.0f;  // 1.5 * 2^23: adding it rounds to an integer
    const float clamped = std::min(std::max(y, -127.0f), 127.0f);
    const float r = (clamped + kRound) - kRound;
    const float f = clamped - r;
    constexpr float l = float(std::numbers::ln2);
    const float p =
        1.0f +
        f * (l + f * (l * l / 2 + f * (l * l * l / 6 + f * (l * l * l * l / 24 +
                                                             f * (l * l * l * l * l / 120 +
                                                                  f * (l * l * l * l * l * l / 720 +
                                                                       f * (l * l * l * l * l * l * l / 5040)))))));
    const int32_t n = int32_t(r);
    const float scale = std::bit_cast<float>((std::max(n, int32_t(-126)) + 127) << 23);
    return n < -126 ? 0.0f : p * scale;
}

// log2(x) for finite x > 0 (subnormals included): x = m 2^e with m in [sqrt(1/2), sqrt(2)),
// ln(m) = 2 atanh(t), t = (m - 1) / (m + 1), |t| <= 0.172, by its series to t^7 (error
// below 1e-12).
[[gnu::always_inline]] inline float log2Approx(float x) {
    const bool tiny = x < 1.17549435e-38f;
    const float scaled = tiny ? x * 8388608.0f : x;  // 2^23: subnormals become normal
    const int32_t bits = std::bit_cast<int32_t>(scaled);
    int32_t e = ((bits >> 23) & 0xFF) - 127 - (tiny ? 23 : 0);
    float m = std::bit_cast<float>((bits & 0x007FFFFF) | 0x3F800000);
    const bool high = m > float(std::numbers::sqrt2);
    m = high ? 0.5f * m : m;
    e += high ? 1 : 0;
    const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    const float ln = 2.0f * t * (1.0f + t2 * (1.0f / 3.0f + t2 * (1.0f / 5.0f + t2 * (1.0f / 7.0f))));
    return float(e) + ln * float(std::numbers::log2e);
}

// x^p for x >= 0 in single precision, within a few ulp of std::pow, as plain arithmetic and
// selects that vectorise (std::pow is a scalar call). 0^p = 0 for p > 0, 1 for p == 0.
[[gnu::always_inline]] inline float powApprox(float x, float p) {
    const float safe = x > 0.0f ? x : 1.0f;
    const float v = exp2Approx(p * log2Approx(safe));
    return x > 0.0f ? v : (p == 0.0f ? 1.0f : 0.0f);
}

// Section 4 of the paper: colour error exponent qc, re-mapping knee pc (a fraction of the
// largest error cmax) mapped to pt, feature detector width w in degrees; the feature error
// exponent qf = 0.5 is the square root of the feature term.
constexpr float kQc = 0.7f;
constexpr float kPc = 0.4f;
constexpr float kPt = 0.95f;
constexpr double kFeatureWidthDeg = 0.082;

// Contrast sensitivity of each YCxCz channel as the paper's sum of Gaussians in the spatial
// domain, x in degrees: S(x) = a1 sqrt(pi/b1) exp(-pi^2 x^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 x^2/b2).
struct Csf {
    double a1, b1, a2, b2;
};
constexpr Csf kCsfAchromatic{1.0, 0.0047, 0.0, 1e-5};
constexpr Csf kCsfRedGreen{1.0, 0.0053, 0.0, 1e-5};
constexpr Csf kCsfBlueYellow{34.1, 0.04, 13.5, 0.025};

// CIE L*a*b*'s f(t): cube root above (6/29)^3, a line below.
constexpr float kLabDelta = 6.0f / 29.0f;
constexpr float kLabDeltaCube = kLabDelta * kLabDelta * kLabDelta;
constexpr float kLabSlope = 1.0f / (3.0f * kLabDelta * kLabDelta);
constexpr float kLabOffset = 4.0f / 29.0f;

// L*a*b*'s f(t). Both sides computed, then selected: the loops around it stay branch-free
// vector code.
[[gnu::always_inline]] inline float labF(float t) {
    const float root = cubeRoot(t), line = kLabSlope * t + kLabOffset;
    return t > kLabDeltaCube ? root : line;
}

// The largest colour error cmax: HyAB (city-block in lightness, Euclidean in chroma) between
// Hunt-adjusted green and blue, to the power qc.
inline float maxColourError() {
    float lab[2][3];
    const float rgb[2][3] = {{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
    for (int i = 0; i < 2; ++i) {
        float xyz[3];
        for (int j = 0; j < 3; ++j)
            xyz[j] = (kRgbToXyz[j][0] * rgb[i][0] + kRgbToXyz[j][1] * rgb[i][1] + kRgbToXyz[j][2] * rgb[i][2]) *
                     kInvWhite[j];
        const float fx = labF(xyz[0]), fy = labF(xyz[1]), fz = labF(xyz[2]);
        lab[i][0] = 116.0f * fy - 16.0f;
        lab[i][1] = 0.01f * lab[i][0] * (500.0f * (fx - fy));
        lab[i][2] = 0.01f * lab[i][0] * (200.0f * (fy - fz));
    }
    const float hyab = std::abs(lab[0][0] - lab[1][0]) + std::sqrt((lab[0][1] - lab[1][1]) * (lab[0][1] - lab[1][1]) +
                                                                   (lab[0][2] - lab[1][2]) * (lab[0][2] - lab[1][2]));
    return std::pow(hyab, kQc);
}

}  // namespace cbr::metrics::flip_detail
