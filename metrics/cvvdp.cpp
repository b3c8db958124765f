// ColorVideoVDP on the CPU, one frame at a time (docs/method/cvvdp.md): temporal channels from
// a window of frames, a Laplacian pyramid of each, contrast against the local background, the CSF,
// masking between channels, and pooling to one figure per frame.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <opencv2/core/utility.hpp>

#include "metrics/cvvdp.h"

namespace cbr::metrics {
namespace {

constexpr float kEps = 1e-5f;  // the model's power function: (x + eps)^p - eps^p
constexpr float kBandK[5] = {0.05f, 0.25f, 0.4f, 0.25f, 0.05f};  // the pyramid's kernel (a = 0.4)

float safePowF(float x, float p) { return std::pow(x + kEps, p) - std::pow(kEps, p); }

struct Plane {
    int w = 0, h = 0;
    std::vector<float> v;
    Plane() = default;
    Plane(int w_, int h_) : w(w_), h(h_), v(size_t(w_) * size_t(h_)) {}
    float* row(int y) { return v.data() + size_t(y) * size_t(w); }
    const float* row(int y) const { return v.data() + size_t(y) * size_t(w); }
};

template <class F>
void rows(int n, const F& f) {
    cv::parallel_for_(cv::Range(0, n), [&](const cv::Range& r) {
        for (int y = r.start; y < r.end; ++y) f(y);
    });
}

// One level down the Gaussian pyramid: 5 taps, stride 2, edges folded back as the reference does
// (its horizontal pass takes the fold from the number of rows: docs/method/cvvdp.md).
Plane reduce(const Plane& x) {
    const int hh = (x.h + 1) / 2, ww = (x.w + 1) / 2;
    Plane a(x.w, hh), y(ww, hh);
    const bool odd_rows = x.h % 2 == 1;
    rows(hh, [&](int r) {
        float* out = a.row(r);
        std::fill(out, out + x.w, 0.f);
        for (int k = 0; k < 5; ++k) {
            const int src = 2 * r + k - 2;
            if (src < 0 || src >= x.h) continue;
            const float* in = x.row(src);
            for (int c = 0; c < x.w; ++c) out[c] += kBandK[k] * in[c];
        }
        auto add = [&](int src, float k) {
            const float* in = x.row(src);
            for (int c = 0; c < x.w; ++c) out[c] += in[c] * k;
        };
        if (r == 0) add(0, kBandK[1]), add(std::min(1, x.h - 1), kBandK[0]);
        if (r == hh - 1) {
            if (odd_rows)
                add(x.h - 1, kBandK[3]), add(std::max(x.h - 2, 0), kBandK[4]);
            else
                add(x.h - 1, kBandK[4]);
        }
    });
    rows(hh, [&](int r) {
        const float* in = a.row(r);
        float* out = y.row(r);
        for (int c = 0; c < ww; ++c) {
            float s = 0;
            for (int k = 0; k < 5; ++k) {
                const int src = 2 * c + k - 2;
                if (src >= 0 && src < x.w) s += kBandK[k] * in[src];
            }
            out[c] = s;
        }
        out[0] += in[0] * kBandK[1] + in[std::min(1, x.w - 1)] * kBandK[0];
        if (odd_rows)
            out[ww - 1] += in[x.w - 1] * kBandK[3] + in[std::max(x.w - 2, 0)] * kBandK[4];
        else
            out[ww - 1] += in[x.w - 1] * kBandK[4];
    });
    return y;
}

// The padded, zero-interleaved line the expansion filters: slot j of n + 4 holds x[(j - 2) / 2]
// at even j in [2, n + 2), x[0] at 0 and the last sample at n + 2 + (n odd).
template <class Get>
float expandTap(int j, int n, int len, const Get& get) {
    if (j == 0) return get(0);
    if (j >= 2 && j < n + 2) return (j % 2 == 0) ? get((j - 2) / 2) : 0.f;
    if (j == n + 2 + (n % 2)) return get(len - 1);
    return 0.f;
}

// One level up: x (about half of w x h) to w x h, kernel doubled.
Plane expand(const Plane& x, int w, int h) {
    Plane a(x.w, h), y(w, h);
    rows(h, [&](int r) {
        float* out = a.row(r);
        std::fill(out, out + x.w, 0.f);
        for (int k = 0; k < 5; ++k) {
            const int j = r + k;
            int src = -1;
            if (j == 0)
                src = 0;
            else if (j >= 2 && j < h + 2 && j % 2 == 0)
                src = (j - 2) / 2;
            else if (j == h + 2 + (h % 2))
                src = x.h - 1;
            if (src < 0) continue;
            const float* in = x.row(src);
            for (int c = 0; c < x.w; ++c) out[c] += 2 * kBandK[k] * in[c];
        }
    });
    rows(h, [&](int r) {
        const float* in = a.row(r);
        float* out = y.row(r);
        auto get = [&](int i) { return in[i]; };
        for (int c = 0; c < w; ++c) {
            float s = 0;
            for (int k = 0; k < 5; ++k) s += 2 * kBandK[k] * expandTap(c + k, w, x.w, get);
            out[c] = s;
        }
    });
    return y;
}

int reflect(int i, int n) { return i < 0 ? -i : (i >= n ? 2 * (n - 1) - i : i); }

// The phase-uncertainty blur: 13-tap Gaussian, edges mirrored (without repeating the edge).
void blur13(Plane& p, const float* k) {
    Plane t(p.w, p.h);
    rows(p.h, [&](int r) {
        float* out = t.row(r);
        std::fill(out, out + p.w, 0.f);
        for (int i = 0; i < 13; ++i) {
            const float* in = p.row(reflect(r + i - 6, p.h));
            for (int c = 0; c < p.w; ++c) out[c] += k[i] * in[c];
        }
    });
    rows(p.h, [&](int r) {
        const float* in = t.row(r);
        float* out = p.row(r);
        for (int c = 0; c < p.w; ++c) {
            float s = 0;
            for (int i = 0; i < 13; ++i) s += k[i] * in[reflect(c + i - 6, p.w)];
            out[c] = s;
        }
    });
}

float sensitivity(const CvvdpModel& m, int band, int channel, float log_l) {
    const auto& s = m.csf_log_s[size_t(band)][size_t(channel)];
    const float ind = std::clamp((log_l - m.csf_log_l0) / (m.csf_log_l1 - m.csf_log_l0) * 31.f, 0.f, 31.f);
    const int i0 = int(ind);
    const int i1 = std::min(i0 + 1, 31);
    const float f = ind - float(i0);
    return std::pow(10.f, s[size_t(i0)] * (1 - f) + s[size_t(i1)] * f) * cvvdpParams().sensitivity_gain;
}

double meanClamped(const Plane& p) {
    double s = 0;
    for (float v : p.v) s += std::max(v, 0.01f);
    return s / double(p.v.size());
}

}  // namespace

struct CvvdpTracker::State {
    CvvdpModel m;
    std::vector<std::vector<uint8_t>> ref_ring, test_ring;  // RGB, oldest at `head + 1`
    int head = -1;
    bool started = false;

