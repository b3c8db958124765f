// Sweep parameter specs and their expansion into configurations.
#include "harness/sweep.h"

#include "camera_paths/text.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace cbr::harness {
namespace {

constexpr const char* kAccepted =
    "; expected NAME=LO:HI:log:N, NAME=LO:HI:lin:N or NAME=V1,V2,... with NAME one of cso-tolerance (> 0), "
    "drr-scale (0, 1], shading-cost (integer >= 1)";
constexpr int kMaxValues = 64;

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

// Which variants a parameter changes; shading-cost changes them all.
bool appliesTo(const std::string& param, const std::string& variant) {
    if (param == "cso-tolerance") return variant == "cbr-cso";
    if (param == "drr-scale") return variant == "drr";
    return param == "shading-cost";
}

}  // namespace

std::string shortParamName(const std::string& name) {
    if (name == "cso-tolerance") return "tol";
    if (name == "drr-scale") return "scale";
    if (name == "shading-cost") return "cost";
    return name;
}

std::string formatParamValue(double value) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", value);
    return buf;
}

SweepParam parseSweepParam(const std::string& spec) {
    auto bad = [&](const std::string& why) {
        return std::invalid_argument("--param " + cbr::paths::printable(spec) + ": " + cbr::paths::printable(why) + kAccepted);
    };
    size_t eq = spec.find('=');
    if (eq == std::string::npos || eq == 0) throw bad("no NAME=");
    SweepParam p;
    p.name = spec.substr(0, eq);
    if (p.name != "cso-tolerance" && p.name != "drr-scale" && p.name != "shading-cost")
        throw bad("unknown parameter " + p.name);
    std::string rest = spec.substr(eq + 1);
    std::vector<double> values;
    if (rest.find(':') != std::string::npos) {
        auto parts = split(rest, ':');
        double lo = 0, hi = 0, n = 0;
        if (parts.size() != 4 || !parseNumber(parts[0], lo) || !parseNumber(parts[1], hi) ||
            (parts[2] != "log" && parts[2] != "lin") || !parseNumber(parts[3], n))
            throw bad("not LO:HI:log|lin:N");
        if (n < 1 || n > kMaxValues || n != std::floor(n)) throw bad("N must be an integer from 1 to 64");
        if (!(hi >= lo)) throw bad("HI below LO");
        p.log_scale = parts[2] == "log";
        if (p.log_scale && !(lo > 0)) throw bad("a log range needs LO > 0");
        int count = int(n);
        for (int i = 0; i < count; ++i) {
            double f = count == 1 ? 0.0 : double(i) / (count - 1);
            double v = p.log_scale ? std::exp(std::log(lo) + f * (std::log(hi) - std::log(lo))) : lo + f * (hi - lo);
            if (i == count - 1) v = hi;  // the end point exactly, not exp(log(hi))
            values.push_back(v);
        }
    } else {
        for (const auto& item : split(rest, ',')) {
            double v = 0;
            if (!parseNumber(item, v)) throw bad("'" + item + "' is not a finite number");
            values.push_back(v);
        }
        if (values.size() > size_t(kMaxValues)) throw bad("more than 64 values");
    }
    for (double v : values) {
        bool ok = p.name == "cso-tolerance" ? v > 0
                  : p.name == "drr-scale"   ? v > 0 && v <= 1
                                            : v >= 1 && v == std::floor(v) && v <= 1024;
        if (!ok) throw bad("value " + formatParamValue(v) + " out of range");
    }
    for (double v : values) {
        // Values equal as labels write them are one configuration.
        bool seen = std::any_of(p.values.begin(), p.values.end(),
                                [&](double u) { return formatParamValue(u) == formatParamValue(v); });
        if (!seen) p.values.push_back(v);
    }
    return p;
}

std::vector<SweepConfig> expandSweep(const std::vector<SweepParam>& params, const std::vector<std::string>& variants) {
    static const char* kTable[] = {"full", "drr", "cbr-aso", "cbr-cso"};
    std::vector<std::string> wanted{"full"};
    for (const char* v : kTable)
        if (std::string(v) != "full" &&
            (variants.empty() || std::find(variants.begin(), variants.end(), v) != variants.end()))
            wanted.emplace_back(v);
    for (const auto& v : variants)
        if (std::find(std::begin(kTable), std::end(kTable), v) == std::end(kTable))
            throw std::invalid_argument("--variants " + v + ": unknown variant; expected full, drr, cbr-aso or cbr-cso");
    for (size_t i = 0; i < params.size(); ++i) {
        for (size_t j = 0; j < i; ++j)
            if (params[j].name == params[i].name)
                throw std::invalid_argument("--param " + params[i].name + ": given twice; expected each parameter once");
        bool used = std::any_of(wanted.begin(), wanted.end(), [&](const std::string& v) { return appliesTo(params[i].name, v); });
        if (!used)
            throw std::invalid_argument("--param " + params[i].name + ": no swept variant uses it; expected " +
                                        (params[i].name == "drr-scale" ? "drr" : "cbr-cso") + " in --variants");
    }

    std::vector<double> costs{0};  // 0: the run's own --shading-cost, not a swept value
    for (const auto& p : params)
        if (p.name == "shading-cost") costs = p.values;
    auto valuesOf = [&](const std::string& name) {
        for (const auto& p : params)
            if (p.name == name) return p.values;
        return std::vector<double>{};
    };
    std::vector<SweepConfig> out;
    for (double cost : costs) {
        std::string base_label;
        for (const auto& v : wanted) {
            std::vector<double> own = v == "drr" ? valuesOf("drr-scale") : v == "cbr-cso" ? valuesOf("cso-tolerance")
                                                                                         : std::vector<double>{};
            const std::string own_name = v == "drr" ? "drr-scale" : "cso-tolerance";
            if (own.empty()) own.push_back(std::nan(""));
            for (double value : own) {
                SweepConfig c;
                c.variant = v;
                c.label = v;
                if (!std::isnan(value)) {
                    c.settings.push_back({own_name, value});
                    c.label += "_" + shortParamName(own_name) + "=" + formatParamValue(value);
                }
                if (cost > 0) {
                    c.settings.push_back({"shading-cost", cost});
                    c.label += "_cost=" + formatParamValue(cost);
                }
                if (v == "full") base_label = c.label;
                c.baseline = base_label;
                out.push_back(std::move(c));
            }
        }
    }
    return out;
}

}  // namespace cbr::harness
