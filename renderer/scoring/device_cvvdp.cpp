// ColorVideoVDP in the device scorer: plans the pyramid, converts the model's figures for the
// score_cvvdp_*.comp passes, records them over a chain's window, and pools their partial sums.
#include "renderer/scoring/device_cvvdp.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "renderer/scoring/device_passes.h"
#include "renderer/vk/context.h"
#include "shaders/score_cvvdp_band.comp.h"
#include "shaders/score_cvvdp_base.comp.h"
#include "shaders/score_cvvdp_channels.comp.h"
#include "shaders/score_cvvdp_expand.comp.h"
#include "shaders/score_cvvdp_pool.comp.h"
#include "shaders/score_cvvdp_reduce.comp.h"

namespace cbr::scoring::detail {
namespace {

constexpr int kCvvdpBindings = 6;  // score_cvvdp.glsl

// metrics/cvvdp.cpp's power function, for the pooling in the CPU's float steps.
float cvvdpPowF(float x, float p) { return std::pow(x + 1e-5f, p) - std::pow(1e-5f, p); }

}  // namespace

uint32_t DeviceCvvdp::plan(int width, int height, const metrics::DisplayModel& display, double fps,
                           uint32_t sums_base) {
    width_ = width;
    height_ = height;
    model_ = metrics::makeCvvdpModel(width, height, display, fps);
    window_ = model_.image ? 1 : model_.filterFrames();
    if (model_.bands > CVVDP_MAX_BANDS)
        throw std::invalid_argument("DeviceMetrics: ColorVideoVDP's " + std::to_string(model_.bands) +
                                    " bands exceed the device passes' " + std::to_string(CVVDP_MAX_BANDS));
    uint32_t sums = sums_base;
    for (int b = 0; b < model_.bands; ++b) {
        shaders::CvvdpLevel l{};
        l.w = model_.band_size[size_t(b)][0];
        l.h = model_.band_size[size_t(b)][1];
        l.offset = pyramid_floats_;
        l.groups_x = groupsFor(uint32_t(l.w));
        l.groups_y = groupsFor(uint32_t(l.h));
        l.sums = sums;
        pyramid_floats_ += CVVDP_PLANES * uint32_t(l.w * l.h);
        sums += (b == model_.bands - 1 ? 1u : l.groups_x * l.groups_y) * CVVDP_SUM_WORDS;
        levels_.push_back(l);
    }
    return sums;
}

// The model's figures for the passes, converted once (score_shared.h CvvdpShaderParams), then
// the temporal taps and the CSF tables.
std::vector<uint8_t> DeviceCvvdp::paramBytes() const {
    const metrics::CvvdpParams& mp = metrics::cvvdpParams();
    shaders::CvvdpShaderParams cp{};
    cp.width = width_;
    cp.height = height_;
    cp.bands = model_.bands;
    cp.channels = model_.channels;
    cp.taps_count = window_;
    cp.taps_at = 0;
    cp.csf_at = 4 * window_;
    cp.image = model_.image ? 1 : 0;
    cp.mask_p = mp.mask_p;
    cp.mask_c_gain = mp.mask_c_gain;
    cp.d_max_gain = mp.d_max_gain;
    cp.sensitivity_gain = mp.sensitivity_gain;
    cp.t_int = model_.image ? mp.image_int : 1.f;
    cp.beta = mp.beta;
    cp.beta_tch = mp.beta_tch;
    cp.csf_log_l0 = model_.csf_log_l0;
    cp.csf_log_l1 = model_.csf_log_l1;
    cp.jod_a10 = float(mp.jod_a / 10);
    cp.jod_exp = float(mp.jod_exp);
    cp.jod_slope10 = float(mp.jod_a * std::pow(0.1, mp.jod_exp - 1) / 10);
    auto epsPow = [](float p) { return std::pow(1e-5f, p); };
    cp.eps_mask_p = epsPow(mp.mask_p);
    cp.eps_beta = epsPow(mp.beta);
    cp.eps_beta_tch = epsPow(mp.beta_tch);
    cp.eps_inv_beta_tch = epsPow(1 / mp.beta_tch);
    for (int i = 0; i < 4; ++i) {
        cp.mask_q[i] = mp.mask_q[i];
        cp.eps_mask_q[i] = epsPow(mp.mask_q[i]);
        cp.ch_gain[i] = mp.ch_gain[i];
        cp.ch_weight[i] = mp.ch_weight[i];
        cp.baseband_weight[i] = mp.baseband_weight[i];
        for (int j = 0; j < 4; ++j) cp.xcm[i * 4 + j] = mp.xcm[i][j];
    }
    for (int i = 0; i < 13; ++i) cp.pu[i] = mp.pu_kernel[i];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) cp.rgb_to_dkl[3 * i + j] = model_.rgb_to_dkl[i][j];
    for (int v = 0; v < 256; ++v) cp.lum_lut[v] = model_.lum_lut[v];
    for (size_t b = 0; b < levels_.size(); ++b) cp.level[b] = levels_[b];
    // Image mode: one frame, each channel its DKL component (taps of 1), no transient (0).
    std::vector<float> cdata;
    if (model_.image) {
        cdata = {1.f, 1.f, 1.f, 0.f};
    } else {
        for (const auto& t : model_.taps) cdata.insert(cdata.end(), t.begin(), t.end());
    }
    for (int b = 0; b < model_.bands; ++b)
        for (int c = 0; c < 4; ++c) {
            const auto& table = model_.csf_log_s[size_t(b)][size_t(c)];
            cdata.insert(cdata.end(), table.begin(), table.end());
        }
    std::vector<uint8_t> cvvdp_bytes(sizeof(cp) + 4 * cdata.size());
    std::memcpy(cvvdp_bytes.data(), &cp, sizeof(cp));
    std::memcpy(cvvdp_bytes.data() + sizeof(cp), cdata.data(), 4 * cdata.size());
    return cvvdp_bytes;
}

