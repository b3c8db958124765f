// Helpers shared by the sweep's data, recommendation and page files (reports/sweep*.cpp).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "reports/sweep.h"

namespace cbr::reports::sweep_detail {

std::string fmtMs(double ms);
std::string fmtDb(std::optional<double> v);

// The shading costs of `points`, ascending.
std::vector<double> shadingCosts(const std::vector<SweepPoint>& points);
// The first ok configuration of a variant at a cost, with a time.
const SweepPoint* findVariant(const std::vector<SweepPoint>& points, const std::string& variant, double cost);
double psnrKey(const SweepPoint& p);

// What a sweep ranks its configurations by (sweepRanksByJod): the JOD or the sequence PSNR,
// higher being better either way, with the words and figures the sentences print.
struct Quality {
    bool jod = false;
    std::optional<double> of(const SweepPoint& p) const { return jod ? p.jod : p.psnr_db; }
    double key(const SweepPoint& p) const { return of(p).value_or(-1e300); }
    double tie() const;                              // 0.02 dB or 0.02 JOD: the best's plateau
    std::string text(std::optional<double> v) const;  // "25.80 dB" or "9.42 JOD"
    std::string diff(double d) const;                 // "0.28 dB" or "0.28 JOD"
    std::string name() const { return jod ? "JOD" : "sequence PSNR"; }  // "the best ..."
    std::string brief() const { return jod ? "JOD" : "PSNR"; }          // "... tied"
};
Quality qualityOf(const std::vector<SweepPoint>& points);
// " at shading cost K" when the sweep has more than one cost, else "".
std::string costSuffix(const std::vector<SweepPoint>& points, double cost);

// The (path, reference) sweeps in `points`, in the order they first appear, with their points.
struct Group {
    std::string path, reference;
    std::vector<SweepPoint> points;
};
std::vector<Group> groups(const std::vector<SweepPoint>& points);
// "flythrough", "ref=ssaa" or "flythrough, ref=ssaa": the group as the page names it.
std::string groupName(const Group& g, bool paths_vary, bool references_vary);
bool pathsVary(const std::vector<Group>& gs);
bool referencesVary(const std::vector<Group>& gs);

}  // namespace cbr::reports::sweep_detail
