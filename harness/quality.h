// Scoring of quality frames on worker threads: PSNR, SSIM and FLIP per frame, edge crawl
// in frame order per variant, and the worst frames kept for the report (method/metrics.md).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "harness/results.h"
#include "harness/wall_account.h"
#include "harness/worker_pool.h"
#include "metrics/image.h"
#include "metrics/temporal.h"

namespace cbr::harness {

using Bytes = std::shared_ptr<const std::vector<uint8_t>>;

// One quality frame of a variant, as read back.
struct QualityFrame {
    int index = 0;
    Bytes rgba;                                    // display image, RGBA8
    Bytes classes;                                 // checkerboard class map (R8), may be null
    std::shared_ptr<const std::vector<float>> analysis;  // motion.xy, depth, previous depth
    bool cut = false;                              // history reset (first frame or camera cut)
};

class QualityScorer {
public:
    // flip_ppd: FLIP's pixels per degree (--flip-ppd). `wall`, when given, receives the
    // workers' time per metric and for image encoding.
    QualityScorer(int width, int height, size_t frames, double flip_ppd, WorkerPool& workers,
                  WallAccount* wall = nullptr);
    ~QualityScorer();

    void setReference(size_t frame, Bytes rgba);
    // Drop each reference frame once its edge-crawl step is done, so a long sequence holds
    // only the frames in flight (score-seq; valid while one variant is scored).
    void releaseReferencesAfterUse() { release_references_ = true; }
    bool hasReference(size_t frame) const;
    // Scores `frame` of `variant` into `row` (which must outlive finish()). `is_reference`:
    // the variant is the reference itself (PSNR inf, SSIM 1, ECI 0, FLIP 0 without computing).
    void score(const std::string& variant, bool is_reference, FrameRow& row, QualityFrame frame);
    // Waits for every job; writes the worst frames (by SSIM and by ECI) of each variant
    // as PNGs under dir/worst/, with their error, SSIM, FLIP, crawl and class maps, each
    // distinct image once, encoded on the workers, and the report's smaller copies under
    // dir/worst/page/. Returns the worst frames in variant order with their files.
    std::vector<WorstFrame> finish(const std::filesystem::path& dir);

private:
    struct Chain;
    struct Worst;
    class Writer;
    void crawlStep(const std::string& variant, FrameRow& row, const QualityFrame& frame);
    Chain& chain(const std::string& variant);

    int width_, height_;
    double flip_ppd_;
    WorkerPool& workers_;
    WallAccount* wall_;
    mutable std::mutex mutex_;
    std::vector<Bytes> reference_;
    bool release_references_ = false;
    std::map<std::string, std::unique_ptr<Chain>> chains_;
    std::vector<std::string> variant_order_;  // first-scored order: the order finish() reports
};

// Every distinct file of the worst frames, in first-use order (run.json `files`).
std::vector<std::string> worstFiles(const std::vector<WorstFrame>& worst);

// Heat-map colouring of a one-channel image (0 black ... 1 white through red and yellow).
std::vector<uint8_t> heatMap(const metrics::Image& value, double scale);
// Checkerboard class map (R8 classes) as RGBA8 colours.
std::vector<uint8_t> classMapRgba(const std::vector<uint8_t>& classes);

}  // namespace cbr::harness
