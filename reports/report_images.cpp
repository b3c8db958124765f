// Report section with the worst frames: reference/variant wipe, error, SSIM, FLIP, ColorVideoVDP, crawl and class maps.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_map>

#include "reports/base64.h"
#include "reports/html.h"
#include "reports/report_sections.h"

namespace cbr::reports {

namespace {

namespace fs = std::filesystem;

struct Embedded {
    std::string uri;  // empty when the file is missing
    int width = 0, height = 0;
    std::string link;  // the full-resolution file, relative to the report, when the page shows a copy
};

// Width and height from a PNG's IHDR chunk (PNG spec, section 11.2.2); 0 when not a PNG.
void pngSize(const std::string& bytes, int& w, int& h) {
    static const unsigned char kSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() < 24 || bytes.compare(0, 8, std::string(reinterpret_cast<const char*>(kSig), 8)) != 0 ||
        bytes.compare(12, 4, "IHDR") != 0)
        return;
    auto be32 = [&](size_t o) {
        return int(uint32_t(uint8_t(bytes[o])) << 24 | uint32_t(uint8_t(bytes[o + 1])) << 16 |
                   uint32_t(uint8_t(bytes[o + 2])) << 8 | uint32_t(uint8_t(bytes[o + 3])));
    };
    w = be32(16);
    h = be32(20);
}

// Width and height from a baseline or progressive JPEG's SOF segment; 0 when not found.
void jpegSize(const std::string& bytes, int& w, int& h) {
    auto u8 = [&](size_t o) { return unsigned(uint8_t(bytes[o])); };
    if (bytes.size() < 4 || u8(0) != 0xFF || u8(1) != 0xD8) return;
    for (size_t o = 2; o + 9 < bytes.size() && u8(o) == 0xFF;) {
        const unsigned marker = u8(o + 1), length = u8(o + 2) << 8 | u8(o + 3);
        if (marker >= 0xC0 && marker <= 0xC2) {
            h = int(u8(o + 5) << 8 | u8(o + 6));
            w = int(u8(o + 7) << 8 | u8(o + 8));
            return;
        }
        o += 2 + length;
    }
}

Embedded embed(const fs::path& file) {
    Embedded e;
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) return e;
    std::ifstream in(file, std::ios::binary);
    if (!in) return e;
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string bytes = ss.str();
    const bool jpeg = file.extension() == ".jpg";
    if (jpeg) jpegSize(bytes, e.width, e.height);
    else pngSize(bytes, e.width, e.height);
    e.uri = std::string(jpeg ? "data:image/jpeg" : "data:image/png") + ";base64," + base64Encode(bytes);
    return e;
}

// The page copy of a worst-frame file named in run.json (worst[].page), linked to the
// full-resolution file (worst[].files); the full file itself in runs without copies.
Embedded embedWorst(const RunData& d, const nlohmann::json& entry, const char* what) {
    const nlohmann::json* full = jsonAt(entry, rundir::pointer(run_json::worst::kFiles, what));
    if (!full || !full->is_string()) return {};
    const nlohmann::json* page = jsonAt(entry, rundir::pointer(run_json::worst::kPage, what));
    Embedded e = page && page->is_string() ? embed(d.dir / page->get<std::string>()) : Embedded{};
    if (e.uri.empty()) e = embed(d.dir / full->get<std::string>());
    if (!e.uri.empty()) e.link = full->get<std::string>();
    return e;
}

// Small images are magnified by a whole factor to at least 480 px, pixelated, so single
// pixels stay visible and sharp.
int displayWidth(const Embedded& e) {
    if (e.width <= 0) return 640;
    if (e.width >= 480) return e.width;
    return e.width * ((480 + e.width - 1) / e.width);
}

std::string img(const Embedded& e, const std::string& alt, const std::string& cls = {}) {
    std::string out = "<img";
    if (!cls.empty()) out += " class=\"" + cls + "\"";
    out += " src=\"" + e.uri + "\" alt=\"" + esc(alt) + "\"";
    if (e.width > 0) out += " width=\"" + std::to_string(e.width) + "\" height=\"" + std::to_string(e.height) + "\"";
    return out + ">";
}

// Reference over variant; the slider uncovers the reference from the left.
std::string wipe(const Embedded& ref, const Embedded& var, const std::string& variant) {
    std::string out = "<div class=\"wipe-box\" style=\"max-width:" + std::to_string(displayWidth(var)) + "px\">";
    out += "<div class=\"wipe\">" + img(var, variant + " frame") + img(ref, "reference frame", "wipe-top") +
           "<div class=\"wipe-bar\"></div></div>";
    out += "<div class=\"wipe-controls\"><span>\u2190 reference</span><input type=\"range\" min=\"0\" "
           "max=\"100\" value=\"50\" aria-label=\"wipe between reference and " + esc(variant) +
           "\"><span>" + esc(variant) + " \u2192</span><button type=\"button\" class=\"flip\">flip</button></div>";
    if (!ref.link.empty() && !var.link.empty())
        out += "<p class=\"note small\">Page copies (JPEG, at most 1280 px wide). Lossless full resolution: <a href=\"" +
               esc(ref.link) + "\">reference</a>, <a href=\"" + esc(var.link) + "\">" + esc(variant) + "</a>.</p>";
    return out + "</div>";
}

