// sweep.csv's schema, reading it back, and combining the sweeps of outer dimensions.
#include "reports/sweep.h"
#include "settings/table.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <stdexcept>

#include "reports/csv.h"
#include "reports/csv_read.h"
#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report_sections.h"
#include "reports/sweep_detail.h"

namespace cbr::reports {
namespace {

const char* kTextColumns[] = {"config", "variant", "path", "reference", "pipeline", "drr_filter", "cso_mode",
                              "cbr_route", "cbr_history", "status", "note"};

bool isSweepNumeric(const std::string& name) {
    return std::find(std::begin(kTextColumns), std::end(kTextColumns), name) == std::end(kTextColumns);
}

}  // namespace

namespace sweep_detail {

std::string fmtMs(double ms) { return fmtShort(ms, 4) + " ms"; }
std::string fmtDb(std::optional<double> v) { return v ? fmt(v, 2) + " dB" : std::string(kDash); }

std::vector<double> shadingCosts(const std::vector<SweepPoint>& points) {
    std::set<double> costs;
    for (const auto& p : points) costs.insert(p.shading_cost);
    return {costs.begin(), costs.end()};
}

const SweepPoint* findVariant(const std::vector<SweepPoint>& points, const std::string& variant, double cost) {
    for (const auto& p : points)
        if (p.variant == variant && p.shading_cost == cost && p.hasTimes() && p.gpu_ms) return &p;
    return nullptr;
}

double psnrKey(const SweepPoint& p) { return p.psnr_db ? *p.psnr_db : -1e300; }

double Quality::tie() const { return jod ? kJodTie : 0.02; }
std::string Quality::text(std::optional<double> v) const { return jod ? jodText(v, kDash) : fmtDb(v); }
std::string Quality::diff(double d) const { return jod ? jodDiffText(d) : fmt(std::abs(d), 2) + " dB"; }
Quality qualityOf(const std::vector<SweepPoint>& points) { return {sweepRanksByJod(points)}; }

std::string costSuffix(const std::vector<SweepPoint>& points, double cost) {
    return shadingCosts(points).size() > 1 ? " at shading cost " + fmtShort(cost) : "";
}

std::vector<Group> groups(const std::vector<SweepPoint>& points) {
    std::vector<Group> out;
    for (const auto& p : points) {
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const Group& g) { return g.path == p.path && g.reference == p.reference; });
        if (it == out.end()) it = out.insert(out.end(), Group{p.path, p.reference, {}});
        it->points.push_back(p);
    }
    return out;
}

bool pathsVary(const std::vector<Group>& gs) {
    return std::any_of(gs.begin(), gs.end(), [&](const Group& g) { return g.path != gs.front().path; });
}

bool referencesVary(const std::vector<Group>& gs) {
    return std::any_of(gs.begin(), gs.end(), [&](const Group& g) { return g.reference != gs.front().reference; });
}

std::string groupName(const Group& g, bool paths_vary, bool references_vary) {
    std::string name = paths_vary ? g.path : "";
    if (references_vary) name += (name.empty() ? "" : ", ") + std::string("ref=") + g.reference;
    return name;
}

}  // namespace sweep_detail

bool sweepRanksByJod(const std::vector<SweepPoint>& points) {
    return std::any_of(points.begin(), points.end(),
                       [](const SweepPoint& p) { return p.hasTimes() && p.jod && std::isfinite(*p.jod); });
}

const std::vector<SweepSettingField>& sweepSettingFields() {
    static const std::vector<SweepSettingField> fields = [] {
        std::vector<SweepSettingField> out;
        for (const auto& row : settings::table())
            if (row.sweep && !row.outer && !row.variants.empty())
                out.push_back({row.name, row.column, row.type != settings::Type::Word});
        return out;
    }();
    return fields;
}

const std::vector<std::string>& sweepColumns() {
    static const std::vector<std::string> cols = [] {
        std::vector<std::string> out = {"config", "variant", "path", "reference", "pipeline", "shading_cost"};
        for (const auto& f : sweepSettingFields()) out.push_back(f.column);
        for (const char* c : {"status", "note", "frames", "repeats", "gpu_ms_median", "gpu_ms_ci_low", "gpu_ms_ci_high",
                              "noise_cv", "speedup_vs_full", "speedup_ci_low", "speedup_ci_high", "psnr_db", "ssim", "eci",
                              "flicker_ratio", kJodColumn, "px_shaded", "px_reused", "px_missing_parity", "px_occluded",
                              "px_offscreen", "px_reset", "px_clipped"})
            out.push_back(c);
        return out;
    }();
    return cols;
}

