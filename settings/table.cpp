// The settings table's rows and what reads them (table.h).
#include "settings/table.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <type_traits>

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
// by a test). Numbers: name, column, help, type, {}, min, max, min_open, max_open.

// The rows that tune the workload and the variants.
void addVariantRows(std::vector<Row>& rows) {
    const std::vector<const char*> kCheckerboard = {"cbr-aso", "cbr-cso", "cbr-clip"};
    auto add = [&](Row r) { rows.push_back(std::move(r)); };
    add({"shading-cost", "shading_cost", "fragment shading about K times more expensive, same image", Type::Int, {}, 1,
         1024, false, false, {}, {}, "cost", false, 1, Hash::Always, true, false, field<&Tunables::shading_cost>()});
    add({"exposure", "exposure", "exposure multiplier before tone mapping", Type::Real, {}, 0, kNoMax, true, true, {},
         {}, nullptr, false, 0, Hash::Always, true, true, field<&Tunables::exposure>()});
    add({"drr-scale", "drr_scale", "drr per-axis render scale", Type::Real, {}, 0, 1, true, false, {}, {"drr"},
         "scale", false, 2, Hash::Always, true, false, field<&Tunables::drr_scale>()});
    add({"drr-filter", "drr_filter", "drr upscale filter", Type::Word, {"bilinear", "catmull-rom"}, 0, 0, false, false,
         {}, {"drr"}, "filter", false, 3, Hash::Always, true, false, field<&Tunables::drr_filter>()});
    add({"drr-target-ms", "drr_target_ms", "dynamic drr: target GPU frame time in ms (0: fixed scale)", Type::Real, {},
         0, kNoMax, false, true, {}, {"drr"}, nullptr, false, 0, Hash::Always, true, false,
         field<&Tunables::drr_target_ms>()});
    add({"cso-tolerance", "cso_tolerance", "cbr-cso depth tolerance (relative, or scene units)", Type::Real, {}, 0,
         kNoMax, true, true, {}, {"cbr-cso"}, "tol", false, 4, Hash::Always, true, false,
         field<&Tunables::cso_tolerance>()});
    add({"cso-mode", "cso_mode", "cbr-cso tolerance mode", Type::Word, {"relative", "absolute"}, 0, 0, false, false,
         {}, {"cbr-cso"}, "mode", false, 5, Hash::Always, true, false, field<&Tunables::cso_mode>()});
    add({"cbr-lod-bias", "cbr_lod_bias",
         "texture LOD bias of checkerboard scene passes (-1 matches full-res derivatives; the paper's: -0.5)",
         Type::Real, {}, -16, 16, false, false, {}, kCheckerboard, "lod", false, 7, Hash::Always, true, true,
         field<&Tunables::cbr_lod_bias>()});
    add({"cbr-route", "cbr_route", "checkerboard route (auto: msaa-jitter where the device has 2x MSAA with sample-rate shading, layers on lavapipe, else multiview)", Type::Word,
         {"auto", "msaa-jitter", "msaa-locations", "multiview", "layers"}, 0, 0, false, false, {}, kCheckerboard,
         "route", false, 6, Hash::Always, true, false, field<&Tunables::cbr_route>()});
    add({"cbr-history", "cbr_history",
         "checkerboard history: quarter (frame N-1's quarter-res samples, the paper's) or full (the previous "
         "resolved frame, clipped to the neighbourhood)",
         Type::Word, {"quarter", "full"}, 0, 0, false, false, {}, {"cbr-aso", "cbr-cso"}, "history", false, 10,
         Hash::UnlessDefault, true, false, field<&Tunables::cbr_history>()});
    add({"taau-scale", "taau_scale", "taau per-axis render scale", Type::Real, {}, 0, 1, true, false, {}, {"taau"},
         "tscale", false, 13, Hash::UnlessDefault, true, false, field<&Tunables::taau_scale>()});
    add({"taau-phases", "taau_phases", "taau Halton(2,3) jitter phases", Type::Int, {}, 8, 16, false, false, {8, 16},
         {"taau"}, nullptr, false, 14, Hash::UnlessDefault, true, false, field<&Tunables::taau_phases>()});
    add({"taau-blend", "taau_blend", "taau history blend weight of a sample on the pixel centre", Type::Real, {}, 0, 1,
         true, false, {}, {"taau"}, "blend", false, 15, Hash::UnlessDefault, true, false,
         field<&Tunables::taau_blend>()});
    add({"taau-lod-offset", "taau_lod_offset",
         "added to taau's texture LOD bias of log2(render width / output width): below 0 sharper textures, more "
         "shimmer for the history to absorb",
         Type::Real, {}, -4, 4, false, false, {}, {"taau"}, nullptr, false, 16, Hash::UnlessDefault, true, false,
         field<&Tunables::taau_lod_offset>()});
    add({"history-filter", "history_filter",
         "how --cbr-history full reads the history (bilinear blurs frame after frame)", Type::Word,
         {"catmull-rom", "bilinear"}, 0, 0, false, false, {}, kCheckerboard, nullptr, false, 11, Hash::UnlessDefault,
         true, false, field<&Tunables::history_filter>()});
    add({"history-format", "history_format",
         "how --cbr-history full stores the history: b10g11r11 (4 bytes a pixel; rgba16f where the device cannot "
         "store it) or rgba16f (8 bytes, exact on a still camera)",
         Type::Word, {"b10g11r11", "rgba16f"}, 0, 0, false, false, {}, kCheckerboard, nullptr, false, 12,
         Hash::UnlessDefault, true, false, field<&Tunables::history_format>()});
}

