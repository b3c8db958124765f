// Quality scoring on worker threads: PSNR/SSIM/FLIP per frame, ECI in order, worst frames.
#include "harness/quality.h"

#include <algorithm>
#include <cmath>

#include "metrics/flip.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"

namespace cbr::harness {

// The worst frame of one kind (by SSIM or by ECI) of one variant, kept until the end.
struct QualityScorer::Worst {
    int frame = -1;
    double value = 0;  // SSIM (lower is worse) or ECI (higher is worse)
    Bytes reference, image, classes;
    std::optional<metrics::Image> crawl_map;
};

// Frames of one variant arrive out of order; the crawl metric needs them in order.
struct QualityScorer::Chain {
    std::mutex mutex;
    int next = 0;
    std::map<int, std::pair<FrameRow*, QualityFrame>> pending;
    metrics::CrawlTracker tracker;
    Worst worst_ssim, worst_eci;
};

QualityScorer::QualityScorer(int width, int height, size_t frames, double flip_ppd, WorkerPool& workers)
    : width_(width), height_(height), flip_ppd_(flip_ppd), workers_(workers), reference_(frames) {}

QualityScorer::~QualityScorer() { workers_.wait(); }

void QualityScorer::setReference(size_t frame, Bytes rgba) {
    std::lock_guard lock(mutex_);
    reference_.at(frame) = std::move(rgba);
}

bool QualityScorer::hasReference(size_t frame) const {
    std::lock_guard lock(mutex_);
    return frame < reference_.size() && reference_[frame] != nullptr;
}

QualityScorer::Chain& QualityScorer::chain(const std::string& variant) {
    std::lock_guard lock(mutex_);
    auto& c = chains_[variant];
    if (!c) c = std::make_unique<Chain>();
    return *c;
}

void QualityScorer::score(const std::string& variant, bool is_reference, FrameRow& row, QualityFrame frame) {
    if (is_reference) {
        // The reference against itself: identical by definition.
        row.quality.mse = 0.0;
        row.quality.psnr_db = metrics::psnrFromMse(0.0);
        row.quality.ssim = 1.0;
        row.quality.ssim_luma = 1.0;
        row.quality.eci = 0.0;
        row.quality.flicker_ratio = 1.0;
        row.quality.flip_mean = row.quality.flip_q1 = row.quality.flip_median = row.quality.flip_q3 = 0.0;
        return;
    }
    Bytes ref;
    {
        std::lock_guard lock(mutex_);
        ref = reference_.at(size_t(frame.index));
    }
    if (!ref) {
        row.quality.note += "no reference frame (the reference failed); ";
        return;
    }
    Chain& c = chain(variant);
    int w = width_, h = height_;
    workers_.submit([this, &c, &row, ref, frame, variant, w, h] {
        try {
            auto a = metrics::fromRgba8(ref->data(), w, h, size_t(w) * 4);
            auto b = metrics::fromRgba8(frame.rgba->data(), w, h, size_t(w) * 4);
            double mse = metrics::mse(a, b);
            auto s = metrics::ssim(a, b);
            row.quality.mse = mse;
            row.quality.psnr_db = metrics::psnrFromMse(mse);
            if (std::isfinite(s.ssim)) row.quality.ssim = s.ssim;
            else row.quality.note += "ssim not finite; ";
            if (std::isfinite(s.luma_ssim)) row.quality.ssim_luma = s.luma_ssim;
            const metrics::FlipResult f = metrics::flip(a, b, flip_ppd_);
            row.quality.flip_mean = f.mean;
            row.quality.flip_q1 = f.q1;
            row.quality.flip_median = f.median;
            row.quality.flip_q3 = f.q3;
            std::lock_guard lock(c.mutex);
            if (row.quality.ssim && (c.worst_ssim.frame < 0 || *row.quality.ssim < c.worst_ssim.value))
                c.worst_ssim = {frame.index, *row.quality.ssim, ref, frame.rgba, frame.classes, std::nullopt};
        } catch (const std::exception& e) {
            row.quality.note += std::string("metrics failed: ") + e.what() + "; ";
        }
        // Edge crawl needs frame t-1 of the same variant: run the chain in order.
        std::lock_guard lock(c.mutex);
        c.pending.emplace(frame.index, std::make_pair(&row, frame));
        for (auto it = c.pending.find(c.next); it != c.pending.end(); it = c.pending.find(c.next)) {
            crawlStep(variant, *it->second.first, it->second.second);
            if (release_references_) {
                std::lock_guard reference_lock(mutex_);
                reference_.at(size_t(c.next)).reset();
            }
            c.pending.erase(it);
            ++c.next;
        }
    });
}

// Called with the chain's mutex held, in frame order.
void QualityScorer::crawlStep(const std::string& variant, FrameRow& row, const QualityFrame& frame) {
    Chain& c = *chains_.at(variant);
    if (!frame.analysis) {
        row.quality.note += "no motion analysis: no edge crawl; ";
        c.tracker.reset();
        return;
    }
    try {
        Bytes ref;
        {
            std::lock_guard lock(mutex_);
            ref = reference_.at(size_t(frame.index));
        }
        int w = width_, h = height_;
        metrics::MotionField motion;
        motion.width = w;
        motion.height = h;
        size_t n = size_t(w) * size_t(h);
        motion.motion.resize(n * 2);
        motion.depth.resize(n);
        motion.prev_depth_expected.resize(n);
        const float* a = frame.analysis->data();
        for (size_t i = 0; i < n; ++i) {
            motion.motion[2 * i] = a[4 * i];
            motion.motion[2 * i + 1] = a[4 * i + 1];
            motion.depth[i] = a[4 * i + 2];
            motion.prev_depth_expected[i] = a[4 * i + 3];
        }
        auto r = metrics::fromRgba8(ref->data(), w, h, size_t(w) * 4);
        auto v = metrics::fromRgba8(frame.rgba->data(), w, h, size_t(w) * 4);
        metrics::CrawlFrame cf = c.tracker.add(r, v, motion, frame.cut, true);
        if (!cf.has_pair) return;  // first frame or after a cut: no pair to compare
        row.quality.eci = cf.eci;
        row.quality.flicker_ratio = cf.flicker_ratio;
        row.quality.crawl_valid_fraction = cf.valid_fraction;
        row.quality.crawl_numerator = cf.numerator;
        row.quality.crawl_denominator = cf.denominator;
        if (cf.no_edges) row.quality.note += "no reference edges in the valid region: ECI 0; ";
        if (c.worst_eci.frame < 0 || cf.eci > c.worst_eci.value)
            c.worst_eci = {frame.index, cf.eci, ref, frame.rgba, frame.classes, std::move(cf.crawl_map)};
    } catch (const std::exception& e) {
        row.quality.note += std::string("edge crawl failed: ") + e.what() + "; ";
        c.tracker.reset();
    }
}

std::vector<uint8_t> heatMap(const metrics::Image& value, double scale) {
    std::vector<uint8_t> out(size_t(value.width) * value.height * 4, 255);
    for (size_t i = 0; i < size_t(value.width) * value.height; ++i) {
        double t = std::clamp(value.data[i * value.channels] * scale, 0.0, 1.0);
        // black -> red -> yellow -> white
        out[i * 4] = uint8_t(std::lround(255 * std::clamp(t * 3, 0.0, 1.0)));
        out[i * 4 + 1] = uint8_t(std::lround(255 * std::clamp(t * 3 - 1, 0.0, 1.0)));
        out[i * 4 + 2] = uint8_t(std::lround(255 * std::clamp(t * 3 - 2, 0.0, 1.0)));
    }
    return out;
}

namespace {

// Colours of the checkerboard classes (also the saved class maps and the report legend).
std::vector<uint8_t> classColours(const std::vector<uint8_t>& classes) {
    static const uint8_t kColours[7][3] = {{96, 96, 96},  {40, 200, 60}, {240, 220, 40}, {230, 40, 40},
                                           {40, 90, 240}, {220, 60, 220}, {40, 200, 200}};
    std::vector<uint8_t> out(classes.size() * 4, 255);
    for (size_t i = 0; i < classes.size(); ++i) {
        const uint8_t* c = kColours[classes[i] < 7 ? classes[i] : 0];
        std::copy(c, c + 3, out.begin() + std::ptrdiff_t(i * 4));
    }
    return out;
}

}  // namespace

std::vector<uint8_t> classMapRgba(const std::vector<uint8_t>& classes) { return classColours(classes); }

std::vector<std::string> QualityScorer::finish(const std::filesystem::path& dir) {
    workers_.wait();
    std::vector<std::string> written;
    int w = width_, h = height_;
    auto save = [&](const std::string& name, const std::vector<uint8_t>& rgba) {
        std::filesystem::create_directories(dir / "worst");
        metrics::writePng(dir / "worst" / name, {w, h, rgba});
        written.push_back("worst/" + name);
    };
    for (auto& [variant, c] : chains_) {
        for (auto [kind, worst] : {std::pair<const char*, Worst*>{"ssim", &c->worst_ssim}, {"eci", &c->worst_eci}}) {
            if (worst->frame < 0) continue;
            std::string base = variant + "_" + kind + "_";
            auto ref = metrics::fromRgba8(worst->reference->data(), w, h, size_t(w) * 4);
            auto img = metrics::fromRgba8(worst->image->data(), w, h, size_t(w) * 4);
            metrics::Image error{w, h, 1, std::vector<double>(size_t(w) * h)};
            for (size_t i = 0; i < error.data.size(); ++i)
                error.data[i] = (std::abs(ref.data[3 * i] - img.data[3 * i]) +
                                 std::abs(ref.data[3 * i + 1] - img.data[3 * i + 1]) +
                                 std::abs(ref.data[3 * i + 2] - img.data[3 * i + 2])) / 3.0;
            auto ssim = metrics::ssimMap(ref, img);
            for (double& v : ssim.data) v = 1.0 - v;  // dissimilarity: bright where worse
            save(base + "reference.png", *worst->reference);
            save(base + "variant.png", *worst->image);
            save(base + "error.png", heatMap(error, 4.0));
            save(base + "ssim_map.png", heatMap(ssim, 2.0));
            // FLIP's error is already in perceptual units on [0,1]: unscaled.
            save(base + "flip_map.png", heatMap(metrics::flip(ref, img, flip_ppd_).map, 1.0));
            if (worst->crawl_map) save(base + "crawl_map.png", heatMap(*worst->crawl_map, 8.0));
            if (worst->classes && !worst->classes->empty()) save(base + "class_map.png", classColours(*worst->classes));
        }
    }
    return written;
}

}  // namespace cbr::harness