    // planes[c * 2 + 0]: test, [c * 2 + 1]: reference, for channel c (Y sustained, RG, YV, Y transient).
    std::vector<Plane> channels() const;
    // The band's per-channel differences (D), and their per-pixel pooled map on request.
    std::array<double, 4> band(const std::vector<std::vector<Plane>>& g, int b, Plane* map) const;
};

std::vector<Plane> CvvdpTracker::State::channels() const {
    const int w = m.width, h = m.height, nch = m.channels;
    std::vector<Plane> out(size_t(nch) * 2, Plane(w, h));
    const int n = m.image ? 1 : m.filterFrames();
    rows(h, [&](int y) {
        for (int x = 0; x < w; ++x) {
            const size_t px = size_t(y) * size_t(w) + size_t(x);
            float acc[2][4] = {};
            for (int j = 0; j < n; ++j) {
                const size_t slot = size_t((head + 1 + j) % n);
                const uint8_t* src[2] = {test_ring[slot].data() + px * 3, ref_ring[slot].data() + px * 3};
                for (int s = 0; s < 2; ++s) {
                    const float r = m.lum_lut[src[s][0]], g = m.lum_lut[src[s][1]], bl = m.lum_lut[src[s][2]];
                    float dkl[3];
                    for (int i = 0; i < 3; ++i) dkl[i] = m.rgb_to_dkl[i][0] * r + m.rgb_to_dkl[i][1] * g + m.rgb_to_dkl[i][2] * bl;
                    if (m.image) {
                        for (int i = 0; i < 3; ++i) acc[s][i] = dkl[i];
                    } else {
                        const auto& t = m.taps[size_t(j)];
                        acc[s][0] += t[0] * dkl[0];
                        acc[s][1] += t[1] * dkl[1];
                        acc[s][2] += t[2] * dkl[2];
                        acc[s][3] += t[3] * dkl[0];
                    }
                }
            }
            for (int c = 0; c < nch; ++c) {
                out[size_t(c) * 2].v[px] = acc[0][c];
                out[size_t(c) * 2 + 1].v[px] = acc[1][c];
            }
        }
    });
    return out;
}

std::array<double, 4> CvvdpTracker::State::band(const std::vector<std::vector<Plane>>& g, int b, Plane* map) const {
    const CvvdpParams& p = cvvdpParams();
    const int nch = m.channels;
    const bool baseband = b == m.bands - 1;
    const int w = m.band_size[size_t(b)][0], h = m.band_size[size_t(b)][1];
    const size_t n = size_t(w) * size_t(h);
    const float t_int = m.image ? p.image_int : 1.f;
    std::array<double, 4> q{};
    std::vector<Plane> diff(size_t(nch), Plane(w, h));
    if (baseband) {
        const float lt = float(meanClamped(g[0][size_t(b)])), lr = float(meanClamped(g[1][size_t(b)]));
        const float log_l = std::log10(lr);
        for (int c = 0; c < nch; ++c) {
            const float s = sensitivity(m, b, c, log_l);
            const auto& tp = g[size_t(c) * 2][size_t(b)].v;
            const auto& rp = g[size_t(c) * 2 + 1][size_t(b)].v;
            for (size_t i = 0; i < n; ++i)
                diff[size_t(c)].v[i] = std::abs(std::min(tp[i] / lt, 1000.f) - std::min(rp[i] / lr, 1000.f)) * s;
        }
    } else {
        const float mul = b == 0 ? 1.f : 2.f;
        std::vector<Plane> ex;
        for (size_t pl = 0; pl < size_t(nch) * 2; ++pl) ex.push_back(expand(g[pl][size_t(b) + 1], w, h));
        std::vector<Plane> mask(size_t(nch), Plane(w, h));
        rows(h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                const float lt = std::max(ex[0].v[i], 0.01f), lr = std::max(ex[1].v[i], 0.01f);
                const float log_l = std::log10(lr);
                for (int c = 0; c < nch; ++c) {
                    const size_t pt = size_t(c) * 2, pr = pt + 1;
                    const float t = std::min((g[pt][size_t(b)].v[i] - ex[pt].v[i]) / lt, 1000.f) * mul;
                    const float r = std::min((g[pr][size_t(b)].v[i] - ex[pr].v[i]) / lr, 1000.f) * mul;
                    const float gain = sensitivity(m, b, c, log_l) * p.ch_gain[c];
                    const float tp = t * gain, rp = r * gain;
                    diff[size_t(c)].v[i] = std::abs(tp - rp);
                    mask[size_t(c)].v[i] = std::min(std::abs(tp), std::abs(rp));
                }
            }
        });
        for (int c = 0; c < nch; ++c) {
            if (w > 6 && h > 6) blur13(mask[size_t(c)], p.pu_kernel);
            for (float& v : mask[size_t(c)].v) v = safePowF(std::abs(v * p.mask_c_gain), p.mask_q[c]);
        }
        rows(h, [&](int y) {
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * size_t(w) + size_t(x);
                float pm[4] = {};
                for (int k = 0; k < nch; ++k) pm[k] = mask[size_t(k)].v[i];
                for (int c = 0; c < nch; ++c) {
                    float mc = 0;
                    for (int k = 0; k < nch; ++k) mc += pm[k] * p.xcm[k][c];
                    const float du = safePowF(diff[size_t(c)].v[i], p.mask_p) / (1 + mc);
                    diff[size_t(c)].v[i] = p.d_max_gain * du / (p.d_max_gain + du);
                }
            }
        });
    }
    for (int c = 0; c < nch; ++c) {
        std::vector<double> row_sum(static_cast<size_t>(h));
        rows(h, [&](int y) {
            double s = 0;
            const float* d = diff[size_t(c)].row(y);
            for (int x = 0; x < w; ++x) s += double(safePowF(d[x], p.beta));
            row_sum[size_t(y)] = s;
        });
        double s = 0;
        for (double v : row_sum) s += v;
        q[size_t(c)] = double(safePowF(float(s / double(n)), 1 / p.beta));
    }
    if (map) {
        *map = Plane(w, h);
        const float mul = (b == 0 || baseband) ? 1.f : 2.f;
        for (size_t i = 0; i < n; ++i) {
            float s = 0;
            for (int c = 0; c < nch; ++c) {
                float wc = p.ch_weight[c] * t_int * (baseband ? p.baseband_weight[c] : 1.f);
                s += safePowF(diff[size_t(c)].v[i] * wc, p.beta_tch);
            }
            map->v[i] = safePowF(s, 1 / p.beta_tch) / mul;
        }
    }
    return q;
}

