// Sweep parameter specs, their expansion into configurations, and the outer dimensions.
#include "harness/jobs/sweep_configs.h"

#include "camera_paths/text.h"
#include "renderer/variants/variants.h"
#include "reports/sweep.h"
#include "settings/table.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <stdexcept>

namespace cbr::harness {
namespace {

constexpr int kMaxValues = 64;
constexpr size_t kMaxConfigs = 256;

bool parseNumber(const std::string& text, double& value) {
    // strtod skips leading blanks and newlines: a number here is the number alone.
    if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return false;
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    return end && *end == '\0' && std::isfinite(value);
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    size_t start = 0;
    for (;;) {
        size_t at = s.find(sep, start);
        out.push_back(s.substr(start, at == std::string::npos ? std::string::npos : at - start));
        if (at == std::string::npos) return out;
        start = at + 1;
    }
}

// Which variants a parameter changes; shading-cost changes them all, outer ones none.
bool appliesTo(const SweepParamInfo& info, const std::string& variant) {
    if (info.outer) return false;
    return info.variants.empty() ||
           std::find(info.variants.begin(), info.variants.end(), variant) != info.variants.end();
}

std::string joinWords(const std::vector<std::string>& words, const char* sep) {
    std::string out;
    for (const auto& w : words) out += (out.empty() ? "" : sep) + w;
    return out;
}

}  // namespace

const std::vector<SweepParamInfo>& sweepParamTable() {
    static const std::vector<SweepParamInfo> table = [] {
        std::vector<SweepParamInfo> out;
        for (const auto& row : settings::table()) {
            if (!row.sweep) continue;
            SweepParamInfo p{row.name, row.sweep, {row.variants.begin(), row.variants.end()},
                             {row.words.begin(), row.words.end()}, "", row.outer};
            if (row.type != settings::Type::Word) p.range = settings::accepted(row);
            out.push_back(std::move(p));
        }
        return out;
    }();
    return table;
}

void applySweepSettings(settings::Tunables& t, const std::vector<SweepSetting>& settings) {
    for (const auto& s : settings) {
        const settings::Row& row = *settings::find(s.name);
        if (s.word.empty()) settings::setNumber(row, t, s.value);
        else settings::setText(row, t, s.word);
    }
}

const SweepParamInfo* findSweepParam(const std::string& name) {
    for (const auto& p : sweepParamTable())
        if (name == p.name) return &p;
    return nullptr;
}

std::string sweepParamSummary() {
    std::string out;
    for (const auto& p : sweepParamTable())
        out += (out.empty() ? "" : ", ") + std::string(p.name) + " (" +
               (p.words.empty() ? std::string(p.range) : joinWords(p.words, "|")) + ")";
    return out;
}

std::string shortParamName(const std::string& name) {
    const SweepParamInfo* p = findSweepParam(name);
    return p ? p->short_name : name;
}

std::string formatParamValue(double value) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", value == 0 ? 0.0 : value);  // never "-0"
    return buf;
}

namespace {

std::vector<double> rangeValues(const std::vector<std::string>& parts, bool& log_scale,
                                const std::function<std::invalid_argument(const std::string&)>& bad) {
    double lo = 0, hi = 0, n = 0;
    if (parts.size() != 4 || !parseNumber(parts[0], lo) || !parseNumber(parts[1], hi) ||
        (parts[2] != "log" && parts[2] != "lin") || !parseNumber(parts[3], n))
        throw bad("not LO:HI:log|lin:N");
    if (n < 1 || n > kMaxValues || n != std::floor(n)) throw bad("N must be an integer from 1 to 64");
    if (!(hi >= lo)) throw bad("HI below LO");
    log_scale = parts[2] == "log";
    if (log_scale && !(lo > 0)) throw bad("a log range needs LO > 0");
    std::vector<double> values;
    int count = int(n);
    for (int i = 0; i < count; ++i) {
        double f = count == 1 ? 0.0 : double(i) / (count - 1);
        double v = log_scale ? std::exp(std::log(lo) + f * (std::log(hi) - std::log(lo))) : lo + f * (hi - lo);
        if (i == count - 1) v = hi;  // the end point exactly, not exp(log(hi))
        // A linear range through zero hits it exactly, not at 5.551e-17 (-0.3:0.3:lin:3).
        if (!log_scale && std::abs(v) < 1e-9 * std::max(std::abs(lo), std::abs(hi))) v = 0;
        values.push_back(v);
    }
    return values;
}

}  // namespace

