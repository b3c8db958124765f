// Edge crawl index (ECI) and flicker ratio, as defined in docs/method/measurement.md ("Edge
// crawl index"): the variant's frame-to-frame change minus the reference's, after backward
// warping with the renderer's motion vectors, scored on the reference's edges only. The
// tracker keeps the previous frame; its stages: crawl_blur.cpp (step 1), crawl_score.cpp.
#include "metrics/temporal.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "metrics/buffers.h"
#include "metrics/crawl_stages.h"

namespace cbr::metrics {

// Two frames' buffers used in turn: frames[current] is the previous frame, the other is
// overwritten by the next one, so a sequence allocates (and page-faults) only once.
struct CrawlTracker::State {
    struct Frame {
        int width = 0;
        int height = 0;
        // Blurred lumas in single precision: ECI and flicker are ratios of differences of
        // about 1e-2, so float's 6e-8 moves them by ~1e-7 of the 1e-4 issue 32 allows, and
        // the blur and the warp read half the bytes.
        std::vector<float> reference_luma;  // blurred; e_t = variant - reference
        std::vector<float> variant_luma;    // blurred
        std::vector<float> depth;            // for the next frame's disocclusion test
    };
    Frame frames[2];
    int current = 0;
};

// What the blur reads: an Image of doubles (RGB or grey), or RGBA8 bytes.
struct CrawlTracker::Input {
    const Image* image = nullptr;
    const uint8_t* rgba = nullptr;
    int width = 0, height = 0;
};

namespace {

std::string sizeText(int width, int height) {
    return std::to_string(width) + "x" + std::to_string(height);
}

void checkImage(const char* what, const Image& image) {
    const std::string where = std::string("CrawlTracker::add: ") + what;
    if (image.channels != 1 && image.channels != 3)
        throw std::invalid_argument(where + " has " + std::to_string(image.channels) +
                                    " channels, expected 1 or 3");
    if (image.width <= 0 || image.height <= 0)
        throw std::invalid_argument(where + " is empty (" + sizeText(image.width, image.height) +
                                    ")");
    const size_t expected = size_t(image.width) * image.height * image.channels;
    if (image.data.size() != expected)
        throw std::invalid_argument(where + " holds " + std::to_string(image.data.size()) +
                                    " values, " + sizeText(image.width, image.height) + "x" +
                                    std::to_string(image.channels) + " needs " +
                                    std::to_string(expected));
}

void checkField(const char* what, size_t size, size_t expected, const MotionField& motion) {
    if (size != expected)
        throw std::invalid_argument(std::string("CrawlTracker::add: motion field ") + what +
                                    " holds " + std::to_string(size) + " values, a " +
                                    sizeText(motion.width, motion.height) + " frame needs " +
                                    std::to_string(expected));
}

void checkInputs(const Image& reference, const Image& variant, const MotionField& motion) {
    checkImage("reference", reference);
    checkImage("variant", variant);
    if (!reference.sameShape(variant))
        throw std::invalid_argument(
            "CrawlTracker::add: reference and variant shapes differ (" +
            sizeText(reference.width, reference.height) + "x" +
            std::to_string(reference.channels) + " vs " +
            sizeText(variant.width, variant.height) + "x" + std::to_string(variant.channels) +
            ")");
    if (motion.width != reference.width || motion.height != reference.height)
        throw std::invalid_argument("CrawlTracker::add: motion field is " +
                                    sizeText(motion.width, motion.height) + ", images are " +
                                    sizeText(reference.width, reference.height));
    const size_t pixels = size_t(reference.width) * reference.height;
    checkField("motion", motion.motion.size(), 2 * pixels, motion);
    checkField("depth", motion.depth.size(), pixels, motion);
    checkField("prev_depth_expected", motion.prev_depth_expected.size(), pixels, motion);
}

void checkSetting(const char* name, double value, bool ok) {
    if (!ok || !std::isfinite(value))
        throw std::invalid_argument(std::string("CrawlSettings: ") + name +
                                    " must be finite and >= 0, got " + std::to_string(value));
}

}  // namespace

CrawlTracker::CrawlTracker(CrawlSettings settings) : settings_(settings) {
    checkSetting("blur_sigma", settings_.blur_sigma, settings_.blur_sigma >= 0);
    checkSetting("margin", settings_.margin, settings_.margin >= 0);
    checkSetting("edge_threshold", settings_.edge_threshold, settings_.edge_threshold >= 0);
    checkSetting("disocclusion_tolerance", settings_.disocclusion_tolerance,
                 settings_.disocclusion_tolerance >= 0);
}

void CrawlTracker::reset() { previous_.reset(); }

void CrawlTracker::dropSpare() {
    // A copy of this tracker shares the state: its next add() may still read that frame.
    if (!previous_ || previous_.use_count() > 1) return;
    State::Frame& spare = previous_->frames[1 - previous_->current];
    std::vector<float>().swap(spare.reference_luma);
    std::vector<float>().swap(spare.variant_luma);
    std::vector<float>().swap(spare.depth);
}

CrawlFrame CrawlTracker::add(const Image& reference, const Image& variant, const MotionField& motion,
                             bool cut, bool want_map) {
    checkInputs(reference, variant, motion);
    return addInputs({&reference, nullptr, reference.width, reference.height},
                     {&variant, nullptr, variant.width, variant.height}, motion, cut, want_map);
}

CrawlFrame CrawlTracker::addRgba8(const uint8_t* reference_rgba, const uint8_t* variant_rgba,
                                  const MotionField& motion, bool cut, bool want_map) {
    if (!reference_rgba || !variant_rgba) throw std::invalid_argument("CrawlTracker::addRgba8: null pixel pointer");
    if (motion.width <= 0 || motion.height <= 0)
        throw std::invalid_argument("CrawlTracker::addRgba8: motion field is " +
                                    sizeText(motion.width, motion.height) + ", the images' size");
    const size_t pixels = size_t(motion.width) * motion.height;
    checkField("motion", motion.motion.size(), 2 * pixels, motion);
    checkField("depth", motion.depth.size(), pixels, motion);
    checkField("prev_depth_expected", motion.prev_depth_expected.size(), pixels, motion);
    return addInputs({nullptr, reference_rgba, motion.width, motion.height},
                     {nullptr, variant_rgba, motion.width, motion.height}, motion, cut, want_map);
}

CrawlFrame CrawlTracker::addInputs(const Input& reference, const Input& variant, const MotionField& motion,
                                   bool cut, bool want_map) {
    const int width = reference.width, height = reference.height;
    const bool chained = previous_ && !cut;
    // A new size mid-sequence has no pixel correspondence with the previous frame: the
    // caller has mixed sequences, which deserves a clear message, not a silent reset.
    if (chained) {
        const State::Frame& last = previous_->frames[previous_->current];
        if (last.width != width || last.height != height)
            throw std::invalid_argument("CrawlTracker::add: frame is " + sizeText(width, height) +
                                        ", the previous frame was " +
                                        sizeText(last.width, last.height) +
                                        " (pass cut = true or reset() between sequences)");
    }
    // Buffers are reused in place unless a copy of this tracker shares them.
    std::shared_ptr<State> state = previous_;
    if (!state)
        state = std::make_shared<State>();
    else if (state.use_count() > 2)
        state = std::make_shared<State>(*previous_);

    State::Frame& now = state->frames[1 - state->current];
    now.width = width;
    now.height = height;
    const size_t pixels = size_t(width) * height;
    now.reference_luma.resize(pixels);
    now.variant_luma.resize(pixels);

    // Step 1: luma of both images, blurred with sigma 1 so that bilinear warping (a
    // slight blur itself) does not read as change.
    if (!crawl_detail::blurLumaPair({reference.image, reference.rgba}, {variant.image, variant.rgba}, width, height,
                                    settings_.blur_sigma, now.reference_luma.data(), now.variant_luma.data()))
        throw std::invalid_argument(
            "CrawlTracker::add: reference or variant contains a NaN or infinite value");
    now.depth.assign(motion.depth.begin(), motion.depth.end());

    CrawlFrame frame;
    if (want_map) frame.crawl_map = Image{width, height, 1, detail::filledBuffer(pixels, 0.0)};
    // From here on the state is consistent: this frame is the one the next compares with.
    const int previous_index = state->current;
    state->current = 1 - state->current;
    previous_ = state;
    // A cut or the first frame: nothing to compare with; this frame starts the chain.
    if (!chained) return frame;
    frame.has_pair = true;
    const State::Frame& before = state->frames[previous_index];

    crawl_detail::CrawlPair pair;
    pair.width = width;
    pair.height = height;
    pair.reference_now = now.reference_luma.data();
    pair.variant_now = now.variant_luma.data();
    pair.reference_then = before.reference_luma.data();
    pair.variant_then = before.variant_luma.data();
    pair.depth_then = before.depth.data();
    pair.motion = &motion;
    pair.crawl_map = want_map ? frame.crawl_map->data.data() : nullptr;
    const crawl_detail::CrawlSums total = crawl_detail::scoreCrawlPair(pair, settings_);
    frame.numerator = total.numerator;
    frame.denominator = total.denominator;
    frame.valid_fraction = total.valid / double(pixels);
    if (total.denominator > 0) {
        frame.eci = std::sqrt(total.numerator / total.denominator);
        // Each scored pixel adds at least 1/255 here, so this is > 0.
        frame.flicker_ratio = total.flicker_variant / total.flicker_reference;
    } else {
        frame.no_edges = true;
    }
    return frame;
}

double pooledEci(const std::vector<CrawlFrame>& frames) {
    double numerator = 0, denominator = 0;
    for (const CrawlFrame& f : frames) {
        if (!f.has_pair) continue;
        numerator += f.numerator;
        denominator += f.denominator;
    }
    // Guarded like the per-frame value: a sequence without scored edges reports 0.
    if (!(denominator > 0) || !std::isfinite(numerator) || !std::isfinite(denominator)) return 0;
    return std::sqrt(numerator / denominator);
}

}  // namespace cbr::metrics
