// ColorVideoVDP on the CPU, one frame at a time (docs/method/cvvdp.md): temporal channels from
// a window of frames, a Laplacian pyramid of each, contrast against the local background, the CSF,
// masking between channels, and pooling to one figure per frame.
//
// Speed: the per-pixel work runs row by row in functions cloned for AVX2 (simd.h; these files are
// built without FMA contraction, so both clones perform the same IEEE operations), the
// expansion of the coarser level is made one row at a time where it is used, and the powers
// (10^x of the CSF, the masking and pooling exponents) use exp2/log2 (cvvdp_kernels.h), within 5e-7
// (relative, about 4 float ulps) of the exact power; the JOD figures move by under 1e-6. Reductions keep one double per row, added in row order, so figures do
// not depend on the number of threads.
//
// The pyramid and the per-row kernels live in metrics/cvvdp_pyramid.cpp (metrics/cvvdp_kernels.h).
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "metrics/cvvdp.h"
#include "metrics/cvvdp_kernels.h"

namespace cbr::metrics {

using namespace cvvdp_detail;

namespace {

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
    const size_t n = p.size();
    for (size_t i = 0; i < n; ++i) s += std::max(p.v[i], 0.01f);
    return s / double(n);
}

// The figures of band b (not the baseband), w x h, for contrastRow and maskRow.
BandConsts bandConsts(const CvvdpModel& m, int b, int w, int h) {
    const CvvdpParams& p = cvvdpParams();
    const int nch = m.channels;
    BandConsts k;
    k.nch = nch;
    k.mul = b == 0 ? 1.f : 2.f;
    for (int c = 0; c < nch; ++c) {
        k.csf[c] = m.csf_log_s[size_t(b)][size_t(c)].data();
        k.ch_gain[c] = p.ch_gain[c];
        k.mask_pow[c] = SafePow(p.mask_q[c]);
        for (int j = 0; j < 4; ++j) k.xcm[c][j] = p.xcm[c][j];
    }
    k.l0 = m.csf_log_l0;
    k.l_range = m.csf_log_l1 - m.csf_log_l0;
    k.sens_gain = p.sensitivity_gain;
    k.mask_c_gain = p.mask_c_gain;
    k.d_pow = SafePow(p.mask_p);
    k.beta_pow = SafePow(p.beta);
    k.d_max = p.d_max_gain;
    k.pu = p.pu_kernel;
    k.blur = w > 6 && h > 6;
    return k;
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
    // The baseband's differences (diff, one plane per channel) and their powers summed per row
    // (row_sum[y * 4 + c]).
    void baseband(const std::vector<std::vector<Plane>>& g, int b, std::vector<Plane>& diff,
                  std::vector<double>& row_sum) const;
    // The same for band b, not the baseband: contrast against the coarser level expanded a row at
    // a time, then masking and pooling; the saturated differences are left in diff when keep.
    void regularBand(const std::vector<std::vector<Plane>>& g, int b, std::vector<Plane>& diff,
                     std::vector<double>& row_sum, bool keep) const;
    // Band b's per-pixel map: its saturated differences pooled over channels.
    Plane bandMap(const std::vector<Plane>& diff, int b) const;
};

std::vector<Plane> CvvdpTracker::State::channels() const {
    const int w = m.width, h = m.height, nch = m.channels;
    std::vector<Plane> out;
    for (int i = 0; i < nch * 2; ++i) out.emplace_back(w, h);
    const int n = m.image ? 1 : m.filterFrames();
    rowRanges(h, [&](int y0, int y1) {
        std::vector<const uint8_t*> test(static_cast<size_t>(n)), ref(static_cast<size_t>(n));
        std::vector<float> lum(size_t(w) * 3);
        float* rows[8] = {};
        for (int y = y0; y < y1; ++y) {
            const size_t off = size_t(y) * size_t(w) * 3;
            for (int j = 0; j < n; ++j) {
                const size_t slot = size_t((head + 1 + j) % n);
                test[size_t(j)] = test_ring[slot].data() + off;
                ref[size_t(j)] = ref_ring[slot].data() + off;
            }
            for (int i = 0; i < nch * 2; ++i) rows[i] = out[size_t(i)].row(y);
            channelsRow(m, test.data(), ref.data(), n, w, rows, lum.data());
        }
    });
    return out;
}

std::array<double, 4> CvvdpTracker::State::band(const std::vector<std::vector<Plane>>& g, int b, Plane* map) const {
    const CvvdpParams& p = cvvdpParams();
    const int nch = m.channels;
    const int w = m.band_size[size_t(b)][0], h = m.band_size[size_t(b)][1];
    const size_t n = size_t(w) * size_t(h);
    std::array<double, 4> q{};
    std::vector<Plane> diff;
    for (int c = 0; c < nch; ++c) diff.emplace_back(w, h);
    std::vector<double> row_sum(size_t(h) * 4);  // [y][c]
    if (b == m.bands - 1)
        baseband(g, b, diff, row_sum);
    else
        regularBand(g, b, diff, row_sum, map != nullptr);
    for (int c = 0; c < nch; ++c) {
        double s = 0;
        for (int y = 0; y < h; ++y) s += row_sum[size_t(y) * 4 + size_t(c)];
        q[size_t(c)] = double(safePowF(float(s / double(n)), 1 / p.beta));
    }
    if (map) *map = bandMap(diff, b);
    return q;
}

void CvvdpTracker::State::baseband(const std::vector<std::vector<Plane>>& g, int b, std::vector<Plane>& diff,
                                   std::vector<double>& row_sum) const {
    const CvvdpParams& p = cvvdpParams();
    const int nch = m.channels;
    const int w = m.band_size[size_t(b)][0], h = m.band_size[size_t(b)][1];
    const size_t n = size_t(w) * size_t(h);
    const float lt = float(meanClamped(g[0][size_t(b)])), lr = float(meanClamped(g[1][size_t(b)]));
    const float log_l = std::log10(lr);
    for (int c = 0; c < nch; ++c) {
        const float s = sensitivity(m, b, c, log_l);
        const float* tp = g[size_t(c) * 2][size_t(b)].v.get();
        const float* rp = g[size_t(c) * 2 + 1][size_t(b)].v.get();
        float* d = diff[size_t(c)].v.get();
        for (size_t i = 0; i < n; ++i) d[i] = std::abs(std::min(tp[i] / lt, 1000.f) - std::min(rp[i] / lr, 1000.f)) * s;
    }
    const SafePow bp(p.beta);
    for (int y = 0; y < h; ++y)
        for (int c = 0; c < nch; ++c) {
            double s = 0;
            const float* d = diff[size_t(c)].row(y);
            for (int x = 0; x < w; ++x) s += double(bp(d[x]));
            row_sum[size_t(y) * 4 + size_t(c)] = s;
        }
}

void CvvdpTracker::State::regularBand(const std::vector<std::vector<Plane>>& g, int b, std::vector<Plane>& diff,
                                      std::vector<double>& row_sum, bool keep) const {
    const int nch = m.channels;
    const int w = m.band_size[size_t(b)][0], h = m.band_size[size_t(b)][1];
    const BandConsts k = bandConsts(m, b, w, h);
    std::vector<Plane> mask;
    for (int c = 0; c < nch; ++c) mask.emplace_back(w, h);
    // Contrast, the coarser level expanded a row at a time.
    rowRanges(h, [&](int y0, int y1) {
        const int npl = 2 * nch;
        const Plane& coarse0 = g[0][size_t(b) + 1];
        std::vector<float> buf(size_t(coarse0.w) + size_t(npl) * size_t(w));
        std::vector<int> idx(static_cast<size_t>(w));
        std::vector<float> frac(static_cast<size_t>(w));
        const float* grow[8];
        const float* exrow[8];
        float* drow[4];
        float* mrow[4];
        for (int y = y0; y < y1; ++y) {
            for (int pl = 0; pl < npl; ++pl) {
                float* e = buf.data() + coarse0.w + size_t(pl) * size_t(w);
                expandRow(g[size_t(pl)][size_t(b) + 1], w, h, y, buf.data(), e);
                exrow[pl] = e;
                grow[pl] = g[size_t(pl)][size_t(b)].row(y);
            }
            for (int c = 0; c < nch; ++c) {
                drow[c] = diff[size_t(c)].row(y);
                mrow[c] = mask[size_t(c)].row(y);
            }
            contrastRow(k, w, grow, exrow, drow, mrow, idx.data(), frac.data());
        }
    });
    // Masking and pooling (the saturated differences kept only for a map).
    rowRanges(h, [&](int y0, int y1) {
        std::vector<float> scratch(size_t(w) + 12 + 5 * size_t(w));
        const float* drow[4];
        float* orow[4];
        for (int y = y0; y < y1; ++y) {
            for (int c = 0; c < nch; ++c) {
                drow[c] = diff[size_t(c)].row(y);
                orow[c] = diff[size_t(c)].row(y);  // row y only: in place is safe
            }
            maskRow(k, w, h, y, mask.data(), drow, keep ? orow : nullptr, scratch.data(), &row_sum[size_t(y) * 4]);
        }
    });
}

Plane CvvdpTracker::State::bandMap(const std::vector<Plane>& diff, int b) const {
    const CvvdpParams& p = cvvdpParams();
    const int nch = m.channels;
    const bool baseband = b == m.bands - 1;
    const int w = m.band_size[size_t(b)][0], h = m.band_size[size_t(b)][1];
    const float t_int = m.image ? p.image_int : 1.f;
    Plane map(w, h);
    const float mul = (b == 0 || baseband) ? 1.f : 2.f;
    float wc[4];
    for (int c = 0; c < nch; ++c) wc[c] = p.ch_weight[c] * t_int * (baseband ? p.baseband_weight[c] : 1.f);
    const float inv_beta_tch = 1 / p.beta_tch;
    rowRanges(h, [&](int y0, int y1) {
        for (size_t i = size_t(y0) * size_t(w); i < size_t(y1) * size_t(w); ++i) {
            float s = 0;
            for (int c = 0; c < nch; ++c) s += safePowF(diff[size_t(c)].v[i] * wc[c], p.beta_tch);
            map.v[i] = safePowF(s, inv_beta_tch) / mul;
        }
    });
    return map;
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
        uint8_t* __restrict o = rgb.data();
        for (size_t i = 0; i < px; ++i) {
            o[i * 3] = rgba[i * 4];
            o[i * 3 + 1] = rgba[i * 4 + 1];
            o[i * 3 + 2] = rgba[i * 4 + 2];
        }
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
            const size_t nb = up.size();
            for (size_t i = 0; i < nb; ++i) up.v[i] += maps[size_t(b)].v[i];
            img = std::move(up);
        }
        Image out;
        out.width = m.width;
        out.height = m.height;
        out.channels = 1;
        out.data.resize(img.size());
        for (size_t i = 0; i < img.size(); ++i) out.data[i] = 1 - cvvdpJod(double(img.v[i])) / 10;
        f.map = std::move(out);
    }
    return f;
}

}  // namespace cbr::metrics