// The rows of how every variant is drawn and scored.
void addRunRows(std::vector<Row>& rows) {
    auto add = [&](Row r) { rows.push_back(std::move(r)); };
    add({"resolve-impl", "resolve_impl",
         "fused (resolve/upscale write the display image), separate (then a tonemap pass), or reference (the "
         "untiled passes the tiled resolve replaced, for image and time comparisons)",
         Type::Word, {"fused", "separate", "reference"}, 0, 0, false, false, {}, {}, nullptr, false, 9, Hash::Always,
         true, false, field<&Tunables::resolve_impl>()});
    add({"target-clear", "target_clear",
         "how scene passes clear colour targets: auto (compute on NVIDIA, load op elsewhere), load-op, or compute "
         "(a compute pass stores the clear value)",
         Type::Word, {"auto", "load-op", "compute"}, 0, 0, false, false, {}, {}, nullptr, false, 0,
         Hash::UnlessDefault, true, false, field<&Tunables::target_clear>()});
    add({"debug-shading", "debug_shading",
         "none, or pixel-id: colours encode the full-res pixel each sample lands on (tests)", Type::Word,
         {"none", "pixel-id"}, 0, 0, false, false, {}, {}, nullptr, false, 0, Hash::Always, true, false,
         field<&Tunables::debug_shading>()});
    add({"reference", "reference", "what variants are scored against", Type::Word, {"full", "ssaa"}, 0, 0, false,
         false, {}, {}, "ref", true, 8, Hash::Always, false, false, field<&Tunables::reference>()});
    add({"ssaa", "ssaa", "samples per axis of the ssaa reference (box filter)", Type::Int, {}, 2, 8, false, false, {},
         {}, nullptr, false, 0, Hash::Always, false, false, field<&Tunables::ssaa>()});
    Row display{"display", "display",
                "how the frames are seen, for ColorVideoVDP and FLIP: a display model (its size, distance, peak "
                "luminance and ambient light; cbrbench displays lists them)",
                Type::Text, {}, 0, 0, false, false, {}, {}, nullptr, false, 0, Hash::UnlessDefault, true, false, {}};
    display.text_field = {[](const Tunables& t) { return t.display.spec(); },
                          [](Tunables& t, const std::string& v) { t.display = metrics::parseDisplay(v); },
                          [](const Tunables& t) {
                              const auto& d = t.display;
                              return nlohmann::json{{"name", d.name},          {"spec", d.spec()},
                                                    {"ppd", d.ppd()},          {"width", d.width},
                                                    {"height", d.height},      {"distance_m", d.distance_m},
                                                    {"diagonal_in", d.diagonal_in}, {"fov_diagonal_deg", d.fov_diagonal_deg},
                                                    {"peak", d.peak},          {"contrast", d.contrast},
                                                    {"ambient_lux", d.ambient_lux}, {"k_refl", d.k_refl},
                                                    {"description", d.describe()}};
                          }};
    add(std::move(display));
    add({"flip-ppd", "flip_ppd",
         "FLIP's pixels per degree of visual angle (0: the display model's, 75.40 for standard_4k; FLIP's own "
         "default observer, 0.7 m from a 0.7 m wide 3840-pixel monitor, is 67.02)",
         Type::Real, {}, 0, kNoMax, false, true, {}, {}, nullptr, false, 0, Hash::UnlessDefault, false, false,
         field<&Tunables::flip_ppd>()});
    add({"scorer", "scorer",
         "where quality frames are scored: device (Vulkan compute, where the images are), cpu, or auto (device on "
         "GPUs, cpu on lavapipe, where it is faster)",
         Type::Word, {"auto", "device", "cpu"}, 0, 0, false, false, {}, {}, nullptr, false, 0, Hash::Never, false,
         false, field<&Tunables::scorer>()});
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
