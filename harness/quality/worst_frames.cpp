// The worst frames: each chain's worst frame kept (on the spill or in memory), its images and
// heat maps written once on the workers, and the list of files the report shows.
#include "harness/quality/quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <thread>

#include "harness/quality/worst_spill.h"
#include "metrics/flip.h"
#include "metrics/image_encode.h"
#include "metrics/image_io.h"
#include "rundir/files.h"
#include "rundir/run_json_variants.h"

namespace cbr::harness {

// run.json worst[].files and page: the images of a worst frame, each file named after its key.
namespace worst_image = rundir::run::worst::image;

// A chain's new worst frame of a kind: its images to the spill, when there is one, for finish()
// to read back; kept in memory otherwise (or when the spill cannot be written).
void QualityScorer::keepWorst(const Chain& c, const char* kind, Worst& slot, Worst worst) {
    if (!spill_.empty()) {
        const auto file = spill_ / (std::to_string(c.number) + "-" + kind + ".raw");
        try {
            std::filesystem::create_directories(spill_);
            spillImages(file, {worst.reference, worst.image, worst.classes, worst.crawl_map});
            worst.reference = worst.image = worst.classes = worst.crawl_map = nullptr;
            worst.load = [file](WorstImages& out) {
                try {
                    const auto images = readSpilledImages(file, 4);
                    out.reference = images[0];
                    out.image = images[1];
                    out.classes = images[2];
                    out.crawl_heat_map = images[3];
                    return out.reference && out.image;
                } catch (const std::exception& e) {
                    std::fprintf(stderr, "cbrbench: worst frame not written: %s\n", e.what());
                    return false;
                }
            };
        } catch (const std::exception& e) {
            std::fprintf(stderr, "cbrbench: worst frame kept in memory: %s\n", e.what());
        }
    }
    slot = std::move(worst);
}

void QualityScorer::offerWorstLater(const std::string& variant, const std::string& kind, int frame, double value,
                                    WorstLoader load) {
    Chain& c = chain(variant);
    std::lock_guard lock(c.mutex);
    const bool ssim = kind == rundir::run::worst::kSsim;
    Worst& w = ssim ? c.worst_ssim : c.worst_eci;
    if (w.frame >= 0 && (ssim ? !(value < w.value) : !(value > w.value))) return;
    w = Worst{};
    w.frame = frame;
    w.value = value;
    w.load = std::move(load);
}
namespace {

// The heat map of n values value(i) (in double, as the maps' own values are turned into
// colours) without an intermediate image: black -> red -> yellow -> white.
template <typename Value>
std::vector<uint8_t> heatMapOf(size_t n, double scale, const Value& value) {
    std::vector<uint8_t> out(n * 4, 255);
    for (size_t i = 0; i < n; ++i) {
        const double t = std::clamp(value(i) * scale, 0.0, 1.0);
        out[i * 4] = uint8_t(std::lround(255 * std::clamp(t * 3, 0.0, 1.0)));
        out[i * 4 + 1] = uint8_t(std::lround(255 * std::clamp(t * 3 - 1, 0.0, 1.0)));
        out[i * 4 + 2] = uint8_t(std::lround(255 * std::clamp(t * 3 - 2, 0.0, 1.0)));
    }
    return out;
}

}  // namespace

std::vector<uint8_t> heatMap(const metrics::Image& value, double scale) {
    return heatMapOf(size_t(value.width) * value.height, scale,
                     [&](size_t i) { return value.data[i * size_t(value.channels)]; });
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

// Schedules each distinct worst-frame image once on the workers: its lossless PNG in worst/
// and the report's JPEG copy in worst/page/ (at most 1280 px wide for the frames the page
// wipes between, 480 px for the maps it shows at 250 px).
class QualityScorer::Writer {
public:
    Writer(const std::filesystem::path& dir, int width, int height, double flip_ppd, WorkerPool& workers,
           WallAccount* wall)
        : dir_(dir), w_(width), h_(height), flip_ppd_(flip_ppd), workers_(workers), wall_(wall) {
        std::filesystem::create_directories(dir / rundir::kWorstDir / rundir::kWorstPageDir);
    }

    void add(WorstFrame& wf, const Worst& worst) {
        char stem[160];
        std::snprintf(stem, sizeof stem, "%s_%04d", wf.variant.c_str(), wf.frame);
        const std::string base = stem;
        std::snprintf(stem, sizeof stem, "reference_%04d", wf.frame);
        image(wf, worst_image::kReference, stem, kept(worst.reference), kFrame);
        image(wf, worst_image::kVariant, base, kept(worst.image), kFrame);
        maps(wf, base, worst);
        cvvdpMap(wf, base, worst);
        if (worst.crawl_map) {
            image(wf, worst_image::kCrawlMap, base + "_" + worst_image::kCrawlMap, kept(worst.crawl_map), kMap);
        } else if (worst.crawl_values) {
            image(wf, worst_image::kCrawlMap, base + "_" + worst_image::kCrawlMap, [map = worst.crawl_values] {
                return colour(heatMapOf(map->size(), 8.0, [&](size_t i) { return double((*map)[i]); }));
            }, kMap);
        }
        if (worst.classes && !worst.classes->empty())
            image(wf, worst_image::kClassMap, base + "_" + worst_image::kClassMap, [classes = worst.classes] { return colour(classMapRgba(*classes)); },
                  kMap);
    }

    // Every file scheduled, once the workers are done; errors were printed as they came.
    void wait() { workers_.wait(); }

private:
    static constexpr int kFrame = 1280, kMap = 480;  // the page copies' widest (shown at about 660 and 250 px)
    // JPEG quality: above 90 stb_image_write keeps full-resolution chroma, so the frames'
    // coloured edges stay sharp (91: the smallest such); the maps' thumbnails, linked to their
    // PNGs, can take 4:2:0. The default bench's page: 8.1 MB at 92/85, 7.3 at 91/80.
    static constexpr int kFrameQuality = 91, kMapQuality = 80;

    // An image's RGBA8 pixels, made on the worker that encodes them: a map is coloured there
    // and dropped with its encode, so no queue of coloured maps waits in memory.
    using Pixels = std::function<Bytes()>;
    static Pixels kept(Bytes pixels) {
        return [pixels = std::move(pixels)] { return pixels; };
    }
    static Bytes colour(std::vector<uint8_t> rgba) { return std::make_shared<const std::vector<uint8_t>>(std::move(rgba)); }

    // Files of one image: recorded in the entry, encoded only the first time the stem appears.
    void image(WorstFrame& wf, const std::string& what, const std::string& stem, Pixels pixels, int page_width) {
        const std::string worst_dir = std::string(rundir::kWorstDir) + "/";
        wf.files.push_back({what, worst_dir + stem + ".png"});
        wf.page.push_back({what, worst_dir + rundir::kWorstPageDir + "/" + stem + ".jpg"});
        if (!scheduled_.insert(stem).second) return;
        const int quality = page_width == kFrame ? kFrameQuality : kMapQuality;
        workers_.submit([this, stem, pixels = std::move(pixels), page_width, quality] {
            WallAccount::WorkerScope timer(wall_, WorkerTask::ImageEncode);
            try {
                const Bytes rgba = pixels();
                if (!rgba) return;  // its making failed, and said so
                const metrics::Rgba8View full{w_, h_, *rgba};
                metrics::writeFileAtomically(dir_ / rundir::kWorstDir / (stem + ".png"), metrics::encodePng(full));
                metrics::writeFileAtomically(dir_ / rundir::kWorstDir / rundir::kWorstPageDir / (stem + ".jpg"),
                                             metrics::encodeJpeg(metrics::downscale(full, page_width), quality));
            } catch (const std::exception& e) {
                std::fprintf(stderr, "cbrbench: worst-frame image %s not written: %s\n", stem.c_str(), e.what());
            }
        });
    }

    // The error, 1 - SSIM and FLIP maps of one (variant, frame). The device's maps are coloured
    // on the workers; maps the CPU must compute are made here, one frame's at a time (each metric
    // is parallel inside, and the full-size intermediates of several frames at once would not
    // fit in a 4K run's memory).
    void maps(WorstFrame& wf, const std::string& base, const Worst& worst) {
        if (scheduled_.count(base + "_" + worst_image::kError)) {
            for (const char* what : {worst_image::kError, worst_image::kSsimMap, worst_image::kFlipMap}) image(wf, what, base + "_" + what, nullptr, kMap);
            return;
        }
        image(wf, worst_image::kError, base + "_" + worst_image::kError, [reference = worst.reference, variant = worst.image, n = pixels()] {
            const auto& a = *reference;
            const auto& b = *variant;
            return colour(heatMapOf(n, 4.0, [&](size_t i) {
                return (std::abs(int(a[4 * i]) - int(b[4 * i])) + std::abs(int(a[4 * i + 1]) - int(b[4 * i + 1])) +
                        std::abs(int(a[4 * i + 2]) - int(b[4 * i + 2]))) / (3.0 * 255.0);
            }));
        }, kMap);
        if (worst.ssim_map && worst.flip_map) {
            // Dissimilarity: bright where worse. FLIP's error is already in perceptual units on [0,1]: unscaled.
            image(wf, worst_image::kSsimMap, base + "_" + worst_image::kSsimMap, [map = worst.ssim_map] {
                return colour(heatMapOf(map->size(), 2.0, [&](size_t i) { return 1.0 - double((*map)[i]); }));
            }, kMap);
            image(wf, worst_image::kFlipMap, base + "_" + worst_image::kFlipMap, [map = worst.flip_map] {
                return colour(heatMapOf(map->size(), 1.0, [&](size_t i) { return double((*map)[i]); }));
            }, kMap);
            return;
        }
        Bytes ssim, flip;
        try {
            const auto& reference = *worst.reference;
            const auto& variant = *worst.image;
            {
                WallAccount::WorkerScope timer(wall_, WorkerTask::Ssim);
                auto map = metrics::ssimMap(metrics::fromRgba8(reference.data(), w_, h_, size_t(w_) * 4),
                                            metrics::fromRgba8(variant.data(), w_, h_, size_t(w_) * 4));
                ssim = colour(heatMapOf(pixels(), 2.0, [&](size_t i) { return 1.0 - map.data[i]; }));
            }
            WallAccount::WorkerScope timer(wall_, WorkerTask::Flip);
            flip = colour(heatMap(metrics::flipRgba8(reference.data(), variant.data(), w_, h_, flip_ppd_, true).map, 1.0));
        } catch (const std::exception& e) {
            std::fprintf(stderr, "cbrbench: maps of %s not written: %s\n", base.c_str(), e.what());
        }
        image(wf, worst_image::kSsimMap, base + "_" + worst_image::kSsimMap, kept(ssim), kMap);
        image(wf, worst_image::kFlipMap, base + "_" + worst_image::kFlipMap, kept(flip), kMap);
    }

    // ColorVideoVDP's map, at 4x (a quarter of the way to 10 JOD is white): kept by the chain step
    // or brought from the device. A frame worst by both kinds has one.
    void cvvdpMap(WorstFrame& wf, const std::string& base, const Worst& worst) {
        constexpr double kScale = 4.0;
        if (worst.cvvdp_map) {
            image(wf, worst_image::kCvvdpMap, base + "_" + worst_image::kCvvdpMap, [map = worst.cvvdp_map] {
                return colour(heatMapOf(map->size(), kScale, [&](size_t i) { return (*map)[i] / 255.0; }));
            }, kMap);
        } else if (worst.cvvdp_values) {
            image(wf, worst_image::kCvvdpMap, base + "_" + worst_image::kCvvdpMap, [map = worst.cvvdp_values] {
                return colour(heatMapOf(map->size(), kScale, [&](size_t i) { return double((*map)[i]); }));
            }, kMap);
        }
    }

    size_t pixels() const { return size_t(w_) * size_t(h_); }

    const std::filesystem::path dir_;
    const int w_, h_;
    const double flip_ppd_;
    WorkerPool& workers_;
    WallAccount* wall_;
    std::set<std::string> scheduled_;  // stems handed to the workers (main thread only)
};

// Brings a worst frame's images from where they were kept.
bool QualityScorer::loadWorst(Worst& worst) {
    WorstImages images;
    if (!worst.load(images)) return false;
    worst.reference = images.reference;
    worst.image = images.image;
    worst.classes = images.classes;
    worst.ssim_map = images.ssim_map;
    worst.flip_map = images.flip_map;
    worst.crawl_map = images.crawl_heat_map;
    if (images.cvvdp_map && images.cvvdp_map->size() == size_t(width_) * size_t(height_))
        worst.cvvdp_values = images.cvvdp_map;
    if (images.crawl_map && images.crawl_map->size() == size_t(width_) * size_t(height_))
        worst.crawl_values = images.crawl_map;
    return true;
}

std::vector<WorstFrame> QualityScorer::finish(const std::filesystem::path& dir) {
    workers_.wait();
    // The spill goes with what it held, before the output is committed.
    struct RemoveSpill {
        const std::filesystem::path& dir;
        ~RemoveSpill() {
            std::error_code ignored;
            if (!dir.empty()) std::filesystem::remove_all(dir, ignored);
        }
    } remove_spill{spill_};
    // The edge-crawl states are done with; what the workers freed stays in their own arenas
    // (process.cpp keeps freed memory), where the images' phase, on other threads, cannot
    // reuse it: given back first (4K, every variant, lavapipe: the phase's peak 4,492 MiB, 453
    // above the quality pass's, before this).
    for (auto& [variant, c] : chains_) {
        c->tracker.reset();
        c->cvvdp.reset();
    }
#ifdef __GLIBC__
    malloc_trim(0);
#endif
    std::vector<WorstFrame> out;
    bool any = false;
    for (auto& [variant, c] : chains_) any |= c->worst_ssim.frame >= 0 || c->worst_eci.frame >= 0;
    if (!any) return out;
    // Nothing else runs now: the cores encode, as many as memory allows.
    const unsigned threads = worstImageEncoders(width_, height_);
    WorkerPool encoders(threads);
    Writer writer(dir, width_, height_, flip_ppd_, encoders, wall_);
    for (const auto& variant : variant_order_) {
        Chain& c = *chains_.at(variant);
        for (auto [kind, worst] : {std::pair<const char*, Worst*>{rundir::run::worst::kSsim, &c.worst_ssim}, {rundir::run::worst::kEci, &c.worst_eci}}) {
            if (worst->frame < 0) continue;
            // One frame's images loaded at a time, once the queue has drained to what runs:
            // the frames in memory are this one and those whose last encodes are running.
            encoders.waitUntilAtMost(threads);
            if (worst->load && !loadWorst(*worst)) continue;
            WorstFrame& wf = out.emplace_back();
            wf.variant = variant;
            wf.kind = kind;
            wf.frame = worst->frame;
            wf.value = worst->value;
            writer.add(wf, *worst);
            // Its images live on in the writer's jobs only as long as they need them.
            if (worst->load) *worst = Worst{worst->frame, worst->value};
        }
    }
    writer.wait();
    return out;
}
unsigned worstImageEncoders(int width, int height) {
    const double job_bytes = kWorstEncodeBytesPerPixel * double(width) * double(height);
    const auto by_memory = unsigned(std::max(2.0, 768e6 / job_bytes));
    return std::clamp(std::min(std::thread::hardware_concurrency(), by_memory), 1u, 16u);
}

std::vector<std::string> worstFiles(const std::vector<WorstFrame>& worst) {
    std::vector<std::string> files;
    std::set<std::string> seen;
    for (const auto& wf : worst)
        for (const auto* list : {&wf.files, &wf.page})
            for (const auto& [what, file] : *list)
                if (seen.insert(file).second) files.push_back(file);
    return files;
}

}  // namespace cbr::harness
