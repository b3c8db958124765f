// The global-shift fallback of the edge-crawl metric: a whole-frame translation by phase
// correlation, for captured sequences without motion vectors.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "metrics/temporal.h"

namespace cbr::metrics {

namespace {

cv::Mat lumaMat(const Image& image) {
    Image y = luma(image);
    cv::Mat m(y.height, y.width, CV_64F);
    for (int r = 0; r < y.height; ++r)
        for (int c = 0; c < y.width; ++c) m.at<double>(r, c) = y.at(c, r);
    return m;
}

// Bilinear sample with clamping (the refinement stays inside a margin, so clamping is rare).
double sample(const cv::Mat& m, double x, double y) {
    x = std::clamp(x, 0.0, double(m.cols - 1));
    y = std::clamp(y, 0.0, double(m.rows - 1));
    const int x0 = std::min(int(x), m.cols - 2), y0 = std::min(int(y), m.rows - 2);  // images are >= 8x8
    const double fx = x - x0, fy = y - y0;
    const double a = m.at<double>(y0, x0), b = m.at<double>(y0, x0 + 1);
    const double c = m.at<double>(y0 + 1, x0), d = m.at<double>(y0 + 1, x0 + 1);
    return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
}

// Phase correlation's sub-pixel centroid is biased by up to a tenth of a pixel; a few
// Gauss-Newton steps on the blurred luma (Lucas-Kanade for one translation) remove it:
// minimise sum (current(p) - previous(p + m))^2 over the pixels whose source stays inside.
cv::Point2d refine(const cv::Mat& previous, const cv::Mat& current, cv::Point2d m) {
    cv::Mat a, b, gx, gy;
    cv::GaussianBlur(previous, a, cv::Size(0, 0), 1.0, 1.0, cv::BORDER_REFLECT);
    cv::GaussianBlur(current, b, cv::Size(0, 0), 1.0, 1.0, cv::BORDER_REFLECT);
    cv::Sobel(a, gx, CV_64F, 1, 0, 3, 1.0 / 8.0);
    cv::Sobel(a, gy, CV_64F, 0, 1, 3, 1.0 / 8.0);
    const int margin = 3;
    for (int iteration = 0; iteration < 8; ++iteration) {
        double hxx = 0, hxy = 0, hyy = 0, bx = 0, by = 0;
        for (int y = margin; y < b.rows - margin; ++y)
            for (int x = margin; x < b.cols - margin; ++x) {
                const double sx = x + m.x, sy = y + m.y;
                if (sx < margin || sy < margin || sx > a.cols - 1 - margin || sy > a.rows - 1 - margin) continue;
                const double r = b.at<double>(y, x) - sample(a, sx, sy);
                const double jx = sample(gx, sx, sy), jy = sample(gy, sx, sy);
                hxx += jx * jx, hxy += jx * jy, hyy += jy * jy;
                bx += jx * r, by += jy * r;
            }
        const double det = hxx * hyy - hxy * hxy;
        if (!(det > 1e-12 * (hxx + hyy) * (hxx + hyy)) || !std::isfinite(det)) break;
        const double ux = (hyy * bx - hxy * by) / det, uy = (hxx * by - hxy * bx) / det;
        if (!std::isfinite(ux) || !std::isfinite(uy) || std::abs(ux) > 1 || std::abs(uy) > 1) break;
        m.x += ux, m.y += uy;
        if (std::abs(ux) < 1e-4 && std::abs(uy) < 1e-4) break;
    }
    return m;
}

// Whether current(p) = previous(p + m) explains the reference's change better than no motion:
// the mean squared differences of both, on the blurred luma, over the same interior pixels
// (those whose source under m lies inside), at least a quarter of the frame.
bool explainsBetterThanNoMotion(const cv::Mat& a, const cv::Mat& b, cv::Point2d m) {
    const int margin = 3;
    double moved = 0, still = 0;
    size_t n = 0;
    for (int y = margin; y < b.rows - margin; ++y)
        for (int x = margin; x < b.cols - margin; ++x) {
            const double sx = x + m.x, sy = y + m.y;
            if (sx < margin || sy < margin || sx > a.cols - 1 - margin || sy > a.rows - 1 - margin) continue;
            const double r = b.at<double>(y, x) - sample(a, sx, sy), r0 = b.at<double>(y, x) - a.at<double>(y, x);
            moved += r * r;
            still += r0 * r0;
            ++n;
        }
    return n * 4 >= size_t(b.rows) * size_t(b.cols) && moved < still;
}

}  // namespace

GlobalShift estimateGlobalShift(const Image& previous, const Image& current) {
    if (previous.width != current.width || previous.height != current.height)
        throw std::invalid_argument("global shift: frames of " + std::to_string(previous.width) + "x" +
                                    std::to_string(previous.height) + " and " + std::to_string(current.width) + "x" +
                                    std::to_string(current.height) + "; accepted: equal sizes");
    if (current.width < 8 || current.height < 8)
        throw std::invalid_argument("global shift: frames smaller than 8x8");
    cv::Mat a = lumaMat(previous), b = lumaMat(current);
    cv::Mat window;
    cv::createHanningWindow(window, a.size(), CV_64F);
    double response = 0;
    // phaseCorrelate(a, b) is the shift d with b(p) = a(p - d): the surface at p in b was
    // at p - d in a.
    // (On copies: OpenCV 4.6 multiplies its inputs by the window in place.)
    const cv::Point2d d = cv::phaseCorrelate(a.clone(), b.clone(), window, &response);
    GlobalShift s;
    if (std::isfinite(d.x) && std::isfinite(d.y)) {
        const cv::Point2d m = refine(a, b, {-d.x, -d.y});
        // Kept only where it explains the reference's change better than no motion at all
        // (zoom, parallax or a cut give a peak somewhere, but not a useful one).
        cv::Mat ba, bb;
        cv::GaussianBlur(a, ba, cv::Size(0, 0), 1.0, 1.0, cv::BORDER_REFLECT);
        cv::GaussianBlur(b, bb, cv::Size(0, 0), 1.0, 1.0, cv::BORDER_REFLECT);
        if (explainsBetterThanNoMotion(ba, bb, m)) {
            s.dx = m.x;
            s.dy = m.y;
        } else {
            s.rejected = true;
        }
    }
    s.response = std::isfinite(response) ? std::clamp(response, 0.0, 1.0) : 0.0;
    // A flat frame has no peak: report no motion and no confidence rather than noise.
    if (!std::isfinite(d.x) || !std::isfinite(d.y)) s.response = 0.0;
    return s;
}

MotionField uniformMotion(int width, int height, double dx, double dy) {
    MotionField m;
    m.width = width;
    m.height = height;
    const size_t n = size_t(width) * size_t(height);
    m.motion.resize(n * 2);
    for (size_t i = 0; i < n; ++i) {
        m.motion[2 * i] = float(dx);
        m.motion[2 * i + 1] = float(dy);
    }
    m.depth.assign(n, 1.0f);
    m.prev_depth_expected.assign(n, 1.0f);
    return m;
}

}  // namespace cbr::metrics
