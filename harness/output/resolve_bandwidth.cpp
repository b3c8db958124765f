// run.json's resolve_bandwidth: the checkerboard resolve's effective bandwidth (issue 14).
#include "harness/output/resolve_bandwidth.h"

#include <string>

#include "rundir/run_json_variants.h"
namespace cbr::harness {

// run.json's resolve_bandwidth of a checkerboard variant: the bytes its resolve must move
// (renderer/passes/cbrResolveBytes) over the pass's median time, against the copy probe.
void resolveBandwidth(nlohmann::json& v, const VariantSummary& sm, const vk::CopyBandwidth& copy) {
    namespace k = rundir::run::variant;
    namespace rb = k::resolve_bandwidth;
    auto bytes_it = v.find(k::kResolveBytesPerFrame);
    if (bytes_it == v.end()) return;
    double bytes = std::stod(bytes_it->get<std::string>());
    for (const auto& [name, ms] : sm.pass_ms_median) {
        if (name != "cbr_resolve" && name != "cbr_resolve_tonemap") continue;
        double gb_per_s = ms > 0 ? bytes / (ms * 1e-3) * 1e-9 : 0.0;
        v[k::kResolveBandwidth] = {{rb::kPass, name},
                                   {rb::kMbPerFrame, bytes * 1e-6},
                                   {rb::kPassMsMedian, ms},
                                   {rb::kGbPerS, gb_per_s},
                                   {rb::kDeviceCopyGbPerS, copy.gb_per_s},
                                   {rb::kFractionOfCopy, copy.gb_per_s > 0 ? gb_per_s / copy.gb_per_s : 0.0},
                                   {rb::kRule, "frame N's samples (colour, depth, motion; SRT and CFB in deferred) and "
                                            "frame N-1's once each, plus the written image, at their formats"}};
    }
}

}  // namespace cbr::harness
