// `cbrbench stress`: each case is one or more `cbrbench run`s in child processes (a crash
// or device loss in one case is that case's failure, not the suite's), checked against
// the case's expectation from their own files.
#include "harness/stress/stress.h"
#include "harness/stress/stress_cases.h"
#include "harness/stress/stress_runs.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <stdexcept>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "harness/base/exit_codes.h"
#include "harness/base/interrupt.h"
#include "harness/jobs/options.h"
#include "harness/base/progress.h"
#include "renderer/variants/variants.h"
#include "reports/csv.h"
#include "reports/output_dir.h"
#include "reports/stress_html.h"
#include "rundir/files.h"
#include "rundir/run_json_variants.h"

namespace cbr::harness {

namespace fs = std::filesystem;
using nlohmann::json;
using namespace stress;

const std::vector<StressCaseInfo>& stressCases() {
    static const std::vector<StressCaseInfo> info = [] {
        std::vector<StressCaseInfo> out;
        StressOptions o;
        auto tmp = fs::temp_directory_path() / ("cbrbench-stress-list-" + std::to_string(::getpid()));
        fs::create_directories(tmp);
        for (const auto& c : buildCases(tmp, o, 96, 64)) out.push_back({c.name, c.expectation});
        fs::remove_all(tmp);
        return out;
    }();
    return info;
}

namespace {

// run.json validation.messages: what the validation layer said (0 without it).
int validationMessages(const nlohmann::json& run) {
    const auto it = run.find(rundir::run::kValidation);
    return it != run.end() && it->is_object() ? it->value(rundir::run::validation::kMessages, 0) : 0;
}

void checkStressOptions(const StressOptions& o) {
    if (o.static_frames < 2 || o.subpixel_frames < 101)
        throw std::invalid_argument("stress: --static-frames >= 2 and --subpixel-frames >= 101 expected");
    std::set<std::string> names;
    for (const auto& c : stressCases()) names.insert(c.name);
    for (const auto& want : o.cases)
        if (!names.count(want)) {
            std::string list;
            for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
            throw std::invalid_argument("--cases " + want + ": unknown case; expected some of " + list);
        }
}

// One pipeline's runs of the selected cases, each sub-run once (the shared flythrough
// baseline too), and each case judged as its runs come in.
class StressPipeline {
public:
    StressPipeline(const StressOptions& o, const reports::OutputDir& out, Pipeline pipeline, ProgressBar& bar)
        : o_(o), out_(out), pipeline_(pipelineWord(pipeline)), bar_(bar) {}

    // The case's runs (started where not run yet) and their links, "pipeline/id".
    Children runCase(const Case& c, std::string& links) {
        Children ch;
        for (const auto& [key, args] : c.runs) {
            std::string id = key == "base" ? "base" : c.name + "-" + key;
            auto it = children_.find(id);
            if (it == children_.end()) it = children_.emplace(id, startChild(c, id, args)).first;
            ch[key] = &it->second;
            links += (links.empty() ? "" : " ") + pipeline_ + "/" + id;
        }
        return ch;
    }

    // The case's check, validation messages counted against it, and paths as they will be.
    Verdict judge(const Case& c, Children& ch) const {
        Verdict v;
        try {
            v = c.check(ch);
        } catch (const std::exception& e) {
            v.held = false;
            v.detail = std::string("checking failed: ") + e.what();
        }
        if (o_.validate)
            for (auto& [key, child] : ch)
                if (const auto messages = validationMessages(child->run); child->loaded && messages != 0) {
                    v.held = false;
                    v.detail += "; " + key + ": " + std::to_string(messages) +
                                " validation messages";
                }
        // Messages name inputs under the partial directory; say where they will be.
        for (std::string* text : {&v.detail, &v.quality}) {
            const std::string from = out_.path().string(), to = out_.finalPath().string();
            for (size_t at = text->find(from); at != std::string::npos; at = text->find(from, at + to.size()))
                text->replace(at, from.size(), to);
        }
        return v;
    }

