// Loading a run directory for the report (with one-line errors) and shared per-frame queries.
#include "reports/report_data.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "reports/html.h"
#include "reports/status.h"

namespace cbr::reports {

namespace {

nlohmann::json readRunJson(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw std::invalid_argument(file.string() +
                                    ": missing or unreadable; the report needs the run's run.json as cbrbench writes it");
    std::stringstream ss;
    ss << in.rdbuf();
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(ss.str());
    } catch (const nlohmann::json::parse_error& e) {
        // e.byte is 1-based; the message names line and column too.
        std::string what = e.what();
        if (auto p = what.find("parse error"); p != std::string::npos) what = what.substr(p);
        throw std::invalid_argument(file.string() + ": malformed JSON at byte " + std::to_string(e.byte) + " (" + what +
                                    "); accepted: one JSON object as cbrbench writes it");
    }
    if (!j.is_object())
        throw std::invalid_argument(file.string() + ": the JSON root (pointer \"\") is " + j.type_name() +
                                    "; accepted: an object");
    if (j.contains(run_json::kVariants)) {
        const auto& v = j[run_json::kVariants];
        if (!v.is_array())
            throw std::invalid_argument(file.string() + ": /variants is " + std::string(v.type_name()) +
                                        "; accepted: an array of objects");
        for (size_t i = 0; i < v.size(); ++i) {
            const std::string ptr = rundir::pointer(run_json::kVariants, std::to_string(i));
            if (!v[i].is_object())
                throw std::invalid_argument(file.string() + ": " + ptr + " is " + v[i].type_name() +
                                            "; accepted: an object with name, status and passes");
            const char* passes = run_json::variant::kPasses;
            if (v[i].contains(passes) && !v[i][passes].is_array())
                throw std::invalid_argument(file.string() + ": " + ptr + "/" + passes + " is " + v[i][passes].type_name() +
                                            "; accepted: an array of {name, ran, reason}");
        }
    }
    for (const char* key : {run_json::kDevice, run_json::kSettings, run_json::kScene, run_json::kPath, run_json::kTool,
                            run_json::kValidation, run_json::kMetrics})
        if (j.contains(key) && !j[key].is_object())
            throw std::invalid_argument(file.string() + ": /" + key + " is " + j[key].type_name() +
                                        "; accepted: an object");
    return j;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

const nlohmann::json* jsonAt(const nlohmann::json& j, const std::string& pointer) {
    try {
        nlohmann::json::json_pointer p(pointer);
        if (!j.contains(p)) return nullptr;
        return &j.at(p);
    } catch (const nlohmann::json::exception&) {
        return nullptr;  // a pointer through a non-object: treated as absent
    }
}

std::string jsonText(const nlohmann::json* j) {
    if (!j || j->is_null()) return kDash;
    if (j->is_string()) return j->get<std::string>();
    if (j->is_boolean()) return j->get<bool>() ? "yes" : "no";
    if (j->is_number_integer() || j->is_number_unsigned()) return j->dump();
    if (j->is_number_float()) return fmtShort(j->get<double>(), 6);
    if (j->is_array()) {
        std::string out;
        for (const auto& e : *j) {
            if (!out.empty()) out += ", ";
            out += e.is_structured() ? e.dump() : jsonText(&e);
        }
        return out.empty() ? kDash : out;
    }
    return j->dump();
}

RunData loadRun(const std::filesystem::path& dir) {
    RunData d;
    d.dir = dir;
    d.summary = readCsv(dir / rundir::kSummaryCsv, isReportNumericColumn, {summary_csv::kVariant, summary_csv::kStatus});
    d.frames = readCsv(dir / rundir::kFramesCsv, isReportNumericColumn,
                       {frames_csv::kVariant, frames_csv::kRepeat, frames_csv::kFrame});
    d.run = readRunJson(dir / rundir::kRunJson);

    for (size_t r = 0; r < d.summary.size(); ++r) {
        const std::string& v = d.summary.text(r, summary_csv::kVariant);
        if (v.empty())
            throw std::invalid_argument(d.summary.file.string() + ":" + std::to_string(d.summary.row_lines[r]) +
                                        ": empty variant name; accepted: a variant name such as full or cbr-cso");
        if (std::find(d.variants.begin(), d.variants.end(), v) == d.variants.end()) d.variants.push_back(v);
    }
    std::set<double> frames;
    std::set<double> repeats;
    for (size_t r = 0; r < d.frames.size(); ++r) {
        auto f = d.frames.num(r, frames_csv::kFrame);
        auto rep = d.frames.num(r, frames_csv::kRepeat);
        if (!f || !rep || !std::isfinite(*f) || !std::isfinite(*rep))
            throw std::invalid_argument(d.frames.file.string() + ":" + std::to_string(d.frames.row_lines[r]) +
                                        ": empty or infinite frame or repeat; accepted: integers from 0");
        frames.insert(*f);
        repeats.insert(*rep);
        // frames.csv may list variants that summary.csv lacks (e.g. an interrupted run).
        const std::string& v = d.frames.text(r, frames_csv::kVariant);
        if (!v.empty() && std::find(d.variants.begin(), d.variants.end(), v) == d.variants.end())
            d.variants.push_back(v);
    }
    d.frame_ids.assign(frames.begin(), frames.end());
    d.repeats = int(repeats.size());
    if (const auto it = d.run.find(run_json::kReferenceVariant); it != d.run.end() && it->is_string())
        d.reference = it->get<std::string>();
    else if (!d.run.contains(run_json::kKind) && !d.variants.empty())
        d.reference = d.variants.front();
    return d;
}

std::optional<size_t> summaryRow(const RunData& d, const std::string& variant) {
    for (size_t r = 0; r < d.summary.size(); ++r)
        if (d.summary.text(r, summary_csv::kVariant) == variant) return r;
    return std::nullopt;
}

std::optional<double> summaryNum(const RunData& d, const std::string& variant, const std::string& column) {
    auto r = summaryRow(d, variant);
    return r ? d.summary.num(*r, column) : std::nullopt;
}

std::string summaryText(const RunData& d, const std::string& variant, const std::string& column) {
    auto r = summaryRow(d, variant);
    return r ? d.summary.text(*r, column) : std::string();
}

bool variantOk(const RunData& d, const std::string& variant) {
    return statusHasTimes(summaryText(d, variant, summary_csv::kStatus));
}

Speedup summarySpeedup(const RunData& d, const std::string& variant) {
    return {summaryNum(d, variant, summary_csv::kSpeedup), summaryNum(d, variant, summary_csv::kSpeedupLow),
            summaryNum(d, variant, summary_csv::kSpeedupHigh)};
}

bool hasJod(const RunData& d) {
    for (const auto& v : d.variants)
        if (auto jod = summaryNum(d, v, summary_csv::kCvvdpJod); jod && std::isfinite(*jod)) return true;
    return false;
}

std::string deviceText(const RunData& d) {
    namespace k = run_json::device;
    auto text = [&](const char* key) {
        const auto* j = runAt(d, run_json::kDevice, key);
        return !j || j->is_null() ? std::string() : j->is_string() ? j->get<std::string>() : j->dump();
    };
    return "'" + text(k::kName) + "' driver " + text(k::kDriverId) + " " + text(k::kDriverVersion);
}

const nlohmann::json* variantJson(const RunData& d, const std::string& variant) {
    auto it = d.run.find(run_json::kVariants);
    if (it == d.run.end() || !it->is_array()) return nullptr;
    for (const auto& v : *it)
        if (v.is_object() && v.value(run_json::variant::kName, std::string()) == variant) return &v;
    return nullptr;
}

bool isCheckerboard(const RunData& d, const std::string& variant) {
    if (summaryNum(d, variant, summary_csv::statMean(rundir::pixels::kShaded))) return true;
    const auto* vj = variantJson(d, variant);
    if (vj && vj->contains(run_json::variant::kRoute)) return true;
    for (size_t r = 0; r < d.frames.size(); ++r)
        if (d.frames.text(r, frames_csv::kVariant) == variant && d.frames.num(r, rundir::pixels::kShaded)) return true;
    return false;
}

std::map<int, std::vector<double>> gpuMsByRepetition(const RunData& d, const std::string& variant, int max_repeats) {
    std::map<int, std::vector<double>> reps;
    const auto& f = d.frames;
    for (size_t i = 0; i < f.size(); ++i) {
        if (f.text(i, frames_csv::kVariant) != variant || f.text(i, frames_csv::kStatus) != "ok") continue;
        auto ms = f.num(i, frames_csv::kGpuMs);
        auto rep = f.num(i, frames_csv::kRepeat);
        if (ms && rep && std::isfinite(*ms) && *rep < max_repeats) reps[int(*rep)].push_back(*ms);
    }
    return reps;
}

std::vector<std::optional<double>> perFrame(const RunData& d, const std::string& variant, const std::string& column,
                                            int repeat) {
    std::vector<std::vector<double>> values(d.frame_ids.size());
    if (d.frames.has(column)) {
        for (size_t r = 0; r < d.frames.size(); ++r) {
            if (d.frames.text(r, frames_csv::kVariant) != variant) continue;
            if (repeat >= 0 && d.frames.num(r, frames_csv::kRepeat) != double(repeat)) continue;
            auto v = d.frames.num(r, column);
            if (!v || std::isnan(*v)) continue;
            auto f = d.frames.num(r, frames_csv::kFrame);
            auto it = std::lower_bound(d.frame_ids.begin(), d.frame_ids.end(), *f);
            values[size_t(it - d.frame_ids.begin())].push_back(*v);
        }
    }
    std::vector<std::optional<double>> out(d.frame_ids.size());
    for (size_t i = 0; i < values.size(); ++i)
        if (!values[i].empty()) out[i] = median(values[i]);
    return out;
}

std::optional<int> extremeFrame(const RunData& d, const std::string& variant, const std::string& column,
                                bool highest) {
    auto values = perFrame(d, variant, column, 0);
    std::optional<int> best;
    double best_v = 0;
    for (size_t i = 0; i < values.size(); ++i) {
        if (!values[i] || !std::isfinite(*values[i])) continue;
        if (!best || (highest ? *values[i] > best_v : *values[i] < best_v)) {
            best = int(d.frame_ids[i]);
            best_v = *values[i];
        }
    }
    return best;
}

std::vector<std::string> passNames(const RunData& d) {
    std::vector<std::string> out;
    for (const auto& h : d.frames.header)
        if (auto pass = frames_csv::passOfColumn(h); !pass.empty()) out.push_back(pass);
    return out;
}

std::string variantColor(const RunData& d, const std::string& variant) {
    return variantColor(d.variants, variant, d.reference);
}

std::string variantColor(const std::vector<std::string>& variants, const std::string& variant,
                         const std::string& reference) {
    // Okabe-Ito, readable for colour-blind readers; the reference in dark grey.
    static const char* kPalette[] = {"#0072b2", "#e69f00", "#009e73", "#cc79a7", "#d55e00", "#56b4e9", "#a08c00"};
    if (variant == reference) return "#404040";
    size_t k = 0;
    for (const auto& v : variants) {
        if (v == variant) break;
        if (v != reference) ++k;
    }
    return kPalette[k % std::size(kPalette)];
}

std::string passColor(const std::string& pass, size_t index) {
    if (pass == "opaque") return "#0072b2";
    if (pass == "transparent") return "#56b4e9";
    if (pass == "upscale") return "#e69f00";
    if (pass == "cbr_resolve") return "#009e73";
    if (pass == "tonemap") return "#cc79a7";
    static const char* kOthers[] = {"#d55e00", "#a08c00", "#7f7f7f", "#8c564b", "#17becf"};
    return kOthers[index % std::size(kOthers)];
}

}  // namespace cbr::reports
