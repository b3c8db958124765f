// The settings table's rows and what reads them (table.h).
#include "settings/table.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "settings/display_keys.h"

namespace cbr::settings {
namespace {

constexpr double kNoMax = std::numeric_limits<double>::infinity();

// The Field of one Tunables member: enums through their index, numbers as themselves.
template <auto Member>
Field field() {
    using T = std::remove_cvref_t<decltype(std::declval<Tunables&>().*Member)>;
    return {[](const Tunables& t) {
                if constexpr (std::is_enum_v<T>) return double(static_cast<int>(t.*Member));
                else return double(t.*Member);
            },
            [](Tunables& t, double v) {
                if constexpr (std::is_enum_v<T>) t.*Member = static_cast<T>(static_cast<int>(v));
                else t.*Member = static_cast<T>(v);
            }};
}

// The order of the rows is the help's, sweep's labels' and sweep.csv's (its columns are held
// by a test). Each row names the fields it sets; the others keep Row's defaults.

// taau's rows, between the checkerboard history's and its reading (the help's order).
void addTaauRows(std::vector<Row>& rows) {
    auto add = [&](Row r) { rows.push_back(std::move(r)); };
    add({.name = "taau-scale", .column = "taau_scale", .help = "taau per-axis render scale", .type = Type::Real,
         .min = 0, .max = 1, .min_open = true, .variants = {"taau"}, .sweep = "tscale", .compare_key = 13,
         .hash = Hash::UnlessDefault, .field = field<&Tunables::taau_scale>()});
    add({.name = "taau-phases", .column = "taau_phases", .help = "taau Halton(2,3) jitter phases", .type = Type::Int,
         .min = 8, .max = 16, .only = {8, 16}, .variants = {"taau"}, .compare_key = 14, .hash = Hash::UnlessDefault,
         .field = field<&Tunables::taau_phases>()});
    add({.name = "taau-blend", .column = "taau_blend",
         .help = "taau history blend weight of a sample on the pixel centre", .type = Type::Real, .min = 0, .max = 1,
         .min_open = true, .variants = {"taau"}, .sweep = "blend", .compare_key = 15, .hash = Hash::UnlessDefault,
         .field = field<&Tunables::taau_blend>()});
    add({.name = "taau-lod-offset", .column = "taau_lod_offset",
         .help = "added to taau's texture LOD bias of log2(render width / output width): below 0 sharper textures, "
                 "more shimmer for the history to absorb",
         .type = Type::Real, .min = -4, .max = 4, .variants = {"taau"}, .compare_key = 16,
         .hash = Hash::UnlessDefault, .field = field<&Tunables::taau_lod_offset>()});
}

// The rows that tune the workload and the variants.
void addVariantRows(std::vector<Row>& rows) {
    const std::vector<const char*> kCheckerboard = {"cbr-aso", "cbr-cso", "cbr-clip"};
    auto add = [&](Row r) { rows.push_back(std::move(r)); };
    add({.name = "shading-cost", .column = "shading_cost", .help = "fragment shading about K times more expensive, same image",
         .type = Type::Int, .min = 1, .max = 1024, .sweep = "cost", .compare_key = 1,
         .field = field<&Tunables::shading_cost>()});
    add({.name = "exposure", .column = "exposure", .help = "exposure multiplier before tone mapping", .type = Type::Real,
         .min = 0, .max = kNoMax, .min_open = true, .max_open = true, .json_float = true,
         .field = field<&Tunables::exposure>()});
    add({.name = "drr-scale", .column = "drr_scale", .help = "drr per-axis render scale", .type = Type::Real, .min = 0,
         .max = 1, .min_open = true, .variants = {"drr"}, .sweep = "scale", .compare_key = 2,
         .field = field<&Tunables::drr_scale>()});
    add({.name = "drr-filter", .column = "drr_filter", .help = "drr upscale filter", .type = Type::Word,
         .words = {"bilinear", "catmull-rom"}, .variants = {"drr"}, .sweep = "filter", .compare_key = 3,
         .field = field<&Tunables::drr_filter>()});
    add({.name = "drr-target-ms", .column = "drr_target_ms",
         .help = "dynamic drr: target GPU frame time in ms (0: fixed scale)", .type = Type::Real, .min = 0,
         .max = kNoMax, .max_open = true, .variants = {"drr"}, .field = field<&Tunables::drr_target_ms>()});
    add({.name = "cso-tolerance", .column = "cso_tolerance", .help = "cbr-cso depth tolerance (relative, or scene units)",
         .type = Type::Real, .min = 0, .max = kNoMax, .min_open = true, .max_open = true, .variants = {"cbr-cso"},
         .sweep = "tol", .compare_key = 4, .field = field<&Tunables::cso_tolerance>()});
    add({.name = "cso-mode", .column = "cso_mode", .help = "cbr-cso tolerance mode", .type = Type::Word,
         .words = {"relative", "absolute"}, .variants = {"cbr-cso"}, .sweep = "mode", .compare_key = 5,
         .field = field<&Tunables::cso_mode>()});
    add({.name = "cbr-lod-bias", .column = "cbr_lod_bias",
         .help = "texture LOD bias of checkerboard scene passes (-1 matches full-res derivatives; the paper's: -0.5)",
         .type = Type::Real, .min = -16, .max = 16, .variants = kCheckerboard, .sweep = "lod", .compare_key = 7,
         .json_float = true, .field = field<&Tunables::cbr_lod_bias>()});
    add({.name = "cbr-route", .column = "cbr_route",
         .help = "checkerboard route (auto: msaa-jitter where the device has 2x MSAA with sample-rate shading, layers "
                 "on lavapipe, else multiview)",
         .type = Type::Word, .words = {"auto", "msaa-jitter", "msaa-locations", "multiview", "layers"},
         .variants = kCheckerboard, .sweep = "route", .compare_key = 6, .field = field<&Tunables::cbr_route>()});
    add({.name = "cbr-history", .column = "cbr_history",
         .help = "checkerboard history: quarter (frame N-1's quarter-res samples, the paper's) or full (the previous "
                 "resolved frame, clipped to the neighbourhood)",
         .type = Type::Word, .words = {"quarter", "full"}, .variants = {"cbr-aso", "cbr-cso"}, .sweep = "history",
         .compare_key = 10, .hash = Hash::UnlessDefault, .field = field<&Tunables::cbr_history>()});
    addTaauRows(rows);
    add({.name = "history-filter", .column = "history_filter",
         .help = "how --cbr-history full reads the history (bilinear blurs frame after frame)", .type = Type::Word,
         .words = {"catmull-rom", "bilinear"}, .variants = kCheckerboard, .compare_key = 11,
         .hash = Hash::UnlessDefault, .field = field<&Tunables::history_filter>()});
    add({.name = "history-format", .column = "history_format",
         .help = "how --cbr-history full stores the history: b10g11r11 (4 bytes a pixel; rgba16f where the device "
                 "cannot store it) or rgba16f (8 bytes, exact on a still camera)",
         .type = Type::Word, .words = {"b10g11r11", "rgba16f"}, .variants = kCheckerboard, .compare_key = 12,
         .hash = Hash::UnlessDefault, .field = field<&Tunables::history_format>()});
}

// The display row: a Text row, its value a display model (metrics/cvvdp.h).
Row displayRow() {
    return {.name = "display", .column = "display",
            .help = "how the frames are seen, for ColorVideoVDP and FLIP: a display model (its size, distance, peak "
                    "luminance and ambient light; cbrbench displays lists them)",
            .type = Type::Text, .hash = Hash::UnlessDefault,
            .text_field = {.get = [](const Tunables& t) { return t.display.spec(); },
                           .set = [](Tunables& t, const std::string& v) { t.display = metrics::parseDisplay(v); },
                           .json = [](const Tunables& t) {
                               const auto& d = t.display;
                               namespace k = display_keys;
                               return nlohmann::json{{k::kName, d.name},          {k::kSpec, d.spec()},
                                                     {k::kPpd, d.ppd()},          {k::kWidth, d.width},
                                                     {k::kHeight, d.height},      {k::kDistanceM, d.distance_m},
                                                     {k::kDiagonalIn, d.diagonal_in}, {k::kFovDiagonalDeg, d.fov_diagonal_deg},
                                                     {k::kPeak, d.peak},          {k::kContrast, d.contrast},
                                                     {k::kAmbientLux, d.ambient_lux}, {k::kKRefl, d.k_refl},
                                                     {k::kDescription, d.describe()}};
                           }}};
}

// The rows of how every variant is drawn and scored.
void addRunRows(std::vector<Row>& rows) {
    auto add = [&](Row r) { rows.push_back(std::move(r)); };
    add({.name = "resolve-impl", .column = "resolve_impl",
         .help = "fused (resolve/upscale write the display image), separate (then a tonemap pass), or reference (the "
                 "untiled passes the tiled resolve replaced, for image and time comparisons)",
         .type = Type::Word, .words = {"fused", "separate", "reference"}, .compare_key = 9,
         .field = field<&Tunables::resolve_impl>()});
    add({.name = "target-clear", .column = "target_clear",
         .help = "how scene passes clear colour targets: auto (compute on NVIDIA, load op elsewhere), load-op, or "
                 "compute (a compute pass stores the clear value)",
         .type = Type::Word, .words = {"auto", "load-op", "compute"}, .hash = Hash::UnlessDefault,
         .field = field<&Tunables::target_clear>()});
    add({.name = "debug-shading", .column = "debug_shading",
         .help = "none, or pixel-id: colours encode the full-res pixel each sample lands on (tests)", .type = Type::Word,
         .words = {"none", "pixel-id"}, .field = field<&Tunables::debug_shading>()});
    add({.name = "reference", .column = "reference", .help = "what variants are scored against", .type = Type::Word,
         .words = {"full", "ssaa"}, .sweep = "ref", .outer = true, .compare_key = 8, .run_json = false,
         .field = field<&Tunables::reference>()});
    add({.name = "ssaa", .column = "ssaa", .help = "samples per axis of the ssaa reference (box filter)",
         .type = Type::Int, .min = 2, .max = 8, .run_json = false, .field = field<&Tunables::ssaa>()});
    add(displayRow());
    add({.name = "flip-ppd", .column = "flip_ppd",
         .help = "FLIP's pixels per degree of visual angle (0: the display model's, 75.40 for standard_4k; FLIP's own "
                 "default observer, 0.7 m from a 0.7 m wide 3840-pixel monitor, is 67.02)",
         .type = Type::Real, .min = 0, .max = kNoMax, .max_open = true, .hash = Hash::UnlessDefault, .run_json = false,
         .field = field<&Tunables::flip_ppd>()});
    add({.name = "scorer", .column = "scorer",
         .help = "where quality frames are scored: device (Vulkan compute, where the images are), cpu, or auto (device "
                 "on GPUs, cpu on lavapipe, where it is faster)",
         .type = Type::Word, .words = {"auto", "device", "cpu"}, .hash = Hash::Never, .run_json = false,
         .field = field<&Tunables::scorer>()});
}

// A local, not a namespace-scope constant: compare.cpp reads the table while statics are
// initialised, in an order no file controls.
std::vector<Row> makeTable() {
    std::vector<Row> rows;
    addVariantRows(rows);
    addRunRows(rows);
    return rows;
}

// The shortest text that reads back as the same double (so a default typed back is the
// default: 67.02064327658226 is not 67.0206), never "-0".
std::string number(double v) {
    if (v == 0) v = 0;
    char buf[40];
    for (int digits = 6; digits <= 17; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, v);
        if (std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

bool parseNumber(const std::string& text, double& value) {
    // strtod skips leading blanks: a number here is the number alone.
    if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return end && *end == '\0' && std::isfinite(value);
}

std::string joinOr(const std::vector<std::string>& items) {
    std::string out;
    for (size_t i = 0; i < items.size(); ++i) out += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
    return out;
}

[[noreturn]] void refuse(const Row& row, const std::string& text, const std::string& why = "") {
    throw std::invalid_argument("--" + std::string(row.name) + " " + text + ": expected " + accepted(row) +
                                " (default " + settings::text(row, Tunables{}) + ")" + (why.empty() ? "" : "; " + why));
}

}  // namespace

const std::vector<Row>& table() {
    static const std::vector<Row> rows = makeTable();
    return rows;
}

const Row* find(std::string_view name) {
    for (const auto& r : table())
        if (name == r.name) return &r;
    return nullptr;
}

std::vector<const Row*> compareKey() {
    std::vector<const Row*> out;
    for (int place = 1;; ++place) {
        const Row* at = nullptr;
        for (const auto& r : table())
            if (r.compare_key == place) at = &r;
        if (!at) return out;
        out.push_back(at);
    }
}

std::string accepted(const Row& row) {
    std::vector<std::string> items;
    if (row.type == Type::Text)
        return "a display name (cbrbench displays: " + joinOr(metrics::displayNames()) +
               ") and/or KEY=VALUE overrides: res, diagonal, width, distance, fov, peak, contrast, black, ambient, refl";
    if (row.type == Type::Word) {
        for (const char* w : row.words) items.emplace_back(w);
        return joinOr(items);
    }
    if (!row.only.empty()) {
        for (double v : row.only) items.push_back(number(v));
        return joinOr(items);
    }
    std::string what = row.type == Type::Int ? "an integer" : "a number";
    if (row.max == kNoMax) return what + (row.min_open ? " > " : " >= ") + number(row.min);
    return what + " in " + (row.min_open ? "(" : "[") + number(row.min) + ", " + number(row.max) +
           (row.max_open ? ")" : "]");
}

std::string text(const Row& row, const Tunables& t) {
    if (row.type == Type::Text) return row.text_field.get(t);
    double v = row.field.get(t);
    return row.type == Type::Word ? std::string(row.words.at(size_t(v))) : number(v);
}

nlohmann::json toJson(const Row& row, const Tunables& t) {
    if (row.type == Type::Text) return row.text_field.json(t);
    double v = row.field.get(t);
    if (row.type == Type::Word) return row.words.at(size_t(v));
    if (row.type == Type::Int) return int(v);
    return v;
}

bool isDefault(const Row& row, const Tunables& t) {
    if (row.type == Type::Text) return row.text_field.get(t) == row.text_field.get(Tunables{});
    return row.field.get(t) == row.field.get(Tunables{});
}

bool acceptsNumber(const Row& row, double v) {
    if (row.type == Type::Word || row.type == Type::Text || !std::isfinite(v)) return false;
    if (row.type == Type::Int && v != std::floor(v)) return false;
    if (!row.only.empty()) {
        for (double o : row.only)
            if (v == o) return true;
        return false;
    }
    return (row.min_open ? v > row.min : v >= row.min) && (row.max_open ? v < row.max : v <= row.max);
}

void setNumber(const Row& row, Tunables& t, double value) {
    if (!acceptsNumber(row, value)) refuse(row, number(value));
    row.field.set(t, value);
}

void setText(const Row& row, Tunables& t, const std::string& text) {
    if (row.type == Type::Text) {
        try {
            return row.text_field.set(t, text);
        } catch (const std::invalid_argument& e) {
            refuse(row, text, e.what());
        }
    }
    if (row.type == Type::Word) {
        for (size_t i = 0; i < row.words.size(); ++i)
            if (text == row.words[i]) return row.field.set(t, double(i));
        refuse(row, text);
    }
    double v = 0;
    if (!parseNumber(text, v) || !acceptsNumber(row, v)) refuse(row, text);
    row.field.set(t, v);
}

void check(const Tunables& t) {
    for (const auto& r : table()) {
        if (r.type == Type::Text) {
            Tunables copy = t;
            setText(r, copy, r.text_field.get(t));  // reads back, or says what is wrong
            continue;
        }
        double v = r.field.get(t);
        if (r.type == Type::Word ? !(v >= 0 && size_t(v) < r.words.size()) : !acceptsNumber(r, v))
            refuse(r, r.type == Type::Word ? number(v) : text(r, t));
    }
}

bool appliesTo(const Row& row, std::string_view variant) {
    if (row.outer) return false;
    if (row.variants.empty()) return true;
    for (const char* v : row.variants)
        if (variant == v) return true;
    return false;
}

}  // namespace cbr::settings
