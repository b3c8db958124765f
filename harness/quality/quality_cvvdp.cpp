// ColorVideoVDP in the CPU scorer: each variant's frames in order against the reference's, with
// the difference map kept for a frame that is its variant's worst so far (docs/method/cvvdp.md).
#include <algorithm>
#include <cmath>

#include "harness/quality/quality.h"

namespace cbr::harness {

void QualityScorer::enableCvvdp(const metrics::DisplayModel& display, double fps) {
    cvvdp_display_ = display;
    cvvdp_fps_ = fps;
}

// With the chain's mutex held, in frame order, after the edge crawl (which picks the worst by ECI).
void QualityScorer::cvvdpStep(Chain& c, FrameRow& row, const QualityFrame& frame, const Bytes& ref) {
    WallAccount::WorkerScope timer(wall_, WorkerTask::Cvvdp);
    try {
        // The model knows no cuts: a cut starts a new sequence, its window filled with the new shot.
        if (!c.cvvdp || frame.cut) c.cvvdp = std::make_unique<metrics::CvvdpTracker>(width_, height_, *cvvdp_display_, cvvdp_fps_);
        const bool worst_ssim = c.worst_ssim.frame == frame.index, worst_eci = c.worst_eci.frame == frame.index;
        const metrics::CvvdpFrame f = c.cvvdp->addRgba8(ref->data(), frame.rgba->data(), worst_ssim || worst_eci);
        if (std::isfinite(f.q)) row.quality.cvvdp_q = f.q;
        else row.quality.note += "cvvdp not finite; ";
        if (!f.map) return;
        auto map = std::make_shared<std::vector<uint8_t>>(f.map->data.size());
        for (size_t i = 0; i < map->size(); ++i)
            (*map)[i] = uint8_t(std::lround(255 * std::clamp(f.map->data[i], 0.0, 1.0)));
        if (worst_ssim) c.worst_ssim.cvvdp_map = map;
        if (worst_eci) c.worst_eci.cvvdp_map = map;
    } catch (const std::exception& e) {
        row.quality.note += std::string("cvvdp failed: ") + e.what() + "; ";
        c.cvvdp.reset();
    }
}

}  // namespace cbr::harness