SweepParam parseSweepParam(const std::string& spec) {
    const std::string accepted = "; expected NAME=LO:HI:log:N, NAME=LO:HI:lin:N or NAME=V1,V2,... with NAME one of " +
                                 sweepParamSummary() + " (word-valued ones take a list only)";
    auto bad = [&](const std::string& why) {
        return std::invalid_argument("--param " + cbr::paths::printable(spec) + ": " + cbr::paths::printable(why) + accepted);
    };
    size_t eq = spec.find('=');
    if (eq == std::string::npos || eq == 0) throw bad("no NAME=");
    SweepParam p;
    p.name = spec.substr(0, eq);
    const SweepParamInfo* info = findSweepParam(p.name);
    if (!info) throw bad("unknown parameter " + p.name);
    std::string rest = spec.substr(eq + 1);
    if (!info->words.empty()) {
        auto items = split(rest, ',');
        if (items.size() > size_t(kMaxValues)) throw bad("more than 64 values");
        for (const auto& item : items) {
            if (std::find(info->words.begin(), info->words.end(), item) == info->words.end())
                throw std::invalid_argument("--param " + cbr::paths::printable(spec) + ": unknown " + p.name + " '" +
                                            cbr::paths::printable(item) + "'; expected " + p.name + "=W1,W2,... with W " +
                                            "one of " + joinWords(info->words, ", "));
            if (std::find(p.words.begin(), p.words.end(), item) == p.words.end()) p.words.push_back(item);
        }
        return p;
    }
    std::vector<double> values;
    if (rest.find(':') != std::string::npos) {
        values = rangeValues(split(rest, ':'), p.log_scale, bad);
    } else {
        for (const auto& item : split(rest, ',')) {
            double v = 0;
            if (!parseNumber(item, v)) throw bad("'" + item + "' is not a finite number");
            values.push_back(v == 0 ? 0.0 : v);
        }
        if (values.size() > size_t(kMaxValues)) throw bad("more than 64 values");
    }
    for (double v : values)
        if (!settings::acceptsNumber(*settings::find(p.name), v))
            throw bad("value " + formatParamValue(v) + " out of range: expected " + info->range);
    for (double v : values) {
        // Values equal as labels write them are one configuration.
        bool seen = std::any_of(p.values.begin(), p.values.end(),
                                [&](double u) { return formatParamValue(u) == formatParamValue(v); });
        if (!seen) p.values.push_back(v);
    }
    return p;
}

namespace {

void checkParams(const std::vector<SweepParam>& params, const std::vector<std::string>& wanted) {
    for (size_t i = 0; i < params.size(); ++i) {
        for (size_t j = 0; j < i; ++j)
            if (params[j].name == params[i].name)
                throw std::invalid_argument("--param " + params[i].name + ": given twice; expected each parameter once");
        const SweepParamInfo& info = *findSweepParam(params[i].name);
        if (info.outer) continue;
        bool used = std::any_of(wanted.begin(), wanted.end(), [&](const std::string& v) { return appliesTo(info, v); });
        if (!used)
            throw std::invalid_argument("--param " + params[i].name + ": no swept variant uses it; expected " +
                                        joinWords(info.variants, " or ") + " in --variants");
    }
}

// Every combination of `own`'s values, the first parameter outermost.
std::vector<std::vector<SweepSetting>> combinations(const std::vector<const SweepParam*>& own) {
    std::vector<std::vector<SweepSetting>> out{{}};
    for (const SweepParam* p : own) {
        std::vector<std::vector<SweepSetting>> next;
        for (const auto& prefix : out)
            for (size_t k = 0; k < p->size(); ++k) {
                auto c = prefix;
                SweepSetting s{p->name};
                if (p->words.empty()) s.value = p->values[k];
                else s.word = p->words[k];
                c.push_back(s);
                next.push_back(std::move(c));
            }
        out = std::move(next);
    }
    return out;
}

}  // namespace

