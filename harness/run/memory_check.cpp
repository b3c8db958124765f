// The run's memory estimate and readings (memory_check.h).
#include "harness/run/memory_check.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "harness/quality/quality.h"
#include "harness/figures/scene_load.h"
#include "renderer/vk/memory_use.h"

namespace cbr::harness {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

double procMib(const char* file, const char* key) {
    std::ifstream in(file);
    std::string line;
    const std::string k = key;
    while (std::getline(in, line))
        if (line.rfind(k, 0) == 0) return std::strtod(line.c_str() + k.size(), nullptr) / 1024.0;  // "Key:  1234 kB"
    return 0;
}

// Bytes the run adds after its renderers exist, by what holds them (docs/reference/outputs.md
// run.json `memory`): each term an upper bound of what is alive at once, not a sum over frames.
struct Growth {
    double host = 0;    // the host's own allocations (images, scores, rows, files being encoded)
    double mapped = 0;  // host-visible device memory still to be allocated (host RAM on a GPU too)
    double device = 0;  // device-local memory still to be allocated
};

Growth growth(const MemoryPlan& plan) {
    const double px = double(plan.width) * double(plan.height);
    const double configs = double(plan.configs);
    const double scored = double(plan.scored);
    const double frames = double(plan.frames);
    const bool device = plan.device_scorer;
    const bool analysis = plan.analysis;
    Growth g;
    // A quality frame read back: RGBA8, the class map, the motion analysis (RGBA32F).
    const double readback = px * (4 + 1 + (analysis ? 16 : 0));
    // The frame rows: the timed ones go to the spill as they are made, their numbers kept
    // (FrameDigest: about 0.25 KB a row); the quality pass's scores are kept per configuration
    // and frame (about 0.5 KB) until repetition 0 has them. The report then reads frames.csv
    // whole and charts every frame, after the worst images: 22 MB of heap for 36,000 rows
    // (0.6 KB a row), bounded at 1 KB.
    const double rows = frames * configs * (512 + double(plan.repeat) * 256);
    const double report = frames * configs * double(plan.repeat) * 1024;
    // The alignment check's images, kept to the end: every configuration's middle frame and
    // the reference's three around it.
    const double alignment = (configs + 3) * px * 4;
    // The worst images' phase: encodes at once (about twice a frame's RGBA8 each) and the worst
    // frames they read, up to three at once (RGBA8 reference and image, class map, float maps).
    const double worst_frames = std::min(3.0, scored * 2);
    const double encoders = std::min(double(worstImageEncoders(plan.width, plan.height)), worst_frames * 7);
    double writing = encoders * kWorstEncodeBytesPerPixel * px + worst_frames * px * 21;
    double scoring;
    if (device) {
        g.device = scored * 2 * px * 21;  // each configuration's two worst-frame stores
        g.mapped = px * 21;               // the one host buffer they are fetched through
        scoring = 0;
    } else {
        // Read back one frame at a time (Renderer::collectNow): one frame's host copies.
        g.mapped = readback;
        // The CPU scorer (quality.h): the frames it holds, with what scoring them takes; each
        // scored configuration's edge-crawl state; the frame being handed in (its heap copy);
        // the metrics' tiles on every thread (under 1 MB each). Its worst frames wait on disk.
        // ColorVideoVDP: each configuration's window (kCvvdpWindowBytesPerPixel a frame of it), and
        // on each thread scoring a frame its pyramids and masks (kCvvdpWorkBytesPerPixel).
        scoring = double(scorerFrames(plan.width, plan.height)) * kScoredFrameBytesPerPixel * px +
                  scored * kCrawlStateBytesPerPixel * px + readback +
                  scored * double(plan.cvvdp_window) * kCvvdpWindowBytesPerPixel * px +
                  double(scorerFrames(plan.width, plan.height)) * kCvvdpWorkBytesPerPixel * px +
                  double(std::thread::hardware_concurrency()) * 1024 * 1024;
        // The worst frames' SSIM and FLIP maps, computed from the images one frame at a time:
        // two RGB images of doubles (48 bytes a pixel), the maps and their colours (12); FLIP's
        // error maps kept from the scoring (4 bytes a pixel each).
        writing += px * 60 + double(scorerFrames(plan.width, plan.height)) * px * 4;
    }
    // The rest (thread stacks, the allocator's slack): a tenth more.
    g.host = 1.1 * (rows + alignment + std::max({scoring, writing, report}));
    return g;
}

std::string mib(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, bytes >= 1024 * kMiB ? "%.1f GiB" : "%.0f MiB",
                  bytes >= 1024 * kMiB ? bytes / (1024 * kMiB) : bytes / kMiB);
    return text;
}

