// Scoring of quality frames on worker threads: PSNR, SSIM and FLIP per frame, edge crawl
// in frame order per variant, and the worst frames kept for the report (docs/method/measurement.md).
#pragma once

#include <condition_variable>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "harness/figures/results.h"
#include "harness/base/wall_account.h"
#include "harness/base/worker_pool.h"
#include "metrics/cvvdp.h"
#include "metrics/image.h"
#include "metrics/temporal.h"
#include "renderer/scoring/device_metrics.h"

namespace cbr::harness {

using Bytes = std::shared_ptr<const std::vector<uint8_t>>;
using Floats = std::shared_ptr<const std::vector<float>>;

// One quality frame of a variant, as read back.
struct QualityFrame {
    int index = 0;
    Bytes rgba;                                    // display image, RGBA8
    Bytes classes;                                 // checkerboard class map (R8), may be null
    std::shared_ptr<const std::vector<float>> analysis;  // motion.xy, depth, previous depth (RGBA32F)
    bool cut = false;                              // history reset (first frame or camera cut)
    // The analysis as the edge crawl reads it, made from `analysis` (then dropped) by the worker.
    std::shared_ptr<const metrics::MotionField> motion;
};

// The CPU scorer's memory for each frame it holds: the frame (image, class map, motion
// analysis: 21 bytes a pixel), its reference frame's share (4) and the most its scoring adds at
// once (20: the edge crawl's new state, 12, and its map, 8; the motion field while the analysis
// is turned into it takes 16, FLIP's error map and buckets 6): 45, 373 MB at 4K. Besides, each
// variant's edge-crawl state between frames (blurred lumas and depth: 12 bytes a pixel).
inline constexpr double kScoredFrameBytesPerPixel = 45;
inline constexpr double kCrawlStateBytesPerPixel = 12;
// ColorVideoVDP (metrics/cvvdp.h): its window keeps RGB of the reference and the variant (6 bytes a
// pixel a frame); scoring a frame holds eight float channel images with their pyramids (43 bytes a
// pixel), then per band the expanded levels, masks and differences of the band (about 64).
inline constexpr double kCvvdpWindowBytesPerPixel = 6;
inline constexpr double kCvvdpWorkBytesPerPixel = 110;
inline constexpr double kScorerBudgetBytes = 768e6;
// How many frames the CPU scorer holds at once for w x h frames: as many as kScorerBudgetBytes
// holds (2 at 4K, 8 at 1080p), at least 1, at most 16.
size_t scorerFrames(int width, int height);
// The spill's directory in the run's temporary directory (QualityScorer's `spill`).
inline constexpr const char* kWorstSpill = ".worst.spill";

class QualityScorer {
public:
    // flip_ppd: FLIP's pixels per degree (--flip-ppd). `wall`, when given, receives the
    // workers' time per metric and for image encoding. `spill`, when given, is a directory
    // (made when first needed, removed by finish()) where the worst frames' images wait for
    // finish() (worst_spill.h); without it they are kept in memory.
    QualityScorer(int width, int height, double flip_ppd, WorkerPool& workers, WallAccount* wall = nullptr,
                  std::filesystem::path spill = {});
    ~QualityScorer();
    // Scores ColorVideoVDP too (in frame order per variant, beside the edge crawl) on `display` at
    // `fps` frames per second (0: each variant's single frame as an image). Before the first score().
    void enableCvvdp(const metrics::DisplayModel& display, double fps);

    // Reference frame `frame`, to be scored against by `uses` frames (one per other variant):
    // it is dropped once they are done (or skipped), so memory does not grow with the path.
    // Frames handed to score() before their reference arrived are scored now.
    void setReference(size_t frame, Bytes rgba, int uses);
    // A variant that will not score `frame` after all (it failed): one use fewer.
    void skip(size_t frame);
    // The reference failed: frames waiting for it, and frames to come, get a note instead.
    void referenceFailed();
    // Scores `frame` of `variant` into `row` (which must outlive finish()). `is_reference`:
    // the variant is the reference itself (PSNR inf, SSIM 1, ECI 0, FLIP 0 without computing).
    void score(const std::string& variant, bool is_reference, FrameRow& row, QualityFrame frame);
    // The frames handed to score() and not yet through their edge-crawl step, less those
    // waiting for their reference frame (which only the caller can hand in): the caller waits
    // for this before it reads back another frame, so that the scorer holds frameLimit() frames.
    void waitUntilHeldAtMost(size_t frames);
    size_t frameLimit() const { return frame_limit_; }
    // The images of a worst frame kept elsewhere (on the device), fetched when it is written.
    struct WorstImages {
        Bytes reference, image, classes;
        Floats crawl_map, ssim_map, flip_map, cvvdp_map;
        Bytes crawl_heat_map;  // the crawl map already as its heat map (the CPU scorer's)
    };
    using WorstLoader = std::function<bool(WorstImages&)>;
    // A variant's worst frame by `kind` (ssim or eci) whose images `load` brings only when
    // finish() writes it, one at a time: a run never holds every variant's at once.
    void offerWorstLater(const std::string& variant, const std::string& kind, int frame, double value, WorstLoader load);
    // Waits for every job; writes the worst frames (by SSIM and by ECI) of each variant
    // as PNGs under dir/worst/, with their error, SSIM, FLIP, crawl and class maps, each
    // distinct image once, encoded on the workers, and the report's smaller copies under
    // dir/worst/page/. Returns the worst frames in variant order with their files.
    std::vector<WorstFrame> finish(const std::filesystem::path& dir);

private:
    struct Chain;
    struct Worst;
    class Writer;
    struct Reference {
        Bytes rgba;
        int uses = 0;  // scores still to come; may go below 0 before the frame arrives (skips)
        std::vector<std::function<void()>> waiting;  // scores handed in before the frame
    };
    void crawlStep(const std::string& variant, FrameRow& row, const QualityFrame& frame, const Bytes& ref);
    void cvvdpStep(Chain& c, FrameRow& row, const QualityFrame& frame, const Bytes& ref);  // quality_cvvdp.cpp
    void submitScore(Chain& c, const std::string& variant, FrameRow& row, QualityFrame frame, Bytes ref);
    void release(size_t frame);  // with mutex_ held
    void letGo();                // a held frame is done with (mutex_ not held)
    void keepWorst(const Chain& c, const char* kind, Worst& slot, Worst worst);  // with c.mutex held
    bool loadWorst(Worst& worst);
    Chain& chain(const std::string& variant);

