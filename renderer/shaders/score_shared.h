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

#ifdef __cplusplus
static_assert(sizeof(ScoreParams) == 4 * (30 + 3 + 3 + 9 + 9 + 256));
static_assert(sizeof(ScorePush) == 32);
}  // namespace cbr::shaders
#endif

#endif