    // The case's runs for the page: each links its report where it wrote one.
    std::vector<reports::StressRunLink> runLinks(const Children& ch) const {
        std::vector<reports::StressRunLink> links;
        for (const auto& [key, child] : ch) {
            std::string rel = pipeline_ + "/" + fs::relative(child->dir, out_.path() / pipeline_).string();
            links.push_back({key, fs::exists(child->dir / rundir::kReportHtml) ? rel + "/" + rundir::kReportHtml : std::string()});
        }
        return links;
    }

private:
    Child startChild(const Case& c, const std::string& id, const std::vector<std::string>& args) {
        Child child;
        child.args = args;
        auto no_save = std::find(child.args.begin(), child.args.end(), "--no-save");
        if (no_save != child.args.end()) child.args.erase(no_save), child.save_frames = false;
        child.dir = out_.path() / pipeline_ / id;
        fs::create_directories(child.dir.parent_path());
        std::vector<std::string> common = {"--res", o_.resolution.text(), "--repeat", "1", "--warmup", "1", "--pipeline", pipeline_,
                                           "--variants", caseVariants()};
        if (!o_.device.empty()) common.insert(common.end(), {"--device", o_.device});
        if (o_.validate) common.push_back("--validate");
        if (!o_.cbr_route.empty()) common.insert(common.end(), {"--cbr-route", o_.cbr_route});
        if (!bar_.shown()) std::fprintf(stderr, "stress: %s %s (%s)\n", pipeline_.c_str(), c.name.c_str(), id.c_str());
        runChild(fs::read_symlink("/proc/self/exe"), child, common);
        bar_.step("stress " + pipeline_ + " " + id);
        throwIfInterrupted();  // the child had the signal too: stop, keep nothing
        return child;
    }

    const StressOptions& o_;
    const reports::OutputDir& out_;
    const std::string pipeline_;
    ProgressBar& bar_;
    std::map<std::string, Child> children_;  // by sub-run id
};

}  // namespace

int runStress(const StressOptions& o) {
    checkStressOptions(o);
    fs::path final_dir = o.out.empty() ? fs::path("out") / ("stress-" + timestampForName()) : fs::path(o.out);
    reports::OutputDir out(final_dir, o.replace);
    fs::path paths_dir = out.path() / "inputs";
    fs::create_directories(paths_dir);
    std::vector<Case> cases = buildCases(paths_dir, o, o.resolution.width, o.resolution.height);

    reports::CsvTable table({"case", "pipeline", "expectation", "finite", "held", "quality", "detail", "runs"});
    int failed = 0, total = 0;
    auto selected = [&](const Case& c) {
        return o.cases.empty() || std::find(o.cases.begin(), o.cases.end(), c.name) != o.cases.end();
    };
    std::set<std::string> run_ids;  // sub-runs of one pipeline (the shared baseline once)
    for (const auto& c : cases)
        if (selected(c))
            for (const auto& run : c.runs) run_ids.insert(run.first == "base" ? "base" : c.name + "-" + run.first);
    ProgressBar bar("runs", int(run_ids.size() * o.pipelines.size()));
    reports::StressPage page{o.resolution.text(), o.validate, variants::variantNames(), {}};
    for (const Pipeline p : o.pipelines) {
        const std::string pipeline = pipelineWord(p);
        StressPipeline runs(o, out, p, bar);
        for (const auto& c : cases) {
            if (!selected(c)) continue;
            std::string links;
            Children ch = runs.runCase(c, links);
            const Verdict v = runs.judge(c, ch);
            const bool ok = v.finite && v.held;
            ++total;
            failed += !ok;
            table.addRow({{"case", c.name},
                          {"pipeline", pipeline},
                          {"expectation", c.expectation},
                          {"finite", v.finite ? "yes" : "NO"},
                          {"held", ok ? "yes" : "NO"},
                          {"quality", v.quality},
                          {"detail", v.detail},
                          {"runs", links}});
            std::printf("%-28s %-9s %-4s %s\n", c.name.c_str(), pipeline.c_str(), ok ? "held" : "FAIL", v.detail.c_str());
            page.rows.push_back(
                {c.name, pipeline, c.expectation, v.finite, v.held, v.detail, v.quality, runs.runLinks(ch)});
        }
    }
    table.write(out.path() / "stress.csv");
    reports::writeTextAtomically(out.path() / "stress.html", reports::stressHtml(page));
    out.commit();
    std::printf("stress: %d of %d cases held; %s\n", total - failed, total, (out.finalPath() / "stress.html").c_str());
    return failed ? kExitFailed : kExitDone;
}

}  // namespace cbr::harness
