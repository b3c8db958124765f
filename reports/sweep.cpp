// sweep.csv read back (its schema: rundir/sweep_csv.h), and the sweeps of outer dimensions combined.
#include "reports/sweep.h"

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
#include "rundir/files.h"
#include "rundir/sweep_csv.h"
#include "settings/table.h"

namespace cbr::reports {
namespace {

namespace sweep_csv = rundir::sweep;

bool isSweepNumeric(const std::string& name) { return !sweep_csv::isTextColumn(name); }

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
        for (const settings::Row* row : sweep_csv::settingRows())
            out.push_back({row->name, row->column, row->type != settings::Type::Word});
        return out;
    }();
    return fields;
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

namespace {

// One sweep.csv row as a point.
SweepPoint sweepPoint(const CsvData& csv, size_t r) {
    using namespace sweep_csv;
    SweepPoint p;
    p.config = csv.text(r, kConfig);
    p.variant = csv.text(r, kVariant);
    p.status = csv.text(r, kStatus);
    if (p.config.empty() || p.variant.empty())
        throw std::invalid_argument(csv.file.string() + ": line " + std::to_string(csv.row_lines[r]) +
                                    ": empty config or variant; expected a configuration label and a variant name");
    p.path = csv.text(r, kPath);
    p.reference = csv.text(r, referenceColumn());
    p.shading_cost = csv.num(r, shadingCostColumn()).value_or(1);
    for (const auto& f : sweepSettingFields()) {
        if (!f.number) {
            if (auto w = csv.text(r, f.column); !w.empty()) p.words[f.column] = w;
        } else if (auto v = csv.num(r, f.column)) {
            p.numbers[f.column] = *v;
        }
    }
    p.gpu_ms = csv.num(r, kGpuMsMedian);
    p.gpu_ms_low = csv.num(r, kGpuMsCiLow);
    p.gpu_ms_high = csv.num(r, kGpuMsCiHigh);
    p.speedup = {csv.num(r, kSpeedup), csv.num(r, kSpeedupLow), csv.num(r, kSpeedupHigh)};
    p.psnr_db = csv.num(r, kPsnrDb);
    p.ssim = csv.num(r, kSsim);
    p.eci = csv.num(r, kEci);
    p.flicker = csv.num(r, kFlickerRatio);
    p.jod = csv.num(r, kCvvdpJod);  // absent in sweeps from before ColorVideoVDP
    for (const auto& pc : kPixelClasses)
        if (auto v = csv.num(r, pc.column)) p.classes[pc.column] = *v;
    return p;
}

}  // namespace

SweepData loadSweep(const std::filesystem::path& dir) {
    using namespace sweep_csv;
    SweepData d;
    d.dir = dir;
    CsvData csv = readCsv(dir / rundir::kSweepCsv, isSweepNumeric,
                          {kConfig, kVariant, kStatus, shadingCostColumn(), kGpuMsMedian, kPsnrDb, kSsim, kEci});
    for (size_t r = 0; r < csv.size(); ++r) d.points.push_back(sweepPoint(csv, r));
    auto run_file = dir / rundir::kRunJson;
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
        const auto file = dir / sub / rundir::kSweepCsv;
        CsvData csv = readCsv(file, isSweepNumeric, {sweep_csv::kConfig, sweep_csv::kPath, sweep_csv::referenceColumn()});
        if (csv.header != sweep_csv::columns())
            throw std::invalid_argument(file.string() +
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
    writeTextAtomically(dir / rundir::kSweepCsv, text);
}

}  // namespace cbr::reports