std::string mapFigure(const Embedded& e, const std::string& caption, const std::string& missing_name) {
    std::string out = "<figure class=\"map\">";
    if (e.uri.empty()) out += "<div class=\"missing\">" + std::string(kDash) + "</div>";
    else if (!e.link.empty()) out += "<a href=\"" + esc(e.link) + "\" title=\"full resolution\">" + img(e, caption) + "</a>";
    else out += img(e, caption);
    out += "<figcaption>" + esc(caption);
    if (e.uri.empty()) out += " <span class=\"muted\">(" + esc(missing_name) + " absent)</span>";
    return out + "</figcaption></figure>";
}

std::string classLegend() {
    std::string out = "<div class=\"legend small\">";
    for (const auto& pc : kPixelClasses)
        out += "<span><i style=\"background:" + std::string(pc.color) + "\"></i>" + pc.label + "</span>";
    return out + "</div>";
}

std::string frameLabel(const RunData& d, const std::string& v, const char* column, bool highest) {
    auto f = extremeFrame(d, v, column, highest);
    if (!f) return {};
    auto values = perFrame(d, v, column, 0);
    std::optional<double> value;
    for (size_t i = 0; i < d.frame_ids.size(); ++i)
        if (int(d.frame_ids[i]) == *f) value = values[i];
    const std::string name = std::string(column) == frames_csv::kSsim ? "SSIM" : std::string(column) == frames_csv::kEci ? "ECI" : column;
    return "frame " + std::to_string(*f) + " (" + name + " " + fmtShort(value.value_or(NAN), 4) + ")";
}

// Saved frames are <variant>_<frame>.png with the frame zero-padded to 4 digits.
fs::path savedFrame(const RunData& d, const std::string& v, int frame, const char* suffix) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "_%04d%s.png", frame, suffix);
    fs::path p = d.dir / rundir::kFramesDir / (v + buf);
    std::error_code ec;
    if (fs::exists(p, ec)) return p;
    return d.dir / rundir::kFramesDir / (v + "_" + std::to_string(frame) + suffix + ".png");
}

std::string fromWorstDir(const RunData& d, const std::string& v) {
    struct Kind {
        const char* kind;
        const char* title;
        const char* column;
        bool highest;
    };
    namespace kw = run_json::worst;
    namespace image = kw::image;
    const Kind kinds[] = {{kw::kSsim, "Lowest SSIM", frames_csv::kSsim, false},
                          {kw::kEci, "Highest edge crawl (ECI)", frames_csv::kEci, true}};
    const bool cbr = isCheckerboard(d, v);
    const nlohmann::json* listed = runAt(d, run_json::kWorst);
    std::string out;
    for (const auto& k : kinds) {
        auto file = [&](const char* what) { return std::string(v) + "_" + k.kind + "_" + what + ".png"; };
        // Runs that list their worst frames in run.json name the files there (shared, written
        // once, with page copies); older runs wrote worst/<variant>_<kind>_<what>.png.
        const nlohmann::json* entry = nullptr;
        if (listed && listed->is_array())
            for (const auto& e : *listed)
                if (e.value(kw::kVariant, "") == v && e.value(kw::kKind, "") == k.kind) entry = &e;
        auto get = [&](const char* what) {
            if (listed && listed->is_array()) return entry ? embedWorst(d, *entry, what) : Embedded{};
            return embed(d.dir / rundir::kWorstDir / file(what));
        };
        Embedded ref = get(image::kReference), var = get(image::kVariant);
        Embedded err = get(image::kError), ssim = get(image::kSsimMap);
        Embedded flip = get(image::kFlipMap);  // absent in runs before FLIP
        Embedded cvvdp = get(image::kCvvdpMap);  // absent in runs before ColorVideoVDP (or without it)
        Embedded crawl = get(image::kCrawlMap);
        Embedded cls = cbr ? get(image::kClassMap) : Embedded{};
        bool any = !ref.uri.empty() || !var.uri.empty() || !err.uri.empty() || !ssim.uri.empty() ||
                   !crawl.uri.empty() || !cls.uri.empty();
        std::string label = frameLabel(d, v, k.column, k.highest);
        out += "<h4>" + esc(k.title) + (label.empty() ? "" : ": " + esc(label)) + "</h4>";
        if (!any) {
            out += "<p class=\"muted\">No worst/" + esc(file("*")) + " images in this run" +
                   (d.frames.has(k.column) ? "." : std::string(" (it has no ") + k.column + " metric).") + "</p>";
            continue;
        }
        out += "<div class=\"compare\">";
        if (!ref.uri.empty() && !var.uri.empty()) out += wipe(ref, var, v);
        else out += mapFigure(var.uri.empty() ? ref : var, var.uri.empty() ? "reference" : v, var.uri.empty() ? file(image::kVariant) : file(image::kReference));
        // Error and SSIM maps always come with a worst frame, the crawl map with the ECI one,
        // the class map with checkerboard variants: only those are marked when absent.
        const bool eci_kind = std::string(k.kind) == kw::kEci;
        out += "<div class=\"maps\">";
        out += mapFigure(err, "error |variant \u2212 reference|", file(image::kError));
        out += mapFigure(ssim, "1 \u2212 SSIM map", file(image::kSsimMap));
        if (!flip.uri.empty()) out += mapFigure(flip, "FLIP error map", file(image::kFlipMap));
        if (!cvvdp.uri.empty()) out += mapFigure(cvvdp, "ColorVideoVDP difference map", file(image::kCvvdpMap));
        if (eci_kind || !crawl.uri.empty())
            out += mapFigure(crawl, "edge crawl |e\u209c \u2212 warp(e\u209c\u208b\u2081)|", file(image::kCrawlMap));
        if (cbr) out += mapFigure(cls, "pixel classes", file(image::kClassMap)) + classLegend();
        out += "<p class=\"note heat\">Maps: black \u2192 red \u2192 yellow \u2192 white as the value grows.</p>";
        out += "</div></div>";
    }
    return out;
}

