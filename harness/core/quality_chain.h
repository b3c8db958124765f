// The CPU scorer's per-variant state (quality.h's QualityScorer::Chain and ::Worst), shared by
// quality.cpp and quality_cvvdp.cpp.
#pragma once

#include <map>
#include <memory>
#include <mutex>

#include "harness/core/quality.h"
#include "metrics/cvvdp.h"
#include "metrics/temporal.h"

namespace cbr::harness {

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

}  // namespace cbr::harness
