// Quality scoring on worker threads: PSNR/SSIM/FLIP per frame, ECI in order, worst frames.
#include "harness/quality/quality.h"

#include <algorithm>
#include <cmath>

#include <cstdio>
#include <malloc.h>
#include <set>
#include <thread>

#include "harness/quality/worst_spill.h"
#include "metrics/flip.h"
#include "metrics/frame_scores.h"
#include "metrics/image_encode.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "rundir/run_json_variants.h"

namespace cbr::harness {

namespace {

// The renderer's analysis (RGBA32F: motion.xy, depth, previous depth) as the edge crawl reads
// it; null when it is not the frame's size.
std::shared_ptr<const metrics::MotionField> motionField(const std::vector<float>& analysis, int w, int h) {
    const size_t n = size_t(w) * size_t(h);
    if (analysis.size() != 4 * n) return nullptr;
    auto motion = std::make_shared<metrics::MotionField>();
    motion->width = w;
    motion->height = h;
    motion->motion.resize(n * 2);
    motion->depth.resize(n);
    motion->prev_depth_expected.resize(n);
    const float* a = analysis.data();
    for (size_t i = 0; i < n; ++i) {
        motion->motion[2 * i] = a[4 * i];
        motion->motion[2 * i + 1] = a[4 * i + 1];
        motion->depth[i] = a[4 * i + 2];
        motion->prev_depth_expected[i] = a[4 * i + 3];
    }
    return motion;
}

}  // namespace

size_t scorerFrames(int width, int height) {
    const double frame = kScoredFrameBytesPerPixel * double(width) * double(height);
    return size_t(std::clamp(std::floor(kScorerBudgetBytes / frame), 1.0, 16.0));
}

QualityScorer::QualityScorer(int width, int height, double flip_ppd, WorkerPool& workers, WallAccount* wall,
                             std::filesystem::path spill)
    : width_(width), height_(height), flip_ppd_(flip_ppd), workers_(workers), wall_(wall), spill_(std::move(spill)),
      frame_limit_(scorerFrames(width, height)) {}

QualityScorer::~QualityScorer() {
    workers_.wait();
    std::error_code ignored;
    if (!spill_.empty()) std::filesystem::remove_all(spill_, ignored);
}

void QualityScorer::letGo() {
    {
        std::lock_guard lock(mutex_);
        --held_;
    }
    let_go_.notify_all();
}

void QualityScorer::waitUntilHeldAtMost(size_t frames) {
    std::unique_lock lock(mutex_);
    let_go_.wait(lock, [&] { return held_ - held_waiting_ <= frames; });
}

void QualityScorer::setReference(size_t frame, Bytes rgba, int uses) {
    std::vector<std::function<void()>> waiting;
    {
        std::lock_guard lock(mutex_);
        Reference& r = references_[frame];
        r.rgba = std::move(rgba);
        r.uses += uses;
        waiting.swap(r.waiting);
        if (r.uses <= 0 && waiting.empty()) references_.erase(frame);
    }
    for (auto& job : waiting) job();
}

void QualityScorer::skip(size_t frame) {
    std::lock_guard lock(mutex_);
    release(frame);
}

void QualityScorer::release(size_t frame) {
    Reference& r = references_[frame];
    if (--r.uses <= 0 && r.rgba && r.waiting.empty()) references_.erase(frame);
}

void QualityScorer::referenceFailed() {
    std::vector<std::function<void()>> waiting;
    {
        std::lock_guard lock(mutex_);
        reference_failed_ = true;
        for (auto& [frame, r] : references_)
            for (auto& job : r.waiting) waiting.push_back(std::move(job));
        references_.clear();
    }
    for (auto& job : waiting) job();
}

QualityScorer::Chain& QualityScorer::chain(const std::string& variant) {
    std::lock_guard lock(mutex_);
    auto& c = chains_[variant];
    if (!c) {
        c = std::make_unique<Chain>();
        c->number = variant_order_.size();
        variant_order_.push_back(variant);
    }
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
        if (cvvdp_display_) row.quality.cvvdp_q = 0.0;
        return;
    }
    Chain& c = chain(variant);
    const size_t index = size_t(frame.index);
    std::unique_lock lock(mutex_);
    if (reference_failed_) {
        row.quality.note += "no reference frame (the reference failed); ";
        return;
    }
    ++held_;
    Reference& r = references_[index];
    if (r.rgba) {
        Bytes ref = r.rgba;
        lock.unlock();
        return submitScore(c, variant, row, std::move(frame), std::move(ref));
    }
    // Its reference frame is still in flight: scored when it arrives (or noted if it never does).
    ++held_waiting_;
    r.waiting.push_back([this, &c, variant, &row, frame = std::move(frame), index]() mutable {
        Bytes ref;
        {
            std::lock_guard inner(mutex_);
            --held_waiting_;
            auto it = references_.find(index);
            if (it != references_.end()) ref = it->second.rgba;
        }
        if (ref) return submitScore(c, variant, row, std::move(frame), std::move(ref));
        row.quality.note += "no reference frame (the reference failed); ";
        letGo();
    });
}

