// Walks the settings table (settings/table.h) and checks every place a row must show up in
// the real program: the option with its default and words, one-line refusals, the plan hash,
// run.json, sweep.csv, compare's key and sweep's parameters. A new row passes or names what
// it is missing.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench_runner.h"
#include "reports/sweep.h"
#include "rundir/sweep_csv.h"
#include "settings/table.h"

namespace {

namespace fs = std::filesystem;
using cbr::settings::Row;
using cbr::settings::Tunables;
using cbr::settings::Type;
using cbr::test::runBench;

// An accepted value other than the default, as typed.
std::string otherValue(const Row& row) {
    const Tunables defaults;
    if (row.type == Type::Text) return "standard_fhd";
    if (row.type == Type::Word) {
        for (const char* w : row.words)
            if (w != cbr::settings::text(row, defaults)) return w;
    }
    const double d = row.field.get(defaults);  // Int, Real and Word rows
    std::vector<double> candidates = row.only;
    for (double v : {row.max, row.min, d * 2, d / 2, d + 1, d - 1, 0.5}) candidates.push_back(v);
    for (double v : candidates) {
        Tunables t;
        if (v != d && cbr::settings::acceptsNumber(row, v)) {
            row.field.set(t, v);
            return cbr::settings::text(row, t);
        }
    }
    ADD_FAILURE() << row.name << ": no accepted value besides the default";
    return "";
}

std::string planHash(const std::vector<std::string>& extra, const fs::path& work) {
    std::vector<std::string> args{"plan"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto r = runBench(args, work);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.out.substr(0, r.out.find(':'));
}

TEST(SettingsTable, RowsAreWellFormed) {
    std::vector<std::string> names, columns;
    for (const auto& row : cbr::settings::table()) {
        SCOPED_TRACE(row.name);
        names.emplace_back(row.name);
        columns.emplace_back(row.column);
        std::string kebab = row.column;
        std::replace(kebab.begin(), kebab.end(), '_', '-');
        EXPECT_EQ(kebab, row.name);
        EXPECT_NO_THROW(cbr::settings::check(Tunables{}));
        EXPECT_EQ(row.type == Type::Word, !row.words.empty());
        // The default is one of the accepted values, and an empty or malformed value is refused.
        Tunables t;
        EXPECT_NO_THROW(cbr::settings::setText(row, t, cbr::settings::text(row, Tunables{})));
        EXPECT_THROW(cbr::settings::setText(row, t, "x1"), std::invalid_argument);
        EXPECT_THROW(cbr::settings::setText(row, t, ""), std::invalid_argument);
    }
    std::sort(names.begin(), names.end());
    EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
    // compare's key: places 1..N, each once.
    EXPECT_EQ(cbr::settings::compareKey().size(),
              size_t(std::count_if(cbr::settings::table().begin(), cbr::settings::table().end(),
                                   [](const Row& r) { return r.compare_key > 0; })));
}

// Each option: in run's help with its default and words; a bad value refused by run,
// plan and sweep with one line naming it and what is accepted; the plan hash as the row says.
TEST(SettingsTable, OptionsChecksAndPlanHash) {
    auto work = cbr::test::scratchDir("settings-table-options");
    auto help = runBench({"run", "--help"}, work);
    ASSERT_EQ(help.exit_code, 0) << help.err;
    const std::string base = planHash({}, work);
    for (const auto& row : cbr::settings::table()) {
        SCOPED_TRACE(row.name);
        const std::string flag = "--" + std::string(row.name);
        EXPECT_NE(help.out.find(flag), std::string::npos);
        EXPECT_NE(help.out.find(cbr::settings::accepted(row)), std::string::npos);
        EXPECT_NE(help.out.find(cbr::settings::text(row, Tunables{})), std::string::npos);
        for (const char* command : {"run", "plan", "sweep"}) {
            auto r = runBench({command, flag, "bogus", "--out", (work / "never").string()}, work);
            EXPECT_EQ(r.exit_code, 2) << command;
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
            EXPECT_NE(r.err.find(flag + " bogus: expected " + cbr::settings::accepted(row)), std::string::npos) << r.err;
            EXPECT_FALSE(fs::exists(work / "never"));
        }
        EXPECT_EQ(planHash({flag, cbr::settings::text(row, Tunables{})}, work), base);
        const std::string other = planHash({flag, otherValue(row)}, work);
        if (row.hash == cbr::settings::Hash::Never) EXPECT_EQ(other, base);
        else EXPECT_NE(other, base);
    }
}

// One small run and a compare of it with itself: run.json's settings hold the rows that say
// so, compare's key lists its rows in their order with the run's values.
TEST(SettingsTable, RunJsonAndCompareKey) {
    auto work = cbr::test::scratchDir("settings-table-run");
    const fs::path dir = work / "run";
    auto r = runBench({"run", "--res", "32x18", "--frames", "2", "--repeat", "1", "--warmup", "0", "--variants", "drr",
                       "--out", dir.string()},
                      work);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto run = nlohmann::json::parse(cbr::test::slurp(dir / "run.json"));
    for (const auto& row : cbr::settings::table()) {
        SCOPED_TRACE(row.name);
        EXPECT_EQ(run.at("settings").contains(row.column), row.run_json);
        if (row.run_json) {
            EXPECT_EQ(run["settings"][row.column], cbr::settings::toJson(row, Tunables{}));
        }
    }
    auto c = runBench({"compare", dir.string(), dir.string()}, work);
    // One repetition per side decides no time verdict: inconclusive (2), compare.csv written.
    ASSERT_EQ(c.exit_code, 2) << c.err;
    // NAME=VALUE;...: the names are the key's rows in order; a row run.json holds has its value.
    const std::string cell = cbr::test::readCsv(dir / "compare.csv").at(0, "settings") + ";";
    std::vector<std::string> names;
    size_t start = 0;
    for (const Row* row : cbr::settings::compareKey()) {
        SCOPED_TRACE(row->name);
        const size_t eq = cell.find('=', start), end = cell.find(';', start);
        ASSERT_NE(end, std::string::npos);
        EXPECT_EQ(cell.substr(start, eq - start), row->column);
        const auto& v = run["settings"][row->column];
        if (row->run_json) {
            EXPECT_EQ(cell.substr(eq + 1, end - eq - 1), v.is_string() ? v.get<std::string>() : v.dump());
        }
        start = end + 1;
    }
    EXPECT_EQ(start, cell.size()) << cell;
}

// Sweep's parameters are the rows that sweep, each with a column in sweep.csv.
TEST(SettingsTable, SweepParameters) {
    const auto& columns = cbr::rundir::sweep::columns();
    for (const auto& row : cbr::settings::table()) {
        SCOPED_TRACE(row.name);
        EXPECT_EQ(std::find(columns.begin(), columns.end(), row.column) != columns.end(), row.sweep != nullptr);
    }
    auto work = cbr::test::scratchDir("settings-table-sweep");
    for (const auto& row : cbr::settings::table()) {
        if (!row.sweep || row.outer) continue;
        SCOPED_TRACE(row.name);
        // A sweep over the row's default and another value parses and expands: the run then
        // stops at the scene, which is checked after the configurations.
        const std::string spec = std::string(row.name) + "=" + cbr::settings::text(row, Tunables{}) + "," + otherValue(row);
        std::vector<std::string> args{"sweep", "--param", spec, "--scene", "no-such-scene", "--out", (work / "never").string()};
        if (!row.variants.empty()) args.insert(args.end(), {"--variants", row.variants[0]});
        auto r = runBench(args, work);
        EXPECT_EQ(r.exit_code, 2);
        EXPECT_NE(r.err.find("no-such-scene"), std::string::npos) << r.err;
    }
}

}  // namespace
