// Layouts shared by the device scoring shaders (score_*.comp) and renderer/scoring: one definition.
#ifndef CBR_SHADERS_SCORE_SHARED_H
#define CBR_SHADERS_SCORE_SHARED_H

#ifdef __cplusplus
#include <cstdint>
namespace cbr::shaders {
using uint = uint32_t;
#endif

// Workgroups of the per-pixel passes are SCORE_GROUP x SCORE_GROUP; one partial-sum record per
// workgroup of the SSIM and crawl passes.
#define SCORE_GROUP 16
// FLIP's weighted quartiles are read off a histogram of the error over [0, 1]: bins of
// 1/16384 resolve them far inside the 1e-3 the suite asks (issue 32).
#define SCORE_HIST_BINS 16384
// Each error is added to its bin's sum in fixed point, 2^-24 a unit (two uints: low word, carry).
#define SCORE_HIST_SCALE 16777216.0
#define SCORE_MAGIC 0x53434F52u  // "SCOR"
#define SCORE_HEADER_WORDS 8u
#define SCORE_SSIM_WORDS 5u      // per workgroup: sum of squared byte differences, SSIM sums R, G, B, luma
#define SCORE_CRAWL_WORDS 5u     // per workgroup: numerator, flicker variant, flicker reference, edges, valid
#define SCORE_HIST_WORDS 3u      // per bin: count, sum (low word), sum (high word)
// Planes of the FLIP band buffer: YCxCz of both images, then seven horizontally filtered rows
// per image (kHY .. kHDD of metrics/flip.cpp).
#define SCORE_FLIP_YCC_PLANES 6
#define SCORE_FLIP_H_PLANES 14

// The settings and filter taps every pass reads, uploaded once (binding 3).
struct ScoreParams {
    int width, height, groups_x, groups_y;
    uint ssim_base, crawl_base, hist_base, pixels;   // word offsets into the result
    int ssim_taps;                                   // offset of the 11 SSIM taps in taps[]
    int blur_taps, blur_radius;                      // crawl blur (scipy truncate 4)
    int flip_colour_radius, flip_feature_radius;
    int flip_y, flip_cx, flip_cz1, flip_cz2, flip_g, flip_d, flip_dd;  // offsets in taps[]
    int margin;
    float edge_threshold2, tolerance, flicker_floor;
    float cmax, pccmax, lab_delta_cube, lab_slope, lab_offset, feature_scale;
    float white[3];
    float inv_white[3];
    float rgb_to_xyz[9];  // row-major
    float xyz_to_rgb[9];
    float srgb_to_linear[256];
};

// ScorePush::maps: score_crawl.comp writes |crawl| at every pixel (0 where not scored),
// score_ssim.comp the channel-mean SSIM (1 on the border), score_flip_v.comp the FLIP error.
#define SCORE_MAP_CRAWL 1
#define SCORE_MAP_SSIM 2
#define SCORE_MAP_FLIP 4

// Per dispatch: the rows it produces and the rows the band buffer holds.
struct ScorePush {
    int y0, y1;   // output rows [y0, y1)
    int r0, r1;   // band rows [r0, r1) (FLIP); 0, height otherwise
    int plane;    // floats per band plane
    int maps;     // SCORE_MAP_* bits: the per-pixel maps this frame's passes write
    int pad1, pad2;
};


// ColorVideoVDP (score_cvvdp_*.comp): a pyramid of CVVDP_PLANES float planes per level (test and
// reference of Y sustained, RG, YV, Y transient: plane 2c the test's, 2c + 1 the reference's
// channel c), levels 0 .. bands - 1, the last the baseband. Per band below the baseband, one
// partial-sum record of 4 floats (the channels' sums of D^beta) per 16x16 workgroup of the
// pooling pass; the baseband: one record.
#define CVVDP_MAX_BANDS 16
#define CVVDP_PLANES 8
#define CVVDP_SUM_WORDS 4u
#define CVVDP_CSF_N 32

struct CvvdpLevel {
    int w, h;
    uint offset;              // first float of the level's planes in the pyramid (planes w * h apart)
    uint groups_x, groups_y;  // 16x16 workgroups over w x h
    uint sums;                // word offset of the level's partial-sum records in the result
    int pad0, pad1;
};

// Binding 1 of the ColorVideoVDP passes: the model's figures (metrics::CvvdpModel and
// metrics::cvvdpParams(), converted once), followed by cdata[]: the temporal taps (taps_count x 4
// floats, oldest frame first) at taps_at and the CSF tables ([band][channel][CVVDP_CSF_N] log10
// sensitivities) at csf_at.
struct CvvdpShaderParams {
    int width, height, bands, channels;  // channels: 4, or 3 in image mode (the transient planes are 0)
    int taps_count, taps_at, csf_at, image;
    float mask_p, mask_c_gain, d_max_gain, sensitivity_gain;
    float t_int, beta, beta_tch, csf_log_l0;
    float csf_log_l1, jod_a10, jod_exp, jod_slope10;  // the map: jod_a / 10 q^jod_exp, jod_slope / 10 q at q <= 0.1
    // eps^p of the power function's exponents, as the CPU rounds them (powf(1e-5f, p)).
    float eps_mask_p, eps_beta, eps_beta_tch, eps_inv_beta_tch;
    float eps_mask_q[4];
    float mask_q[4];
    float xcm[16];  // xcm[k * 4 + c]: mask channel k's weight on channel c
    float ch_gain[4];
    float ch_weight[4];
    float baseband_weight[4];
    float pu[16];          // the 13-tap phase-uncertainty kernel
    float rgb_to_dkl[12];  // row-major 3x3
    float lum_lut[256];
    CvvdpLevel level[CVVDP_MAX_BANDS];
};

// Per ColorVideoVDP dispatch.
struct CvvdpPush {
    int band;    // the level the pass works on
    int head;    // the window's newest slot
    int filled;  // frames in the window since the sequence began (1 .. taps_count)
    int maps;    // SCORE_MAP_CVVDP: write the per-band maps and the difference map
};
#define SCORE_MAP_CVVDP 8

#ifdef __cplusplus
static_assert(sizeof(CvvdpLevel) == 32);
static_assert(sizeof(CvvdpShaderParams) == 4 * (28 + 4 + 16 + 12 + 16 + 12 + 256) + 32 * CVVDP_MAX_BANDS);
static_assert(sizeof(CvvdpPush) == 16);
static_assert(sizeof(ScoreParams) == 4 * (30 + 3 + 3 + 9 + 9 + 256));
static_assert(sizeof(ScorePush) == 32);
}  // namespace cbr::shaders
#endif

#endif
