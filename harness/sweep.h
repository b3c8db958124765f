// `cbrbench sweep`: parameter specs and the configurations they expand to.
#pragma once

#include <string>
#include <vector>

namespace cbr::harness {

// One swept setting. Accepted names: cso-tolerance (> 0), drr-scale (0, 1],
// shading-cost (integer >= 1). Values: "LO:HI:log:N", "LO:HI:lin:N" or "V1,V2,...".
struct SweepParam {
    std::string name;
    std::vector<double> values;  // in the order given; duplicates removed
    bool log_scale = false;      // how the report draws its axis
};

// Throws std::invalid_argument with one line naming the spec and what is accepted.
SweepParam parseSweepParam(const std::string& spec);

// The short name a configuration label uses (tol, scale, cost).
std::string shortParamName(const std::string& name);

// A value as configuration labels and CSV cells write it (up to 4 significant digits).
std::string formatParamValue(double value);

// What one configuration of a sweep sets, besides its variant.
struct SweepSetting {
    std::string name;  // a SweepParam name
    double value = 0;
};

// One configuration: a variant with settings. `label` is unique within the sweep and
// safe in file names ([a-z0-9.=_-]); `baseline` is the label of the `full` configuration
// at the same shading cost, for paired speedups.
struct SweepConfig {
    std::string variant;
    std::vector<SweepSetting> settings;
    std::string label;
    std::string baseline;
};

// The cartesian expansion: for each shading cost, full once, drr per drr-scale, cbr-aso
// once and cbr-cso per cso-tolerance (a parameter applies only to the variants it
// affects). `variants` lists the wanted variants (full is always added); parameters
// that no wanted variant uses are refused. Without parameters: one configuration per
// variant, labelled with the variant's name.
std::vector<SweepConfig> expandSweep(const std::vector<SweepParam>& params, const std::vector<std::string>& variants);

}  // namespace cbr::harness
