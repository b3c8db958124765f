// The tunables of a run, typed: what settings/table.cpp's rows read and write. Words the user
// types become these enums once, while the command line is parsed (settings/options.h).
#pragma once

#include "metrics/cvvdp.h"
#include "metrics/flip.h"

namespace cbr::settings {

// Each enum's values are in the order of its row's words (settings/table.cpp).
enum class DrrFilter { Bilinear, CatmullRom };
enum class CbrRoute { Auto, MsaaJitter, MsaaLocations, Multiview, Layers };
// The checkerboard resolve's history: frame N-1's quarter-res samples (the paper's), or the
// previous resolved full-res frame, clipped.
enum class CbrHistory { Quarter, Full };
enum class HistoryFilter { CatmullRom, Bilinear };  // the full history's read
// How the full history stores the previous resolved frame: B10G11R11, 4 bytes a pixel (6- and
// 5-bit mantissas), where the device can store that format, else RGBA16F; or RGBA16F, 8 bytes.
// At 4K the full history's extra cost is mostly these bytes (docs/method/full-history.md).
enum class HistoryFormat { B10g11r11, Rgba16f };
enum class CsoMode { Relative, Absolute };  // relative: to the mean neighbour depth
// How the full-resolution passes after the scene run: the checkerboard reconstruction and the
// drr upscale, with or without the tone map folded in.
enum class ResolveImpl {
    Fused,      // the tiled resolve or upscale writes the display image: `cbr_resolve_tonemap`, `upscale_tonemap`
    Separate,   // the tiled passes write linear colour, then `tonemap` (to measure the fusion)
    Reference,  // the pre-issue-14 passes (cbr_resolve_reference.glsl, upscale_reference.comp, `tonemap`,
                // the class map every frame, motion written for every sample): the images the tiled
                // passes must reproduce, and the "before" of their measurements
};
// How scene passes clear their colour targets: the attachment's load op, or a compute pass
// that stores the clear value (renderer/passes/target_clear.h says why and when).
enum class TargetClear { Auto, LoadOp, Compute };
enum class DebugShading { None, PixelId };  // pixel-id: colours encode the full-res pixel each sample lands on
enum class Reference { Full, Ssaa };        // what variants are scored against
enum class Scorer { Auto, Device, Cpu };    // where quality frames are scored

// One field per row of the table, with the row's default.
struct Tunables {
    int shading_cost = 1;        // >= 1; the fragment work is about K times, the image the same
    double exposure = 1.0;
    double drr_scale = 0.7071;   // per axis: half the pixels
    DrrFilter drr_filter = DrrFilter::CatmullRom;
    double drr_target_ms = 0;    // dynamic resolution's target frame time; 0: fixed scale
    double taau_scale = 0.7071;  // taau: per-axis render scale, Halton(2,3) jitter phases, history blend weight
    int taau_phases = 8;
    double taau_blend = 0.1;
    double taau_lod_offset = 0;  // added to taau's texture LOD bias, log2(render width / output width)
    double cso_tolerance = 0.05;
    CsoMode cso_mode = CsoMode::Relative;
    double cbr_lod_bias = -1.0;  // matches full-res derivatives (chosen by a sweep: docs/history); the paper: -0.5
    CbrRoute cbr_route = CbrRoute::Auto;
    CbrHistory cbr_history = CbrHistory::Quarter;
    HistoryFilter history_filter = HistoryFilter::CatmullRom;
    HistoryFormat history_format = HistoryFormat::B10g11r11;
    ResolveImpl resolve_impl = ResolveImpl::Fused;
    TargetClear target_clear = TargetClear::Auto;
    DebugShading debug_shading = DebugShading::None;
    Reference reference = Reference::Full;
    int ssaa = 4;                // k x k samples per pixel of the ssaa reference
    // How the frames are seen (ColorVideoVDP's display model); its pixels per degree are FLIP's too
    // unless flip_ppd is given.
    metrics::DisplayModel display;
    double flip_ppd = 0;  // FLIP's observer: pixels per degree of visual angle; 0: the display's
    Scorer scorer = Scorer::Auto;
};

// FLIP's pixels per degree: flip_ppd where given, else the display model's.
inline double flipPpd(const Tunables& t) { return t.flip_ppd > 0 ? t.flip_ppd : t.display.ppd(); }

}  // namespace cbr::settings
