// `cbrbench stress`'s cases and their expectations (stress_cases.h).
#include "harness/stress/stress_cases.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "camera_paths/path.h"
#include "harness/jobs/builtin_context.h"
#include "metrics/image_io.h"
#include "renderer/scene/scene.h"
#include "renderer/variants/variants.h"
#include "rundir/pixel_classes.h"
#include "rundir/run_json.h"
#include "rundir/summary_csv.h"

namespace cbr::harness::stress {
namespace {

// Every case runs every variant of the table; the checkerboard expectations apply to the
// checkerboard variants.
std::vector<std::string> variantsWhere(bool (*keep)(const variants::Variant&)) {
    std::vector<std::string> out;
    for (const auto& v : variants::allVariants())
        if (keep(v)) out.emplace_back(v.name);
    return out;
}
const std::vector<std::string> kVariants = variantsWhere([](const variants::Variant&) { return true; });
const std::vector<std::string> kCbr = variantsWhere([](const variants::Variant& v) { return v.checkerboard; });
// Whether a checkerboard variant keeps the full-res history at the suite's settings (the
// default quarter history for the others): it has no pixels missing by parity, and a
// still camera converges to its storage's rounding (B10G11R11), not to full's image.
bool fullHistory(const std::string& name) { return variants::findVariant(name).full_history; }
// The scaled variant the checkerboard ones are matched with at equal cost (drr).
std::string scaledBaseline() { return std::string(variants::findVariant(kCbr.front()).equal_cost_with); }


// Quality of the run's variants against full, as sequence PSNR.
std::string qualityLine(const Child& c) {
    std::string s;
    for (const auto& v : kVariants)
        if (v != variants::referenceVariant().name) s += (s.empty() ? "" : ", ") + v + " " + db(summaryValue(c, v, rundir::summary::kPsnrDbMean)) + " dB";
    return s;
}

// The shared finiteness verdict of all children of a case.
Verdict base(Children& ch) {
    Verdict v;
    for (auto& [key, c] : ch) {
        std::string why;
        if (!finiteAndOk(*c, why)) {
            v.finite = false;
            v.detail += key + ": " + why + "; ";
        }
    }
    return v;
}

// Same images (per variant) as the baseline run, to `min_db`, and the same class shares.
Verdict sameAsBase(Children& ch, const std::string& other, double min_db, double share_tol,
                   const std::string& base_key = "base") {
    Verdict v = base(ch);
    if (!v.finite) return v;
    Child& a = *ch.at(base_key);
    Child& b = *ch.at(other);
    v.held = true;
    for (const auto& var : kVariants) {
        auto p = imagePsnr(a, b, var);
        v.detail += var + " " + db(p) + " dB; ";
        if (!p || *p < min_db) v.held = false;
    }
    double worst = 0;
    for (const auto& var : kCbr)
        for (const char* pixels : {rundir::pixels::kReused, rundir::pixels::kOccluded, rundir::pixels::kMissingParity}) {
            const std::string cls = rundir::summary::statMean(pixels);
            auto x = summaryValue(a, var, cls), y = summaryValue(b, var, cls);
            if (x && y) worst = std::max(worst, std::abs(*x - *y));
        }
    v.detail += "class shares differ by at most " + num(worst, 4);
    if (worst > share_tol) v.held = false;
    v.quality = qualityLine(b);
    return v;
}


}  // namespace

std::string caseVariants() {
    std::string every;
    for (const auto& v : kVariants) every += (every.empty() ? "" : ",") + v;
    return every;
}
namespace {

// The inputs the cases read, written once: camera paths and glTF files.
struct Inputs {
    double fov = 60.0;
    int n_sub = 0, n_cancel = 0;  // frames of the sub-pixel and parity-cancelling paths
    fs::path sub, cancel, turn, cut;
    fs::path bad_normals, infinites, zero_area, no_texture, bright, dim;
    fs::path blocks_near, blocks_far, pan_near, pan_far;
};

std::vector<std::string> plus(std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

const std::vector<std::string> kFly = {"--scene", "atrium", "--path", "flythrough", "--frames", "8"};

Inputs writeInputs(const fs::path& paths_dir, const StressOptions& o, uint32_t w, uint32_t h) {
    Inputs in;
    // Poses from the atrium flythrough's start: inside the scene, looking down the aisle.
    scene::Scene atrium = scene::buildProcedural("atrium");
    const paths::BuiltinContext bctx = builtinContext(atrium, "flythrough", int(w), int(h));
    paths::CameraPose p0 = paths::samplePose(paths::builtinPath("flythrough", bctx), 0.0);
    auto yaw = [](double rad) { return glm::angleAxis(rad, glm::dvec3(0, 1, 0)); };
    const glm::dquat q0 = p0.orientation;

    // Sub-pixel motion: a yaw pan moving the screen centre 0.01 px per frame.
    const double fov = in.fov, f_px = (h / 2.0) / std::tan(glm::radians(fov) / 2);
    const int n_sub = in.n_sub = o.subpixel_frames;
    const double d_sub = std::atan(0.01 / f_px);
    in.sub = writePath(paths_dir, "subpixel-0.01px", fov,
                             {{0, p0.position, q0, false}, {n_sub - 1, p0.position, q0 * yaw(d_sub * (n_sub - 1)), false}});
    // Jitter-cancelling motion: 1 px per frame with a 10-degree field of view (within 0.8%
    // of 1 px across the frame), so last frame's samples land on this frame's parity.
    const double fov_narrow = 10.0, f_narrow = (h / 2.0) / std::tan(glm::radians(fov_narrow) / 2);
    const int n_cancel = in.n_cancel = 24;
    in.cancel = writePath(paths_dir, "parity-cancel-1px", fov_narrow,
                                {{0, p0.position, q0, false},
                                 {n_cancel - 1, p0.position, q0 * yaw(std::atan(1.0 / f_narrow) * (n_cancel - 1)), false}});
    // 180 degrees between frames 10 and 11, still before and after; and the same with a cut.
    auto turnPath = [&](const std::string& name, bool cut) {
        return writePath(paths_dir, name, fov,
                         {{0, p0.position, q0, false}, {10, p0.position, q0, false},
                          {11, p0.position, q0 * yaw(glm::pi<double>()), cut},
                          {21, p0.position, q0 * yaw(glm::pi<double>()), false}});
    };
    in.turn = turnPath("turn-180", false);
    in.cut = turnPath("cut-180", true);
    // Debian's assimp-testmodels; CBR_ASSIMP_MODELS points elsewhere (a GPU host without it).
    const char* models_env = std::getenv("CBR_ASSIMP_MODELS");
    const fs::path models = models_env && *models_env ? fs::path(models_env) : fs::path("/usr/share/assimp/models");
    in.bad_normals = models / "glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb";
    in.infinites = models / "glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb";
    in.zero_area = writeDegenerateGltf(paths_dir, "zero-area-triangle", false);
    in.no_texture = writeDegenerateGltf(paths_dir, "missing-texture", true);
    in.bright = writeDegenerateGltf(paths_dir, "emissive-1e4", false, {{"strength", 1e4}});
    in.dim = writeDegenerateGltf(paths_dir, "emissive-1e-6", false, {{"factor", {1e-6, 1e-6, 1e-6}}});

    // Vertices baked 1e6 from the origin (survey or georeferenced data) against the same
    // file near the origin, seen from the same camera path moved with them: a slow pan and
    // dolly past 1/16-wide poles, so a camera-dependent rounding of positions shows as
    // crawl. Both sets of coordinates are exact floats (writeBlocksGltf).
    const glm::dquat look = glm::angleAxis(-0.2, glm::dvec3(1, 0, 0));
    const glm::dvec3 cam0(-1.3, 1.6, 4.1), cam1(1.1, 1.9, 3.3), far(1e6);
    in.blocks_near = writeBlocksGltf(paths_dir, "blocks-near-origin", glm::dvec3(0));
    in.blocks_far = writeBlocksGltf(paths_dir, "blocks-baked-at-1e6", far);
    in.pan_near = writePath(paths_dir, "blocks-pan", fov, {{0, cam0, look, false}, {39, cam1, look, false}});
    in.pan_far = writePath(paths_dir, "blocks-pan-at-1e6", fov,
                                 {{0, cam0 + far, look, false}, {39, cam1 + far, look, false}});
    return in;
}

// Far from the origin, extreme clip planes, tiny and huge units: the same images.
void addPrecisionCases(std::vector<Case>& cases, const Inputs& in) {
    cases.push_back({"extreme-planes", "near 1e-4 / far 1e7: images >= 40 dB of default planes, class shares within 0.01",
                     {{"base", kFly}, {"planes", plus(kFly, {"--near", "1e-4", "--far", "1e7"})}},
                     [](Children& c) { return sameAsBase(c, "planes", 40, 0.01); }});
    cases.push_back({"far-from-origin", "scene and path moved by (1e6, 1e6, 1e6): the same images (>= 60 dB), same class shares",
                     {{"base", kFly}, {"offset", plus(kFly, {"--scene-offset", "1e6,1e6,1e6"})}},
                     [](Children& c) { return sameAsBase(c, "offset", 60, 0.001); }});
    cases.push_back({"far-baked-vertices",
                     "a glTF whose vertex positions are baked at (1e6, 1e6, 1e6), camera path moved with it: the same "
                     "images as the file near the origin (>= 60 dB), same class shares",
                     {{"near", {"--scene", in.blocks_near.string(), "--path", in.pan_near.string(), "--frames", "40"}},
                      {"baked", {"--scene", in.blocks_far.string(), "--path", in.pan_far.string(), "--frames", "40"}}},
                     [](Children& c) { return sameAsBase(c, "baked", 60, 0.001, "near"); }});
    cases.push_back({"tiny-scene", "millimetre units (scale 0.001, planes scaled): images >= 40 dB of unscaled, shares within 0.01",
                     {{"base", kFly}, {"mm", plus(kFly, {"--scene-scale", "0.001"})}},
                     [](Children& c) { return sameAsBase(c, "mm", 40, 0.01); }});
    cases.push_back({"huge-scene", "kilometre units (scale 1000): images >= 40 dB of unscaled, shares within 0.01",
                     {{"base", kFly}, {"km", plus(kFly, {"--scene-scale", "1000"})}},
                     [](Children& c) { return sameAsBase(c, "km", 40, 0.01); }});
}

// Motion the reconstruction must survive: sub-pixel drift, motion that cancels the jitter.
void addMotionCases(std::vector<Case>& cases, const Inputs& in) {
    cases.push_back(
        {"subpixel-motion", "0.01 px per frame for " + std::to_string(in.n_sub) +
                                " frames: checkerboard PSNR of the last 50 frames within 0.5 dB of frames 1-50 (no drift)",
         {{"subpixel", {"--scene", "atrium", "--path", in.sub.string(), "--frames", std::to_string(in.n_sub)}}},
         [](Children& c) {
             Verdict v = base(c);
             if (!v.finite) return v;
             const Child& r = *c.at("subpixel");
             v.held = true;
             for (const auto& var : kCbr) {
                 auto s = frameSeries(r, var, rundir::frames::kPsnrDb);
                 if (s.size() < 101) return v.held = false, v.detail = "too few frames", v;
                 double early = 0, late = 0;
                 for (size_t i = 1; i <= 50; ++i) early += s[i] / 50;
                 for (size_t i = s.size() - 50; i < s.size(); ++i) late += s[i] / 50;
                 v.detail += var + " frames 1-50 " + db(early) + " dB, last 50 " + db(late) + " dB; ";
                 if (!(late >= early - 0.5)) v.held = false;
             }
             v.quality = qualityLine(r);
             return v;
         }});
    cases.push_back({"parity-cancelling-motion",
                     "1 px per frame, cancelling the jitter: with the quarter history most pixels missing by parity, "
                     "reconstructed spatially; finite, PSNR >= 12 dB, SSIM >= 0.3 (no garbage)",
                     {{"cancel", {"--scene", "atrium", "--path", in.cancel.string(), "--frames", std::to_string(in.n_cancel)}}},
                     [](Children& c) {
                         Verdict v = base(c);
                         if (!v.finite) return v;
                         const Child& r = *c.at("cancel");
                         v.held = true;
                         for (const auto& var : kCbr) {
                             auto miss = summaryValue(r, var, rundir::summary::statMean(rundir::pixels::kMissingParity));
                             auto reused = summaryValue(r, var, rundir::summary::statMean(rundir::pixels::kReused));
                             auto psnr = summaryValue(r, var, rundir::summary::kPsnrDbMean);
                             auto ssim = summaryValue(r, var, rundir::summary::kSsimMean);
                             v.detail += var + " missing by parity " + num(miss) + ", reused " + num(reused) + ", " +
                                         db(psnr) + " dB, SSIM " + num(ssim) + "; ";
                             const bool parity_holes = !fullHistory(var);  // a full-res history has none
                             if (!miss || (parity_holes && *miss < 0.3) || !psnr || *psnr < 12 || !ssim || *ssim < 0.3)
                                 v.held = false;
                         }
                         v.quality = qualityLine(r);
                         return v;
                     }});
}

// History that must be dropped: a turn, a cut.
void addHistoryCases(std::vector<Case>& cases, const Inputs& in) {
    auto frame11 = [](const Child& r, const std::string& var, const char* col) { return frameValue(r, var, 11, col); };
    cases.push_back(
        {"180-degree-turn",
         "a 180-degree turn in one frame: the next frame reuses nothing (< 1%) and matches a history reset at the "
         "same pose (PSNR within 0.5 dB)",
         {{"turn", {"--scene", "atrium", "--path", in.turn.string(), "--frames", "22"}},
          {"cut", {"--scene", "atrium", "--path", in.cut.string(), "--frames", "22"}}},
         [frame11](Children& c) {
             Verdict v = base(c);
             if (!v.finite) return v;
             v.held = true;
             for (const auto& var : kCbr) {
                 auto reused = frame11(*c.at("turn"), var, rundir::pixels::kReused);
                 auto pt = frame11(*c.at("turn"), var, rundir::frames::kPsnrDb), pc = frame11(*c.at("cut"), var, rundir::frames::kPsnrDb);
                 v.detail += var + " frame 11 reused " + num(reused) + ", " + db(pt) + " dB vs " + db(pc) + " dB after a cut; ";
                 if (!reused || *reused > 0.01 || !pt || !pc || std::abs(*pt - *pc) > 0.5) v.held = false;
             }
             v.quality = qualityLine(*c.at("turn"));
             return v;
         }});
    cases.push_back(
        {"camera-cut", "a cut: history resets on the cut frame (reset share >= 40%, nothing reused), no smear from the "
                       "old shot (PSNR within 3 dB of the first frame's, the other reset, or of the run's median)",
         {{"cut", {"--scene", "atrium", "--path", in.cut.string(), "--frames", "22"}}},
         [frame11](Children& c) {
             Verdict v = base(c);
             if (!v.finite) return v;
             const Child& r = *c.at("cut");
             v.held = true;
             for (const auto& var : kCbr) {
                 auto reset = frame11(r, var, rundir::pixels::kReset), reused = frame11(r, var, rundir::pixels::kReused);
                 auto p = frame11(r, var, rundir::frames::kPsnrDb);
                 auto s = frameSeries(r, var, rundir::frames::kPsnrDb);
                 // The first frame is the other reset (spatial fill only): a cut frame without
                 // smear is as good as it. With LOD bias -1 the reconstructed frames gained more
                 // than reset frames do (atrium: cut 25.5 dB, median 29.1), so the median alone
                 // no longer measures smear.
                 double first = s.empty() ? 0 : s.front();
                 std::sort(s.begin(), s.end());
                 double med = s.empty() ? 0 : s[s.size() / 2];
                 v.detail += var + " cut frame reset " + num(reset) + ", reused " + num(reused) + ", " + db(p) +
                             " dB (first frame " + db(first) + ", median " + db(med) + "); ";
                 if (!reset || *reset < 0.4 || !reused || *reused > 0.001 || !p || *p < std::min(first, med) - 3)
                     v.held = false;
             }
             v.quality = qualityLine(r);
             return v;
         }});
}

// A still camera: the history is kept forever, and must neither drift nor differ from full.
void addStaticCameraCase(std::vector<Case>& cases, const StressOptions& o) {
    cases.push_back(
        {"static-camera", "static camera for " + std::to_string(o.static_frames) +
                              " frames, untextured scene: checkerboard identical to full (>= 60 dB) on every frame after the "
                              "first; with a full-res history (B10G11R11) within its rounding (>= 38 dB) and no drift (the "
                              "last 50 frames' worst within 0.1 dB of the first 50's)",
         {{"static", {"--scene", "blocks", "--path", "static", "--frames", std::to_string(o.static_frames), "--no-save"}}},
         [](Children& c) {
             Verdict v = base(c);
             if (!v.finite) return v;
             const Child& r = *c.at("static");
             v.held = true;
             for (const auto& var : kCbr) {
                 auto s = frameSeries(r, var, rundir::frames::kPsnrDb);
                 // Drift: the worst of the first k frames after the first against the last k's.
                 const size_t k = std::min<size_t>(50, s.size() / 2);
                 double worst = INFINITY, early = INFINITY, late = INFINITY;
                 for (size_t i = 1; i < s.size(); ++i) {
                     worst = std::min(worst, s[i]);
                     if (i <= k) early = std::min(early, s[i]);
                     if (i + k >= s.size()) late = std::min(late, s[i]);
                 }
                 v.detail += var + " worst of frames 1-" + std::to_string(s.size() - 1) + ": " + db(worst) + " dB";
                 if (s.size() < 2) v.held = false;
                 if (fullHistory(var)) {
                     v.detail += " (first " + std::to_string(k) + " " + db(early) + ", last " + std::to_string(k) + " " +
                                 db(late) + ")";
                     if (worst < 38 || !(late >= early - 0.1)) v.held = false;
                 } else if (worst < 60) {
                     v.held = false;
                 }
                 v.detail += "; ";
             }
             v.quality = qualityLine(r);
             return v;
         }});
}

// A constant image (all black, all white): every variant identical to full, and every
// frame pair flagged as having no reference edges rather than divided by zero.
std::function<Verdict(Children&)> constantImageCheck(const char* key) {
    return [key](Children& c) {
        Verdict v = base(c);
        if (!v.finite) return v;
        const Child& r = *c.at(key);
        v.held = true;
        int flagged = 0, frames = 0;
        for (const auto& var : kVariants) {
            auto p = summaryValue(r, var, rundir::summary::kPsnrDbMean), s = summaryValue(r, var, rundir::summary::kSsimMean),
                 e = summaryValue(r, var, rundir::summary::kEci);
            if (!p || !std::isinf(*p) || !s || *s != 1.0 || !e || *e != 0.0) v.held = false;
            v.detail += var + " PSNR " + db(p) + ", SSIM " + num(s) + ", ECI " + num(e) + "; ";
        }
        for (size_t i = 0; i < r.frames.size(); ++i)
            if (r.frames.num(i, rundir::frames::kFrame).value_or(0) > 0 && r.frames.text(i, rundir::frames::kVariant) != variants::referenceVariant().name) {
                ++frames;
                flagged += r.frames.text(i, rundir::frames::kNote).find("no reference edges") != std::string::npos;
            }
        v.detail += std::to_string(flagged) + " of " + std::to_string(frames) + " frame pairs flagged 'no edges'";
        if (flagged != frames) v.held = false;
        v.quality = "every variant identical to full";
        return v;
    };
}

// Thin geometry and the extremes of the image: black, white, emitters, exposure.
void addImageCases(std::vector<Case>& cases, const Inputs& in) {
    cases.push_back({"thin-geometry-and-foliage",
                     "atrium's 1 cm cables, chain-link fence and alpha-tested foliage: finite; checkerboard crawls less "
                     "than drr (ECI)",
                     {{"base", kFly}},
                     [](Children& c) {
                         Verdict v = base(c);
                         if (!v.finite) return v;
                         const Child& r = *c.at("base");
                         const std::string scaled = scaledBaseline();
                         auto drr = summaryValue(r, scaled, rundir::summary::kEci);
                         v.held = bool(drr);
                         for (const auto& var : kCbr) {
                             auto e = summaryValue(r, var, rundir::summary::kEci);
                             v.detail += var + " ECI " + num(e, 4) + "; ";
                             if (!e || !drr || *e > *drr) v.held = false;
                         }
                         v.detail += scaled + " ECI " + num(drr, 4);
                         v.quality = qualityLine(r);
                         return v;
                     }});
    const std::vector<std::string> blocks = {"--scene", "blocks", "--path", "orbit", "--frames", "6"};
    cases.push_back({"black-frames", "exposure 1e-12 (all black): PSNR inf, SSIM 1, ECI 0 flagged 'no edges'; no 0/0",
                     {{"black", plus(blocks, {"--exposure", "1e-12"})}}, constantImageCheck("black")});
    cases.push_back({"white-frames", "exposure 1e12 (all white): PSNR inf, SSIM 1, ECI 0 flagged 'no edges'; no 0/0",
                     {{"white", plus(blocks, {"--exposure", "1e12"})}}, constantImageCheck("white")});
    cases.push_back({"emissive-extremes",
                     "a glTF emitter of strength 1e4 (KHR_materials_emissive_strength) and one of 1e-6 through the "
                     "tone map: finite output, every variant ran, the bright one saturates to white",
                     {{"emit-high", {"--scene", in.bright.string(), "--path", "orbit", "--frames", "4"}},
                      {"emit-low", {"--scene", in.dim.string(), "--path", "orbit", "--frames", "4"}}},
                     [](Children& c) {
                         Verdict v = base(c);
                         v.held = v.finite;
                         if (!v.finite) return v;
                         // The 1e4 emitter's pixels: pure white in full's saved frame.
                         auto img = metrics::readPng(c.at("emit-high")->dir / "frames" /
                                                   (std::string(variants::referenceVariant().name) + "_0000.png"));
                         size_t white = 0;
                         for (size_t i = 0; i + 3 < img.pixels.size(); i += 4)
                             white += img.pixels[i] == 255 && img.pixels[i + 1] == 255 && img.pixels[i + 2] == 255;
                         v.detail = std::to_string(white) + " white pixels from the 1e4 emitter; " +
                                    "1e4: " + qualityLine(*c.at("emit-high")) + "; 1e-6: " + qualityLine(*c.at("emit-low"));
                         v.quality = v.detail;
                         if (white == 0) v.held = false;
                         return v;
                     }});
    cases.push_back({"exposure-extremes",
                     "radiance scaled by 1e4 and by 1e-6 (exposure) through the tone map: finite output, every variant ran",
                     {{"hdr-high", plus(kFly, {"--exposure", "1e4"})}, {"hdr-low", plus(kFly, {"--exposure", "1e-6"})}},
                     [](Children& c) {
                         Verdict v = base(c);
                         v.held = v.finite;
                         if (v.finite)
                             v.detail = v.quality =
                                 "1e4: " + qualityLine(*c.at("hdr-high")) + "; 1e-6: " + qualityLine(*c.at("hdr-low"));
                         return v;
                     }});
}

// Damaged glTF files: a warning in run.json or one line and exit 2, never a crash.
void addGltfCases(std::vector<Case>& cases, const Inputs& in) {
    auto gltfCase = [&](const std::string& name, const fs::path& file, const std::string& expect,
                        const std::string& warning) {
        std::vector<std::string> args = {"--scene", file.string(), "--path", "orbit", "--frames", "4"};
        cases.push_back({name, expect, {{"gltf", args}}, [warning](Children& c) {
                             Verdict v;
                             const Child& r = *c.at("gltf");
                             size_t lines = size_t(std::count(r.err.begin(), r.err.end(), '\n'));
                             if (r.signal) {
                                 v.finite = false;
                                 v.detail = "crashed (signal " + std::to_string(r.signal) + ")";
                             } else if (r.exit_code == 2) {
                                 v.held = lines == 1 && !fs::exists(r.dir);
                                 v.detail = "refused: " + r.err.substr(0, r.err.find('\n'));
                                 v.quality = "not rendered";
                             } else if (r.exit_code == 0) {
                                 std::string why;
                                 v.finite = finiteAndOk(r, why);
                                 auto warnings = r.run.value(rundir::run::kScene, json::object()).value(rundir::run::scene::kWarnings, json::array());
                                 std::string found;
                                 for (const auto& w : warnings)
                                     if (w.is_string() && w.get<std::string>().find(warning) != std::string::npos)
                                         found = w.get<std::string>();
                                 v.held = v.finite && !found.empty();
                                 v.detail = "rendered with " + std::to_string(warnings.size()) + " warning(s) in run.json" +
                                            (found.empty() ? ", none about '" + warning + "'" : ": " + found) + why;
                                 v.quality = qualityLine(r);
                             } else {
                                 v.detail = "exit " + std::to_string(r.exit_code) + ": " + r.err.substr(0, 300);
                             }
                             return v;
                         }});
    };
    const std::string either = "rendered with a warning in run.json, or refused with one line and exit 2; never a crash";
    gltfCase("gltf-zero-length-normals", in.bad_normals, "assimp-testmodels BoxBadNormals: " + either, "zero-length normal");
    gltfCase("gltf-non-finite-positions", in.infinites, "assimp-testmodels BoxWithInfinites: " + either, "non-finite");
    gltfCase("gltf-zero-area-triangles", in.zero_area, "a degenerate (collinear) triangle beside a quad: " + either,
             "zero-area triangle");
    gltfCase("gltf-missing-texture", in.no_texture, "a base colour texture whose image file is missing: " + either,
             "texture");
}

}  // namespace

std::vector<Case> buildCases(const fs::path& paths_dir, const StressOptions& o, uint32_t w, uint32_t h) {
    const Inputs in = writeInputs(paths_dir, o, w, h);
    std::vector<Case> cases;
    addPrecisionCases(cases, in);
    addMotionCases(cases, in);
    addHistoryCases(cases, in);
    addStaticCameraCase(cases, o);
    addImageCases(cases, in);
    addGltfCases(cases, in);
    return cases;
}

}  // namespace cbr::harness::stress