std::vector<SweepConfig> expandSweep(const std::vector<SweepParam>& params, const std::vector<std::string>& variants) {
    // In table order (renderer/variants), the reference first.
    const std::string reference(cbr::variants::referenceVariant().name);
    std::vector<std::string> wanted{reference};
    for (const auto& v : cbr::variants::allVariants())
        if (v.name != reference &&
            (variants.empty() || std::find(variants.begin(), variants.end(), v.name) != variants.end()))
            wanted.emplace_back(v.name);
    for (const auto& v : variants) {
        bool known = false;
        for (const auto& t : cbr::variants::allVariants()) known = known || t.name == v;
        if (!known)
            throw std::invalid_argument("--variants " + v + ": unknown variant; expected one of " +
                                        cbr::variants::variantNames());
    }
    checkParams(params, wanted);

    std::vector<double> costs{0};  // 0: the run's own --shading-cost, not a swept value
    for (const auto& p : params)
        if (p.name == "shading-cost") costs = p.values;
    std::vector<SweepConfig> out;
    for (double cost : costs) {
        std::string base_label;
        for (const auto& v : wanted) {
            std::vector<const SweepParam*> own;  // in table order, whatever the command line's
            for (const auto& info : sweepParamTable())
                for (const auto& p : params)
                    if (p.name == info.name && p.name != "shading-cost" && appliesTo(info, v)) own.push_back(&p);
            for (auto& settings : combinations(own)) {
                SweepConfig c;
                c.variant = v;
                c.label = v;
                for (const auto& s : settings) c.label.append("_").append(shortParamName(s.name)).append("=").append(s.text());
                c.settings = std::move(settings);
                if (cost > 0) {
                    c.settings.push_back({"shading-cost", cost});
                    c.label += "_cost=" + formatParamValue(cost);
                }
                if (v == reference) base_label = c.label;
                c.baseline = base_label;
                out.push_back(std::move(c));
            }
        }
        if (out.size() > kMaxConfigs)
            throw std::invalid_argument("--param: the parameters expand to more than " + std::to_string(kMaxConfigs) +
                                        " configurations; expected fewer values");
    }
    return out;
}

std::string sweepPathName(const std::string& spec) {
    std::filesystem::path p(spec);
    std::string stem = p.has_extension() ? p.stem().string() : spec;
    for (char& c : stem)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '-';
    return stem;
}

std::vector<OuterSweep> outerSweeps(const std::vector<std::string>& paths, const std::string& reference,
                                    const std::vector<std::string>& params) {
    std::vector<std::string> inner;
    std::vector<std::string> references{reference};
    bool swept = false;
    for (const auto& spec : params) {
        if (spec.rfind("reference=", 0) != 0) {
            inner.push_back(spec);
            continue;
        }
        if (swept) throw std::invalid_argument("--param reference: given twice; expected each parameter once");
        references = parseSweepParam(spec).words;
        swept = true;
    }
    std::string path_list;
    for (size_t i = 0; i < paths.size(); ++i) path_list += (i ? "," : "") + paths[i];
    std::vector<std::string> names;
    for (const auto& path : paths) {
        if (path.empty())
            throw std::invalid_argument("--path " + cbr::paths::printable(path_list) + ": empty item; expected PATH[,PATH...]");
        std::string name = sweepPathName(path);
        if (std::find(names.begin(), names.end(), name) != names.end())
            throw std::invalid_argument("--path " + cbr::paths::printable(path_list) + ": two paths named " +
                                        cbr::paths::printable(name) + "; expected each path once, with distinct names");
        names.push_back(name);
    }
    std::vector<OuterSweep> out;
    for (size_t i = 0; i < paths.size(); ++i)
        for (const auto& ref : references) {
            std::string dir = paths.size() > 1 || references.size() > 1
                                  ? reports::sweepGroupDir(names[i], ref, paths.size() > 1, references.size() > 1)
                                  : "";
            out.push_back({dir, paths[i], ref, inner});
        }
    return out;
}

}  // namespace cbr::harness