CvvdpTracker::CvvdpTracker(int width, int height, const DisplayModel& display, double fps)
    : s_(std::make_unique<State>()) {
    s_->m = makeCvvdpModel(width, height, display, fps);
    const size_t n = size_t(s_->m.image ? 1 : s_->m.filterFrames());
    s_->ref_ring.assign(n, std::vector<uint8_t>(size_t(width) * size_t(height) * 3));
    s_->test_ring.assign(n, std::vector<uint8_t>(size_t(width) * size_t(height) * 3));
}

CvvdpTracker::~CvvdpTracker() = default;

const CvvdpModel& CvvdpTracker::model() const { return s_->m; }

size_t CvvdpTracker::stateBytes() const { return 2 * s_->ref_ring.size() * s_->ref_ring[0].size(); }

CvvdpFrame CvvdpTracker::addRgba8(const uint8_t* reference, const uint8_t* test, bool want_map) {
    if (!reference || !test) throw std::invalid_argument("CvvdpTracker::addRgba8: null image");
    State& s = *s_;
    const CvvdpModel& m = s.m;
    const size_t px = size_t(m.width) * size_t(m.height);
    const int n = int(s.ref_ring.size());
    auto pack = [&](const uint8_t* rgba, std::vector<uint8_t>& rgb) {
        for (size_t i = 0; i < px; ++i) std::memcpy(rgb.data() + i * 3, rgba + i * 4, 3);
    };
    s.head = (s.head + 1) % n;
    pack(reference, s.ref_ring[size_t(s.head)]);
    pack(test, s.test_ring[size_t(s.head)]);
    if (!s.started) {  // the window before the first frame repeats it
        for (int j = 0; j < n; ++j) {
            s.ref_ring[size_t(j)] = s.ref_ring[size_t(s.head)];
            s.test_ring[size_t(j)] = s.test_ring[size_t(s.head)];
        }
        s.started = true;
    }
    // Gaussian pyramid of every channel plane.
    std::vector<Plane> ch = s.channels();
    std::vector<std::vector<Plane>> g(ch.size());
    for (size_t pl = 0; pl < ch.size(); ++pl) {
        g[pl].push_back(std::move(ch[pl]));
        for (int b = 1; b < m.bands; ++b) g[pl].push_back(reduce(g[pl].back()));
    }
    const CvvdpParams& p = cvvdpParams();
    std::vector<Plane> maps(want_map ? size_t(m.bands) : 0);
    std::array<double, 4> sch{};  // per channel, pooled over bands
    for (int b = 0; b < m.bands; ++b) {
        const auto q = s.band(g, b, want_map ? &maps[size_t(b)] : nullptr);
        for (int c = 0; c < m.channels; ++c) {
            const float x = float(q[size_t(c)]) * p.ch_weight[c] * (b == m.bands - 1 ? p.baseband_weight[c] : 1.f);
            sch[size_t(c)] += double(safePowF(x, p.beta_sch));
        }
    }
    float tc = 0;
    for (int c = 0; c < m.channels; ++c) tc += safePowF(safePowF(float(sch[size_t(c)]), 1 / p.beta_sch), p.beta_tch);
    CvvdpFrame f;
    f.q = double(safePowF(tc, 1 / p.beta_tch));
    f.jod = cvvdpJod(m.image ? cvvdpImageQ(f.q) : f.q);
    if (want_map) {
        Plane img = std::move(maps.back());
        for (int b = m.bands - 2; b >= 0; --b) {
            Plane up = expand(img, maps[size_t(b)].w, maps[size_t(b)].h);
            for (size_t i = 0; i < up.v.size(); ++i) up.v[i] += maps[size_t(b)].v[i];
            img = std::move(up);
        }
        Image out;
        out.width = m.width;
        out.height = m.height;
        out.channels = 1;
        out.data.resize(img.v.size());
        for (size_t i = 0; i < img.v.size(); ++i) out.data[i] = 1 - cvvdpJod(double(img.v[i])) / 10;
        f.map = std::move(out);
    }
    return f;
}

}  // namespace cbr::metrics