    int width_, height_;
    double flip_ppd_;
    std::optional<metrics::DisplayModel> cvvdp_display_;  // set: ColorVideoVDP is scored
    double cvvdp_fps_ = 0;
    WorkerPool& workers_;
    WallAccount* wall_;
    const std::filesystem::path spill_;
    const size_t frame_limit_;
    mutable std::mutex mutex_;
    std::condition_variable let_go_;
    size_t held_ = 0, held_waiting_ = 0;  // frames handed in and not done; of them, waiting for a reference
    std::map<size_t, Reference> references_;  // the frames still to be scored against
    bool reference_failed_ = false;
    std::map<std::string, std::unique_ptr<Chain>> chains_;
    std::vector<std::string> variant_order_;  // first-scored order: the order finish() reports
};

// The scorer's state per variant (defined here so that quality_cvvdp.cpp, the ColorVideoVDP step,
// shares it with quality.cpp).
// The worst frame of one kind (by SSIM or by ECI) of one variant, kept until the end.
struct QualityScorer::Worst {
    int frame = -1;
    double value = 0;  // SSIM (lower is worse) or ECI (higher is worse)
    Bytes reference, image, classes;
    Bytes crawl_map;  // the ECI kind's crawl map, as its heat map (RGBA8)
    // Scored on the device: its SSIM and FLIP maps, made into heat maps only if the frame stays
    // the worst (the writer computes them from the images otherwise).
    Floats ssim_map, flip_map;
    WorstLoader load;     // images kept elsewhere: fetched by finish()
    Floats crawl_values;  // the ECI kind's crawl map as loaded (the device's values), coloured when written
    // ColorVideoVDP's difference map of the frame (1 - JOD/10 per pixel): 8 bits a pixel from the CPU
    // scorer (its chain step, which alone has the frames before), floats from the device.
    Bytes cvvdp_map;
    Floats cvvdp_values;
};

// Frames of one variant arrive out of order; the crawl metric needs them in order.
struct QualityScorer::Chain {
    std::mutex mutex;
    int next = 0;
    struct Pending {
        FrameRow* row;
        QualityFrame frame;
        Bytes reference;
    };
    std::map<int, Pending> pending;
    metrics::CrawlTracker tracker;
    std::unique_ptr<metrics::CvvdpTracker> cvvdp;  // made at the chain's first frame and at each cut
    Worst worst_ssim, worst_eci;
    size_t number = 0;  // in first-scored order: its spill files' names
};


// The CPU scorer's worker threads for w x h frames: `requested` (--scoring-threads) when above
// 0, else half the hardware threads (the other half renders); at most scorerFrames(), as no more
// frames are scored at once. More workers would score nothing more (each metric is parallel
// inside), but each would keep the memory it freed (glibc's per-thread arenas, with freed
// memory kept: process.cpp): 8 at 4K held 310 MB more than 2 (docs/history/memory.md).
unsigned scoringThreads(int requested, int width, int height);

// At most this many worst-frame images are encoded at once for w x h images: each encode holds
// about twice the frame's RGBA8 bytes while it runs (a coloured map, the filtered rows, the
// stream), and a 4K run must stay within its memory (about 66 MB an encode there: 11 at once).
inline constexpr double kWorstEncodeBytesPerPixel = 8;
unsigned worstImageEncoders(int width, int height);

// Every distinct file of the worst frames, in first-use order (run.json `files`).
std::vector<std::string> worstFiles(const std::vector<WorstFrame>& worst);

// The row's figures from the device scorer's (the same definitions; notes where one is
// missing or not finite).
void fillQuality(Quality& quality, const scoring::DeviceScores& scores);

// Heat-map colouring of a one-channel image (0 black ... 1 white through red and yellow).
std::vector<uint8_t> heatMap(const metrics::Image& value, double scale);
// Checkerboard class map (R8 classes) as RGBA8 colours.
std::vector<uint8_t> classMapRgba(const std::vector<uint8_t>& classes);

}  // namespace cbr::harness
