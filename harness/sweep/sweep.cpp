// `cbrbench sweep`: one run over the swept configurations, or, over several paths or
// reference kinds, one run per combination under one output directory.
#include "harness/sweep/sweep.h"

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "harness/run/run.h"
#include "harness/jobs/sweep_configs.h"
#include "harness/output/table_roles.h"
#include "reports/output_dir.h"
#include "settings/table.h"
#include "reports/sweep.h"
#include "rundir/files.h"

namespace cbr::harness {
namespace {

// The sweeps of the outer dimensions (harness/jobs/sweep_configs.h) one after another into OUT/<dir>/,
// then OUT/sweep.csv (every row, naming its path and reference) and the index sweep.html.
// Every sweep's input is checked before the first renders; OUT appears whole or not at all.
int runOuterSweeps(const RunOptions& options, const std::vector<std::string>& paths, const std::vector<OuterSweep>& outer) {
    auto sub = [&](const OuterSweep& o, const std::filesystem::path& out) {
        RunOptions s = options;
        s.path = o.path;
        settings::setText(*settings::find("reference"), s.tune, o.reference);
        s.params = o.params;
        s.out = out.string();
        return s;
    };
    if (outer.size() == 1) return runBenchmark(sub(outer[0], options.out));
    std::string names;
    for (const auto& path : paths) {
        if (!names.empty()) names += '+';
        names += sweepPathName(path);
    }
    const std::filesystem::path final_out =
        options.out.empty() ? std::filesystem::path("out") / ("sweep-" + specStem(options.scene) + "-" + names + "-" +
                                                              timestampForName())
                            : std::filesystem::path(options.out);
    for (const auto& o : outer) checkRunOptions(sub(o, final_out / o.dir));
    reports::OutputDir out(final_out, options.replace);
    std::vector<std::string> dirs;
    for (const auto& o : outer) {
        RunOptions s = sub(o, out.path() / o.dir);
        s.control.shown_out = (final_out / o.dir).string();
        std::cout << "sweep " << dirs.size() + 1 << "/" << outer.size() << ": " << o.dir << "\n";
        if (int rc = runBenchmark(s); rc != 0) return rc;
        dirs.push_back(o.dir);
    }
    reports::combineSweeps(out.path(), dirs);
    reports::writeSweepReport(out.path(), variantRoles());
    out.commit();
    std::cout << "\nsweep over " << outer.size() << " runs:\n";
    for (const auto& line : reports::sweepSummaryLines(reports::loadSweep(out.finalPath()).points, variantRoles()))
        std::cout << line << "\n";
    std::cout << "sweep: " << (out.finalPath() / rundir::kSweepCsv).string() << ", "
              << (out.finalPath() / rundir::kSweepHtml).string() << " (each run in its own subdirectory)\n";
    return 0;
}

}  // namespace

int runSweep(const RunOptions& options, const std::vector<std::string>& paths) {
    // A sweep over paths or reference kinds: one run per combination.
    auto outer = outerSweeps(paths, settings::text(*settings::find("reference"), options.tune), options.params);
    if (outer.size() > 1 || outer[0].params.size() != options.params.size()) return runOuterSweeps(options, paths, outer);
    return runBenchmark(options);
}

}  // namespace cbr::harness