[[noreturn]] void refuse(const MemoryPlan& plan, const char* what, double need, double limit, const std::string& from,
                         const char* option) {
    throw std::invalid_argument(std::string("--res ") + plan.resolution + ", " + std::to_string(plan.configs) +
                                " configurations, " + std::to_string(plan.frames) + " frames: the run needs about " + mib(need) +
                                " of " + what + " memory, above the limit of " + mib(limit) + " (" + from +
                                "); expected a lower --res, fewer --variants, or a higher " + option);
}

}  // namespace

double currentRssMib() { return procMib("/proc/self/status", "VmRSS:"); }
double availableHostMib() { return procMib("/proc/meminfo", "MemAvailable:"); }

void checkMemory(const MemoryPlan& plan, const vk::Context& ctx, MemoryFigures& m) {
    const Growth g = growth(plan);
    const vk::HeapReading heaps = vk::readDeviceHeaps(ctx);
    // lavapipe's "device" memory is the host's: it counts against both.
    const bool shared = ctx.description.is_lavapipe || ctx.description.device_type == "cpu";
    const double device_now = double(ctx.memory_use.deviceLocal());
    const double rss_now = currentRssMib();
    m.device_estimate_mib = (device_now + g.device + (shared ? g.mapped : 0)) / kMiB;
    // There its allocations so far are not yet in the RSS either: their pages are touched as
    // the frames render.
    m.host_estimate_mib = rss_now + (g.host + g.mapped + (shared ? device_now + g.device : 0)) / kMiB;
    m.device_heap_mib = double(heaps.heap_bytes) / kMiB;
    if (heaps.has_budget) m.device_budget_mib = double(heaps.budget_bytes) / kMiB;

    if (plan.host_limit_mib > 0) {
        m.host_limit_mib = plan.host_limit_mib;
        m.host_limit_from = "--host-memory-limit";
    } else {
        m.host_limit_mib = rss_now + availableHostMib();
        m.host_limit_from = "the run's own and the host's MemAvailable";
    }
    if (plan.device_limit_mib > 0) {
        m.device_limit_mib = plan.device_limit_mib;
        m.device_limit_from = "--device-memory-limit";
    } else if (heaps.has_budget) {
        // The budget covers what the process already uses: its own allocations are inside it.
        m.device_limit_mib = double(heaps.budget_bytes) / kMiB;
        m.device_limit_from = "the device's budget, VK_EXT_memory_budget";
    } else {
        m.device_limit_mib = m.device_heap_mib;
        m.device_limit_from = "the device-local heaps' size";
    }
    if (m.host_limit_mib > 0 && m.host_estimate_mib > m.host_limit_mib)
        refuse(plan, "host", m.host_estimate_mib * kMiB, m.host_limit_mib * kMiB, m.host_limit_from, "--host-memory-limit");
    // On lavapipe the heaps are the host's memory, checked above, unless a limit is given.
    const bool device_limited = !shared || plan.device_limit_mib > 0;
    if (device_limited && m.device_limit_mib > 0 && m.device_estimate_mib > m.device_limit_mib)
        refuse(plan, "device", m.device_estimate_mib * kMiB, m.device_limit_mib * kMiB, m.device_limit_from,
               "--device-memory-limit");
}

void noteMemory(const vk::Context& ctx, const char* phase, MemoryFigures& m, WallAccount& wall) {
    const double rss = peakRssMib();
    wall.notePeakRss(phase, rss);
    MemoryFigures::Reading r;
    r.after = phase;
    r.peak_rss_mib = rss;
    r.device_allocated_mib = double(ctx.memory_use.deviceLocal()) / kMiB;
    const vk::HeapReading heaps = vk::readDeviceHeaps(ctx);
    if (heaps.has_budget) r.device_usage_mib = double(heaps.usage_bytes) / kMiB;
    m.after.push_back(r);
    m.device_allocated_peak_mib = double(ctx.memory_use.deviceLocalPeak()) / kMiB;
    m.host_visible_allocated_peak_mib = double(ctx.memory_use.hostVisiblePeak()) / kMiB;
}

}  // namespace cbr::harness
