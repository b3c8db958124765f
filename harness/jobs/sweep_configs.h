// `cbrbench sweep`: parameter specs, the configurations they expand to, and the outer
// dimensions (paths, reference kinds) that each get a run of their own.
#pragma once

#include <string>
#include <vector>

#include "settings/settings.h"

namespace cbr::harness {

// A sweepable setting: a row of the settings table (settings/table.h) that sweeps, as the
// parser, the expansion, labels and help read it.
struct SweepParamInfo {
    const char* name;                  // --param NAME, e.g. cbr-lod-bias
    const char* short_name;            // in configuration labels, e.g. lod
    std::vector<std::string> variants;  // the variants it changes; empty: every variant
    std::vector<std::string> words;     // accepted values of a word-valued setting; empty: numeric
    std::string range;                 // numeric: what is accepted, e.g. "a number in (0, 1]"
    bool outer = false;                // one run per value (the reference is rendered once per run)
};
const std::vector<SweepParamInfo>& sweepParamTable();
const SweepParamInfo* findSweepParam(const std::string& name);

// "NAME: cso-tolerance (> 0), ..., cbr-route (auto|msaa-jitter|...)": for --help and errors.
std::string sweepParamSummary();

// One swept setting. Numeric ones take "LO:HI:log:N", "LO:HI:lin:N" or "V1,V2,..."; word
// ones "W1,W2,...".
struct SweepParam {
    std::string name;
    std::vector<double> values;      // numeric: in the order given; duplicates removed
    std::vector<std::string> words;  // word-valued: in the order given; duplicates removed
    bool log_scale = false;          // how the report draws its axis
    size_t size() const { return words.empty() ? values.size() : words.size(); }
};

// Throws std::invalid_argument with one line naming the spec and what is accepted.
SweepParam parseSweepParam(const std::string& spec);

// The short name a configuration label uses (tol, scale, cost, lod, route, mode, filter).
std::string shortParamName(const std::string& name);

// A value as configuration labels and CSV cells write it (up to 4 significant digits).
std::string formatParamValue(double value);

// What one configuration of a sweep sets, besides its variant.
struct SweepSetting {
    std::string name;   // a SweepParam name
    double value = 0;   // numeric settings
    std::string word;   // word-valued settings (empty for numeric ones)
    std::string text() const { return word.empty() ? formatParamValue(value) : word; }
};

// A configuration's settings applied to the run's: each a row of the settings table.
void applySweepSettings(settings::Tunables& t, const std::vector<SweepSetting>& settings);

// One configuration: a variant with settings. `label` is unique within the sweep and
// safe in file names ([a-z0-9.=_-]); `baseline` is the label of the `full` configuration
// at the same shading cost, for paired speedups.
struct SweepConfig {
    std::string variant;
    std::vector<SweepSetting> settings;
    std::string label;
    std::string baseline;
};

// The cartesian expansion: for each shading cost, full once, then each wanted variant
// once per combination of the parameters that change it (in table order: cso-tolerance,
// cso-mode, drr-scale, drr-filter, cbr-lod-bias, cbr-route), e.g.
// cbr-aso_lod=-1_route=multiview. `variants` lists the wanted variants (full is always
// added); parameters that no wanted variant uses are refused, outer ones are skipped.
// Without parameters: one configuration per variant, labelled with the variant's name.
std::vector<SweepConfig> expandSweep(const std::vector<SweepParam>& params, const std::vector<std::string>& variants);

// The outer dimensions of a sweep: --path's list and --param reference=...
// (the reference is rendered once per run, so it cannot vary per configuration). Each
// combination is a sweep of its own: `dir` is its subdirectory of --out ("" when there
// is only one: the sweep writes into --out itself), `path` and `reference` its values.
struct OuterSweep {
    std::string dir;
    std::string path;       // one --path spec
    std::string reference;  // full or ssaa
    std::vector<std::string> params;  // the --param specs less reference=
};
// Throws std::invalid_argument for a bad reference spec, an empty or repeated path, or
// two paths whose names (file stems) coincide.
std::vector<OuterSweep> outerSweeps(const std::vector<std::string>& paths, const std::string& reference,
                                    const std::vector<std::string>& params);

// A path spec as sweep.csv's `path` column and directory names write it: the file stem,
// characters outside [A-Za-z0-9._-] replaced by '-'.
std::string sweepPathName(const std::string& spec);

}  // namespace cbr::harness