std::string fromSavedFrames(const RunData& d, const std::string& v) {
    auto f = extremeFrame(d, v, frames_csv::kSsim, false);
    if (!f) return "<p class=\"muted\">No per-frame SSIM for " + esc(v) + ".</p>";
    Embedded ref = embed(savedFrame(d, d.reference, *f, "")), var = embed(savedFrame(d, v, *f, ""));
    if (ref.uri.empty() || var.uri.empty())
        return "<p class=\"muted\">frames/ lacks frame " + std::to_string(*f) + " of " + esc(v) + " or of " + esc(d.reference) + ".</p>";
    std::string out = "<h4>Lowest SSIM: " + esc(frameLabel(d, v, frames_csv::kSsim, false)) + ", from frames/</h4>";
    out += "<div class=\"compare\">" + wipe(ref, var, v) + "<div class=\"maps\">";
    if (isCheckerboard(d, v)) {
        Embedded cls = embed(savedFrame(d, v, *f, "_class"));
        out += mapFigure(cls, "pixel classes", std::string(rundir::kFramesDir) + "/" + v + "_class.png") + classLegend();
    }
    return out + "</div></div>";
}

// A data URI repeated in the section (the reference frame of several variants' worst
// frames, a frame worst by both SSIM and ECI) is embedded once: a later <img> names the first
// by id and the page's script copies its source.
std::string embedOnce(const std::string& html) {
    static const std::string kKey = " src=\"data:";
    std::unordered_map<std::string_view, int> ids;
    std::string out;
    out.reserve(html.size());
    size_t pos = 0;
    for (size_t at = html.find(kKey); at != std::string::npos; at = html.find(kKey, pos)) {
        const size_t begin = at + 6, end = html.find('"', begin);  // the URI, after ` src="`
        if (end == std::string::npos) break;
        out.append(html, pos, at - pos);
        const std::string_view uri(html.data() + begin, end - begin);
        const auto [it, first] = ids.try_emplace(uri, int(ids.size()));
        const std::string id = "img-" + std::to_string(it->second);
        if (first) out.append(" id=\"" + id + "\" src=\"").append(uri).append("\"");
        else out += " data-same=\"" + id + "\"";
        pos = end + 1;
    }
    out.append(html, pos, std::string::npos);
    return out;
}

}  // namespace

std::string imagesSection(const RunData& d) {
    std::string out = "<section id=\"images\"><h2>Worst frames</h2>";
    std::error_code ec;
    const bool worst = fs::is_directory(d.dir / rundir::kWorstDir, ec);
    const bool saved = fs::is_directory(d.dir / rundir::kFramesDir, ec);
    if (worst) {
        out += "<p class=\"note\">Per variant, the frame with the lowest SSIM and the one with the highest edge crawl, "
               "from worst/. Drag the slider (or press flip) to compare the reference with the variant; maps at "
               "the right.</p>";
    } else if (saved) {
        out += "<p class=\"note\">This run has no worst/ folder (it predates the worst-frame export), so there are "
               "no error, SSIM or crawl maps. Shown instead: each variant's lowest-SSIM frame from the saved frames/ "
               "(repetition 0), with its class map for checkerboard variants.</p>";
    } else {
        return out + "<p class=\"muted\">No images in this run: neither worst/ nor frames/ exists (run with "
                     "<code>--save-frames</code> to keep them).</p></section>";
    }
    for (const auto& v : d.variants) {
        if (v == d.reference) continue;
        out += "<div class=\"variant-images\"><h3>" + esc(v) + "</h3>";
        if (!variantOk(d, v)) out += "<p class=\"muted\">" + esc(v) + " did not run (" + esc(summaryText(d, v, summary_csv::kStatus)) + ").</p>";
        else out += worst ? fromWorstDir(d, v) : fromSavedFrames(d, v);
        out += "</div>";
    }
    return embedOnce(out + "</section>");
}

}  // namespace cbr::reports