void QualityScorer::submitScore(Chain& c, const std::string& variant, FrameRow& row, QualityFrame frame, Bytes ref) {
    int w = width_, h = height_;
    workers_.submit([this, &c, &row, ref, frame = std::move(frame), variant, w, h]() mutable {
        if (frame.analysis) {
            frame.motion = motionField(*frame.analysis, w, h);
            frame.analysis.reset();
        }
        try {
            // Straight from the 8-bit readbacks (metrics/frame_scores.h): no [0,1] image built.
            const metrics::FrameScores f = metrics::scoreFrame(ref->data(), frame.rgba->data(), w, h, flip_ppd_);
            if (wall_) {
                wall_->addWorker(WorkerTask::Psnr, f.mse_ms * 1e-3);
                wall_->addWorker(WorkerTask::Ssim, f.ssim_ms * 1e-3);
                wall_->addWorker(WorkerTask::Flip, f.flip_ms * 1e-3);
            }
            row.quality.mse = f.mse;
            row.quality.psnr_db = f.psnr_db;
            if (std::isfinite(f.ssim)) row.quality.ssim = f.ssim;
            else row.quality.note += "ssim not finite; ";
            if (std::isfinite(f.ssim_luma)) row.quality.ssim_luma = f.ssim_luma;
            row.quality.flip_mean = f.flip_mean;
            row.quality.flip_q1 = f.flip_q1;
            row.quality.flip_median = f.flip_median;
            row.quality.flip_q3 = f.flip_q3;
            std::lock_guard lock(c.mutex);
            if (row.quality.ssim && (c.worst_ssim.frame < 0 || *row.quality.ssim < c.worst_ssim.value))
                keepWorst(c, rundir::run::worst::kSsim, c.worst_ssim, {frame.index, *row.quality.ssim, ref, frame.rgba, frame.classes, nullptr});
        } catch (const std::exception& e) {
            row.quality.note += std::string("metrics failed: ") + e.what() + "; ";
        }
        // Edge crawl needs frame t-1 of the same variant: run the chain in order. Each
        // reference frame is given back once its crawl step is done.
        size_t done = 0;
        {
            std::lock_guard lock(c.mutex);
            const int index = frame.index;
            c.pending.emplace(index, Chain::Pending{&row, std::move(frame), std::move(ref)});
            for (auto it = c.pending.find(c.next); it != c.pending.end(); it = c.pending.find(c.next)) {
                crawlStep(variant, *it->second.row, it->second.frame, it->second.reference);
                if (cvvdp_display_) cvvdpStep(c, *it->second.row, it->second.frame, it->second.reference);
                c.tracker.dropSpare();  // one frame's state kept per variant (kCrawlStateBytesPerPixel)
                c.pending.erase(it);
                std::lock_guard reference_lock(mutex_);
                release(size_t(c.next));
                --held_;
                ++done;
                ++c.next;
            }
        }
        if (done) let_go_.notify_all();
    });
}


void fillQuality(Quality& q, const scoring::DeviceScores& d) {
    auto put = [&q](std::optional<double>& field, double value, const char* name) {
        if (std::isfinite(value)) field = value;
        else q.note += std::string(name) + " not finite; ";
    };
    if (std::isfinite(d.mse) && d.mse >= 0) {
        q.mse = d.mse;
        q.psnr_db = metrics::psnrFromMse(d.mse);
    } else {
        q.note += "mse not finite; ";
    }
    put(q.ssim, d.ssim, "ssim");
    put(q.ssim_luma, d.ssim_luma, "ssim_luma");
    put(q.flip_mean, d.flip_mean, "flip");
    put(q.flip_q1, d.flip_q1, "flip_q1");
    put(q.flip_median, d.flip_median, "flip_median");
    put(q.flip_q3, d.flip_q3, "flip_q3");
    put(q.cvvdp_q, d.cvvdp_q, "cvvdp");
    if (!d.has_pair) return;  // first frame or after a cut: no pair to compare
    put(q.eci, d.eci, "eci");
    put(q.flicker_ratio, d.flicker_ratio, "flicker_ratio");
    put(q.crawl_valid_fraction, d.valid_fraction, "crawl_valid_fraction");
    q.crawl_numerator = d.crawl_numerator;
    q.crawl_denominator = d.crawl_denominator;
    if (d.no_edges) q.note += "no reference edges in the valid region: ECI 0; ";
}

// Called with the chain's mutex held, in frame order.
void QualityScorer::crawlStep(const std::string& variant, FrameRow& row, const QualityFrame& frame, const Bytes& ref) {
    Chain& c = *chains_.at(variant);
    WallAccount::WorkerScope timer(wall_, WorkerTask::Eci);
    if (!frame.motion) {
        row.quality.note += "no motion analysis: no edge crawl; ";
        c.tracker.reset();
        return;
    }
    try {
        metrics::CrawlFrame cf = c.tracker.addRgba8(ref->data(), frame.rgba->data(), *frame.motion, frame.cut, true);
        if (!cf.has_pair) return;  // first frame or after a cut: no pair to compare
        row.quality.eci = cf.eci;
        row.quality.flicker_ratio = cf.flicker_ratio;
        row.quality.crawl_valid_fraction = cf.valid_fraction;
        row.quality.crawl_numerator = cf.numerator;
        row.quality.crawl_denominator = cf.denominator;
        if (cf.no_edges) row.quality.note += "no reference edges in the valid region: ECI 0; ";
        if (c.worst_eci.frame < 0 || cf.eci > c.worst_eci.value)
            keepWorst(c, rundir::run::worst::kEci, c.worst_eci,
                      {frame.index, cf.eci, ref, frame.rgba, frame.classes,
                       cf.crawl_map ? std::make_shared<const std::vector<uint8_t>>(heatMap(*cf.crawl_map, 8.0)) : nullptr});
    } catch (const std::exception& e) {
        row.quality.note += std::string("edge crawl failed: ") + e.what() + "; ";
        c.tracker.reset();
    }
}


unsigned scoringThreads(int requested, int width, int height) {
    const unsigned threads = requested > 0 ? unsigned(requested) : std::max(1u, std::thread::hardware_concurrency() / 2);
    return std::min(threads, unsigned(scorerFrames(width, height)));
}


}  // namespace cbr::harness
