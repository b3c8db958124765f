// frames.csv's ordered columns (frames_csv.h).
#include "rundir/frames_csv.h"

namespace cbr::rundir::frames {

std::string passTime(std::string_view pass) { return std::string(kPassTimePrefix) + std::string(pass); }

std::string passInvocations(std::string_view pass) { return std::string(kFsInvocations) + "_" + std::string(pass); }

std::string passOfColumn(std::string_view column) {
    if (column.size() <= kPassTimePrefix.size() || column.substr(0, kPassTimePrefix.size()) != kPassTimePrefix) return {};
    return std::string(column.substr(kPassTimePrefix.size()));
}

const std::vector<std::string>& fixedColumns() {
    static const std::vector<std::string> cols = {
        kVariant,  kRepeat,        kFrame,   kTimeS,    kWidth,         kHeight,
        kRenderWidth, kRenderHeight, kRenderScale, kGpuMs, kTimingOk,    kPsnrDb,
        kSsim,     kSsimLuma,      kMse,     kEci,      kFlickerRatio,  kCrawlValidFraction,
        kFlipMean, kFlipQ1,        kFlipMedian, kFlipQ3, kCvvdpJod,     kFsInvocations,
        kStatus,   kNote};
    return cols;
}

std::vector<std::string> columns(const std::vector<std::string>& stats, const std::vector<std::string>& passes,
                                 const std::set<std::string>& passes_with_invocations) {
    std::vector<std::string> cols = fixedColumns();
    cols.insert(cols.end(), stats.begin(), stats.end());
    for (const auto& p : passes) cols.push_back(passTime(p));
    // Invocation columns only for passes that report them (graphics passes, where the device
    // has pipeline statistics).
    for (const auto& p : passes)
        if (passes_with_invocations.count(p)) cols.push_back(passInvocations(p));
    return cols;
}

const std::vector<std::string>& sequenceColumns() {
    static const std::vector<std::string> cols = {
        kVariant,   kRepeat,     kFrame,       kFrameNumber, kReferenceFile, kTestFile,    kPsnrDb,
        kMse,       kSsim,       kSsimLuma,    kFlipMean,    kFlipQ1,        kFlipMedian,  kFlipQ3,
        kCvvdpJod,  kEci,        kFlickerRatio, kCrawlValidFraction, kMotion, kShiftDx,    kShiftDy,
        kShiftResponse, kGlobalShiftRejected, kCut, kNote};
    return cols;
}

}  // namespace cbr::rundir::frames
