// summary.csv's ordered columns (summary_csv.h).
#include "rundir/summary_csv.h"

namespace cbr::rundir::summary {

std::string passMedian(std::string_view pass) { return frames::passTime(pass) + "_median"; }

std::string statMean(std::string_view stat) { return std::string(stat) + "_mean"; }

const std::vector<std::string>& fixedColumns() {
    static const std::vector<std::string> cols = {
        kVariant,     kStatus,        kFrames,       kRepeats,      kRenderWidth,    kRenderHeight,
        kGpuMsMedian, kGpuMsP5,       kGpuMsP95,     kGpuMsP99,     kGpuMsMean,      kGpuMsCv,
        kSpeedup,     kSpeedupLow,    kSpeedupHigh,  kPsnrDbMean,   kPsnrDbMin,      kPsnrDbP5,
        kSsimMean,    kSsimMin,       kSsimLumaMean, kFlipMean,     kCvvdpJod,       kEci,
        kEciP95,      kEciMax,        kFlickerRatioMean, kFsInvocationsMedian, kNote};
    return cols;
}

std::vector<std::string> columns(const std::vector<std::string>& passes, const std::vector<std::string>& stats) {
    std::vector<std::string> cols = fixedColumns();
    for (const auto& p : passes) cols.push_back(passMedian(p));
    for (const auto& s : stats) cols.push_back(statMean(s));
    return cols;
}

const std::vector<std::string>& sequenceColumns() {
    static const std::vector<std::string> cols = {
        kVariant,  kStatus,  kFrames,   kRepeats,  kWidth,        kHeight,  kPsnrDbMean,
        kPsnrDbMin, kPsnrDbP5, kSsimMean, kSsimMin, kSsimLumaMean, kFlipMean, kCvvdpJod,
        kEci,      kEciP95,  kEciMax,   kFlickerRatioMean, kNote};
    return cols;
}

}  // namespace cbr::rundir::summary