const SweepSettingField* findSweepSetting(const std::string& name) {
    for (const auto& f : sweepSettingFields())
        if (name == f.name) return &f;
    return nullptr;
}

std::optional<std::string> settingText(const SweepPoint& p, const SweepSettingField& f) {
    if (f.number) {
        const auto n = p.number(f.column);
        if (!n) return std::nullopt;
        char buf[32];
        double v = *n;
        std::snprintf(buf, sizeof buf, "%.4g", v == 0 ? 0.0 : v);  // as configuration labels write it
        return std::string(buf);
    }
    auto it = p.words.find(f.column);
    return it == p.words.end() || it->second.empty() ? std::nullopt : std::optional<std::string>(it->second);
}

std::string sweepGroupDir(const std::string& path, const std::string& reference, bool paths_vary, bool references_vary) {
    std::string dir = paths_vary ? path : "";
    if (references_vary) {
        if (!dir.empty()) dir += '_';
        dir += "ref=";
        dir += reference;
    }
    return dir;
}

SweepData loadSweep(const std::filesystem::path& dir) {
    SweepData d;
    d.dir = dir;
    CsvData csv = readCsv(dir / "sweep.csv", isSweepNumeric,
                          {"config", "variant", "status", "shading_cost", "gpu_ms_median", "psnr_db", "ssim", "eci"});
    for (size_t r = 0; r < csv.size(); ++r) {
        SweepPoint p;
        p.config = csv.text(r, "config");
        p.variant = csv.text(r, "variant");
        p.status = csv.text(r, "status");
        if (p.config.empty() || p.variant.empty())
            throw std::invalid_argument((dir / "sweep.csv").string() + ": line " + std::to_string(csv.row_lines[r]) +
                                        ": empty config or variant; expected a configuration label and a variant name");
        p.path = csv.text(r, "path");
        p.reference = csv.text(r, "reference");
        p.shading_cost = csv.num(r, "shading_cost").value_or(1);
        for (const auto& f : sweepSettingFields()) {
            if (!f.number) {
                if (auto w = csv.text(r, f.column); !w.empty()) p.words[f.column] = w;
            } else if (auto v = csv.num(r, f.column)) {
                p.numbers[f.column] = *v;
            }
        }
        p.gpu_ms = csv.num(r, "gpu_ms_median");
        p.gpu_ms_low = csv.num(r, "gpu_ms_ci_low");
        p.gpu_ms_high = csv.num(r, "gpu_ms_ci_high");
        p.speedup = {csv.num(r, "speedup_vs_full"), csv.num(r, "speedup_ci_low"), csv.num(r, "speedup_ci_high")};
        p.psnr_db = csv.num(r, "psnr_db");
        p.ssim = csv.num(r, "ssim");
        p.eci = csv.num(r, "eci");
        p.flicker = csv.num(r, "flicker_ratio");
        p.jod = csv.num(r, kJodColumn);  // absent in sweeps from before ColorVideoVDP
        for (const auto& pc : kPixelClasses)
            if (auto v = csv.num(r, pc.column)) p.classes[pc.column] = *v;
        d.points.push_back(std::move(p));
    }
    auto run_file = dir / "run.json";
    if (std::filesystem::exists(run_file)) {
        std::ifstream in(run_file);
        d.run = nlohmann::json::parse(in, nullptr, false);
        if (d.run.is_discarded() || !d.run.is_object())
            throw std::invalid_argument(run_file.string() + ": not a JSON object; expected the run's run.json");
    }
    return d;
}

void combineSweeps(const std::filesystem::path& dir, const std::vector<std::string>& subdirs) {
    std::string text;
    for (const auto& sub : subdirs) {
        CsvData csv = readCsv(dir / sub / "sweep.csv", isSweepNumeric, {"config", "path", "reference"});
        if (csv.header != sweepColumns())
            throw std::invalid_argument((dir / sub / "sweep.csv").string() +
                                        ": other columns than this cbrbench writes; expected one sweep's sweep.csv");
        auto line = [](const std::vector<std::string>& cells) {
            std::string out;
            for (size_t i = 0; i < cells.size(); ++i) {
                if (i) out += ',';
                out += csvEscape(cells[i]);
            }
            return out + "\n";
        };
        if (text.empty()) text = line(csv.header);
        for (size_t r = 0; r < csv.size(); ++r) text += line(csv.row(r));
    }
    writeTextAtomically(dir / "sweep.csv", text);
}

}  // namespace cbr::reports