void DeviceCvvdp::create(vk::Context& ctx) {
    const std::vector<uint8_t> cvvdp_bytes = paramBytes();
    params_ = vk::uploadBuffer(ctx, cvvdp_bytes.data(), cvvdp_bytes.size(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    pyramid_ = vk::createBuffer(ctx, pyramidBytes(), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    const std::vector<vk::Binding> cb = storageBindings(kCvvdpBindings);
    constexpr uint32_t cv_push = sizeof(shaders::CvvdpPush);
    auto cvvdpKernel = [&](const uint32_t* spirv, size_t bytes) {
        return vk::createComputeKernel(ctx, spirv, bytes, cb, cv_push);
    };
    channels_ = cvvdpKernel(kSpirv_score_cvvdp_channels_comp, sizeof(kSpirv_score_cvvdp_channels_comp));
    reduce_ = cvvdpKernel(kSpirv_score_cvvdp_reduce_comp, sizeof(kSpirv_score_cvvdp_reduce_comp));
    band_ = cvvdpKernel(kSpirv_score_cvvdp_band_comp, sizeof(kSpirv_score_cvvdp_band_comp));
    pool_ = cvvdpKernel(kSpirv_score_cvvdp_pool_comp, sizeof(kSpirv_score_cvvdp_pool_comp));
    base_ = cvvdpKernel(kSpirv_score_cvvdp_base_comp, sizeof(kSpirv_score_cvvdp_base_comp));
    expand_ = cvvdpKernel(kSpirv_score_cvvdp_expand_comp, sizeof(kSpirv_score_cvvdp_expand_comp));
}

void DeviceCvvdp::release(vk::Context& ctx) {
    for (vk::ComputeKernel* k : {&channels_, &reduce_, &band_, &pool_, &base_, &expand_})
        vk::destroyComputeKernel(ctx, *k);
    for (vk::Buffer* b : {&params_, &pyramid_}) vk::destroyBuffer(ctx, *b);
}

VkDescriptorSet DeviceCvvdp::createSet(vk::Context& ctx, VkDescriptorPool& pool, VkBuffer window_reference,
                                       VkBuffer window_test, VkBuffer result, VkBuffer map) const {
    const std::vector<vk::Binding> cb = storageBindings(kCvvdpBindings);
    pool = vk::createPool(ctx, cb, 1);
    const VkDescriptorSet set = vk::allocateSet(ctx, pool, channels_.set_layout);
    const VkBuffer cv[kCvvdpBindings] = {window_reference, window_test, params_.buffer, pyramid_.buffer, result, map};
    for (uint32_t i = 0; i < kCvvdpBindings; ++i)
        vk::writeBuffer(ctx, set, i, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, cv[i], 0, VK_WHOLE_SIZE);
    return set;
}

void DeviceCvvdp::dispatch(VkCommandBuffer cmd, const vk::ComputeKernel& kernel, VkDescriptorSet set, int band,
                           int head, int filled, int maps, uint32_t groups_x, uint32_t groups_y,
                           uint32_t groups_z) const {
    const shaders::CvvdpPush push{band, head, filled, maps};
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.layout, 0, 1, &set, 0, nullptr);
    vkCmdPushConstants(cmd, kernel.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, groups_x, groups_y, groups_z);
}

// ColorVideoVDP (metrics/cvvdp.cpp addRgba8): the temporal channels from the chain's window, the
// Gaussian pyramid, then band by band the contrast/CSF pass and the masking/pooling pass (the
// pooling of band b runs beside the contrast pass of band b + 1: they touch different levels),
// the baseband, and on request the difference map from the per-band maps.
void DeviceCvvdp::record(VkCommandBuffer cmd, VkDescriptorSet set, int head, int filled, int maps) const {
    const int last = model_.bands - 1;
    auto level = [&](int b) { return levels_[size_t(b)]; };
    auto stamp = [&](uint32_t i) {
        if (time_pool_) vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, time_pool_, time_first_ + i);
    };
    auto pass = [&](const vk::ComputeKernel& kernel, int band, uint32_t groups_x, uint32_t groups_y,
                    uint32_t groups_z = 1) {
        dispatch(cmd, kernel, set, band, head, filled, maps, groups_x, groups_y, groups_z);
    };
    stamp(0);
    pass(channels_, 0, level(0).groups_x, level(0).groups_y);
    computeBarrier(cmd);
    for (int b = 0; b < last; ++b) {
        pass(reduce_, b, level(b + 1).groups_x, level(b + 1).groups_y, CVVDP_PLANES);
        computeBarrier(cmd);
    }
    stamp(1);
    for (int b = 0; b < last; ++b) {
        pass(band_, b, level(b).groups_x, level(b).groups_y);
        computeBarrier(cmd);
        pass(pool_, b, level(b).groups_x, level(b).groups_y);
    }
    pass(base_, last, 1, 1);
    computeBarrier(cmd);
    stamp(2);
    if (maps & SCORE_MAP_CVVDP) {
        for (int b = last - 1; b >= 0; --b) {
            pass(expand_, b, level(b).groups_x, level(b).groups_y);
            computeBarrier(cmd);
        }
    }
    stamp(3);
}

std::vector<std::array<double, 4>> DeviceCvvdp::bands(const void* mapped_result) const {
    const auto* words = static_cast<const uint32_t*>(mapped_result);
    const metrics::CvvdpParams& p = metrics::cvvdpParams();
    std::vector<std::array<double, 4>> q(size_t(model_.bands));
    for (int b = 0; b < model_.bands; ++b) {
        const shaders::CvvdpLevel& l = levels_[size_t(b)];
        const uint32_t records = b == model_.bands - 1 ? 1u : l.groups_x * l.groups_y;
        const double n = double(l.w) * double(l.h);
        for (int c = 0; c < model_.channels; ++c) {
            double sum = 0;
            for (uint32_t g = 0; g < records; ++g) sum += wordFloat(words[l.sums + g * CVVDP_SUM_WORDS + uint32_t(c)]);
            q[size_t(b)][size_t(c)] = double(cvvdpPowF(float(sum / n), 1 / p.beta));
        }
    }
    return q;
}

// Each band's q per channel, pooled over bands and channels as CvvdpTracker::addRgba8 pools
// them (its float steps).
double DeviceCvvdp::q(const void* mapped_result) const {
    const metrics::CvvdpParams& p = metrics::cvvdpParams();
    const std::vector<std::array<double, 4>> per_band = bands(mapped_result);
    std::array<double, 4> sch{};
    for (int b = 0; b < model_.bands; ++b)
        for (int c = 0; c < model_.channels; ++c) {
            const float x = float(per_band[size_t(b)][size_t(c)]) * p.ch_weight[c] *
                            (b == model_.bands - 1 ? p.baseband_weight[c] : 1.f);
            sch[size_t(c)] += double(cvvdpPowF(x, p.beta_sch));
        }
    float tc = 0;
    for (int c = 0; c < model_.channels; ++c)
        tc += cvvdpPowF(cvvdpPowF(float(sch[size_t(c)]), 1 / p.beta_sch), p.beta_tch);
    return double(cvvdpPowF(tc, 1 / p.beta_tch));
}

}  // namespace cbr::scoring::detail
