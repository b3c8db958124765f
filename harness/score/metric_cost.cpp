// `cbrbench metric-cost` (metric_cost.h): the CPU scorer's metrics one by one, the device
// scorer's all four together.
#include "harness/score/metric_cost.h"

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "harness/base/exit_codes.h"
#include "harness/jobs/options.h"
#include "metrics/cost.h"
#include "renderer/scoring/device_cost.h"
#include "renderer/vk/context.h"
#include "settings/table.h"

namespace cbr::harness {

int runMetricCost(const MetricCostOptions& o) {
    const uint32_t w = o.res.width, h = o.res.height;
    checkFlipPpd(o.flip_ppd);
    if (!(o.fps > 0 && std::isfinite(o.fps)))
        throw std::invalid_argument("--fps " + std::to_string(o.fps) + ": expected a number > 0");
    settings::Tunables tune;
    settings::setText(*settings::find("display"), tune, o.display);
    tune.flip_ppd = o.flip_ppd;
    if (o.scorer != "device") {
        auto c = metrics::measureMetricCost(int(w), int(h), o.frames, settings::flipPpd(tune), tune.display, o.fps);
        std::printf("cpu scorer per %ux%u frame (median of %d, %d threads): psnr %.1f ms, ssim %.1f ms, "
                    "eci %.1f ms, flip %.1f ms, cvvdp %.1f ms (%g fps), total %.1f ms\n",
                    w, h, o.frames, c.threads, c.psnr_ms, c.ssim_ms, c.eci_ms, c.flip_ms, c.cvvdp_ms, o.fps,
                    c.psnr_ms + c.ssim_ms + c.eci_ms + c.flip_ms + c.cvvdp_ms);
    }
    if (o.scorer != "cpu") {
        vk::Context ctx({false, o.device});
        auto d = scoring::measureDeviceCost(ctx, w, h, o.frames, settings::flipPpd(tune), tune.display, o.fps);
        std::printf("device scorer per %ux%u frame (median of %d, %s): every metric (ColorVideoVDP at %g fps) "
                    "%.2f ms of GPU time, %.2f ms from recording to the figures on the host\n",
                    w, h, o.frames, ctx.description.name.c_str(), o.fps, d.gpu_ms, d.wall_ms);
    }
    return kExitDone;
}

}  // namespace cbr::harness
