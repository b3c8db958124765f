// Sweep specs, their expansion, outer dimensions, the recommendations and quality at equal cost.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include <gtest/gtest.h>
#include <unistd.h>

#include "harness/jobs/sweep_configs.h"
#include "harness/output/table_roles.h"
#include "reports/csv.h"
#include "reports/html.h"
#include "reports/jod.h"
#include "reports/sweep.h"
#include "rundir/sweep_csv.h"

using cbr::harness::expandSweep;
using cbr::harness::outerSweeps;
using cbr::harness::parseSweepParam;
using cbr::reports::SweepPoint;

namespace {
// The roles the variant table gives: the rules below are the table's.
const cbr::reports::VariantRoles kRoles = cbr::harness::variantRoles();
}  // namespace

TEST(SweepParam, LogRangeHitsBothEndsExactly) {
    auto p = parseSweepParam("cso-tolerance=0.001:1:log:12");
    ASSERT_EQ(p.values.size(), 12u);
    EXPECT_TRUE(p.log_scale);
    EXPECT_DOUBLE_EQ(p.values.front(), 0.001);
    EXPECT_DOUBLE_EQ(p.values.back(), 1.0);
    for (size_t i = 1; i < p.values.size(); ++i)  // equal ratios
        EXPECT_NEAR(p.values[i] / p.values[i - 1], std::pow(1000.0, 1.0 / 11), 1e-9);
}

TEST(SweepParam, LinearRangeAndList) {
    auto p = parseSweepParam("drr-scale=0.5:1:lin:6");
    ASSERT_EQ(p.values.size(), 6u);
    EXPECT_DOUBLE_EQ(p.values[1], 0.6);
    auto q = parseSweepParam("shading-cost=1,4,16,4");
    EXPECT_EQ(q.values, (std::vector<double>{1, 4, 16}));  // duplicates removed, order kept
}

TEST(SweepParam, BadSpecsNameTheSpecAndWhatIsAccepted) {
    for (const char* bad : {"cso-tolerance", "=1", "tolerance=1,2", "cso-tolerance=0:1:log:4", "cso-tolerance=1:0.1:lin:3",
                            "drr-scale=0.5,1.5", "shading-cost=1.5", "shading-cost=0", "cso-tolerance=1:2:cubic:3",
                            "cso-tolerance=1:2:lin:0", "cso-tolerance=1:2:lin:65", "cso-tolerance=nan", "cso-tolerance=1,,2",
                            "drr-scale=inf", "cso-tolerance=0.1:1:lin:2.5", "cbr-route=foo", "cbr-route=",
                            "cbr-route=multiview,,auto", "cso-mode=relative,bogus", "drr-filter=nearest",
                            "cbr-lod-bias=17", "cbr-lod-bias=-1:1:log:3", "reference=msaa", "cbr-route=0:1:lin:2",
                            "cbr-lod-bias=a,b"}) {
        try {
            parseSweepParam(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const std::invalid_argument& e) {
            std::string what = e.what();
            EXPECT_NE(what.find(std::string("--param ") + bad), std::string::npos) << what;
            EXPECT_NE(what.find("expected"), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos);
        }
    }
}

TEST(SweepExpand, ParametersApplyOnlyToTheVariantsTheyChange) {
    auto configs = expandSweep({parseSweepParam("cso-tolerance=0.01,0.1,1"), parseSweepParam("drr-scale=0.5,1")}, {});
    std::vector<std::string> labels;
    for (const auto& c : configs) labels.push_back(c.label);
    EXPECT_EQ(labels, (std::vector<std::string>{"full", "drr_scale=0.5", "drr_scale=1", "cbr-aso", "cbr-cso_tol=0.01",
                                                "cbr-cso_tol=0.1", "cbr-cso_tol=1", "cbr-clip", "taau"}));
    for (const auto& c : configs) EXPECT_EQ(c.baseline, "full");
}

TEST(SweepExpand, ShadingCostMultipliesEveryVariantWithItsOwnBaseline) {
    auto configs = expandSweep({parseSweepParam("shading-cost=1,4"), parseSweepParam("cso-tolerance=0.1,1")},
                               {"cbr-cso"});
    ASSERT_EQ(configs.size(), 6u);  // per cost: full, cso x 2
    EXPECT_EQ(configs[0].label, "full_cost=1");
    EXPECT_EQ(configs[3].label, "full_cost=4");
    EXPECT_EQ(configs[5].label, "cbr-cso_tol=1_cost=4");
    EXPECT_EQ(configs[5].baseline, "full_cost=4");
    EXPECT_EQ(configs[1].baseline, "full_cost=1");
}

TEST(SweepExpand, RefusesParametersNoVariantUsesAndRepeats) {
    EXPECT_THROW(expandSweep({parseSweepParam("drr-scale=0.5,1")}, {"cbr-aso"}), std::invalid_argument);
    EXPECT_THROW(expandSweep({parseSweepParam("drr-scale=0.5"), parseSweepParam("drr-scale=1")}, {}),
                 std::invalid_argument);
    EXPECT_THROW(expandSweep({}, {"cbr-foo"}), std::invalid_argument);
}

namespace {

SweepPoint point(const std::string& variant, double ms, double psnr, double eci, std::optional<double> tol = {},
                 std::optional<double> scale = {}) {
    SweepPoint p;
    p.config = variant + (tol ? "_tol=" + std::to_string(*tol) : "") + (scale ? "_scale=" + std::to_string(*scale) : "");
    p.variant = variant;
    p.status = "ok";
    p.gpu_ms = ms;
    p.psnr_db = psnr;
    p.ssim = 0.9;
    p.eci = eci;
    if (tol) p.numbers["cso_tolerance"] = *tol;
    if (scale) p.numbers["drr_scale"] = *scale;
    return p;
}

}  // namespace

TEST(SweepRecommend, BestPsnrWithinTheCostMarginOfAso) {
    std::vector<SweepPoint> pts{point("full", 10, INFINITY, 0), point("cbr-aso", 6, 30, 0.02),
                                point("cbr-cso", 6.1, 30.2, 0.02, 0.01), point("cbr-cso", 6.2, 30.5, 0.02, 0.1),
                                point("cbr-cso", 7.0, 31.0, 0.02, 1)};  // best PSNR but 17% dearer
    auto choices = cbr::reports::recommendTolerance(pts, kRoles);
    ASSERT_EQ(choices.size(), 1u);
    EXPECT_DOUBLE_EQ(*choices[0].tolerance, 0.1);
    EXPECT_NE(choices[0].sentence.find("within 5% of cbr-aso"), std::string::npos) << choices[0].sentence;
    EXPECT_EQ(choices[0].sentence.find('\n'), std::string::npos);
}

TEST(SweepRecommend, PsnrTiesGoToLowerEciThenLargerTolerance) {
    std::vector<SweepPoint> pts{point("cbr-aso", 6, 30, 0.02), point("cbr-cso", 6, 30.01, 0.030, 0.01),
                                point("cbr-cso", 6, 30.00, 0.025, 0.1), point("cbr-cso", 6, 30.00, 0.025, 0.3)};
    auto choices = cbr::reports::recommendTolerance(pts, kRoles);
    ASSERT_EQ(choices.size(), 1u);
    EXPECT_DOUBLE_EQ(*choices[0].tolerance, 0.3);
}

TEST(SweepEqualCost, InterpolatesTheDrrScaleAtTheCheckerboardTime) {
    std::vector<SweepPoint> pts{point("drr", 4, 26, 0.05, {}, 0.5), point("drr", 8, 30, 0.03, {}, 1.0),
                                point("cbr-aso", 6, 29, 0.02)};
    auto eq = cbr::reports::equalCost(pts, {}, kRoles);
    ASSERT_EQ(eq.size(), 1u);
    EXPECT_TRUE(eq[0].matched);
    EXPECT_NEAR(*eq[0].drr_scale, 0.75, 1e-12);
    EXPECT_NEAR(*eq[0].drr_psnr, 28, 1e-12);
    EXPECT_NE(eq[0].verdict.find("better by 1.00 dB"), std::string::npos) << eq[0].verdict;
}

TEST(SweepEqualCost, OutsideTheDrrRangeMakesNoClaim) {
    std::vector<SweepPoint> pts{point("drr", 4, 26, 0.05, {}, 0.5), point("drr", 8, 30, 0.03, {}, 1.0),
                                point("cbr-aso", 12, 29, 0.02)};
    auto eq = cbr::reports::equalCost(pts, {}, kRoles);
    ASSERT_EQ(eq.size(), 1u);
    EXPECT_FALSE(eq[0].matched);
    EXPECT_NEAR(*eq[0].drr_scale, 1.0, 1e-12);
    EXPECT_NE(eq[0].verdict.find("dearer than every drr scale"), std::string::npos) << eq[0].verdict;
}

TEST(SweepParam, ControlCharactersInASpecKeepTheMessageOneLine) {
    // Found by fuzz_settings: the spec was echoed raw.
    try {
        parseSweepParam("cso-tolerance=\n1");
        ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("\\x0a"), std::string::npos) << e.what();
    }
}

TEST(SweepParam, LodBiasTakesNegativeValuesAndLinearRangesHitZeroExactly) {
    auto p = parseSweepParam("cbr-lod-bias=-1.5:0:lin:7");
    ASSERT_EQ(p.values.size(), 7u);
    EXPECT_DOUBLE_EQ(p.values.front(), -1.5);
    EXPECT_DOUBLE_EQ(p.values[1], -1.25);
    EXPECT_EQ(p.values.back(), 0.0);
    auto q = parseSweepParam("cbr-lod-bias=-0.3:0.3:lin:3");
    EXPECT_EQ(cbr::harness::formatParamValue(q.values[1]), "0");  // not 5.551e-17
    EXPECT_EQ(cbr::harness::formatParamValue(parseSweepParam("cbr-lod-bias=-0").values[0]), "0");  // not -0
    EXPECT_EQ(parseSweepParam("cbr-lod-bias=-1,0,-1").values, (std::vector<double>{-1, 0}));
}

TEST(SweepParam, WordValuedSettingsKeepTheirWordsInOrder) {
    auto r = parseSweepParam("cbr-route=multiview,auto,multiview");
    EXPECT_EQ(r.words, (std::vector<std::string>{"multiview", "auto"}));
    EXPECT_TRUE(r.values.empty());
    EXPECT_EQ(r.size(), 2u);
    EXPECT_EQ(parseSweepParam("cso-mode=absolute,relative").words.size(), 2u);
    EXPECT_EQ(parseSweepParam("drr-filter=bilinear,catmull-rom").words.size(), 2u);
    EXPECT_EQ(parseSweepParam("reference=full,ssaa").words.size(), 2u);
}

TEST(SweepParam, AnUnknownWordNamesTheSpecAndTheAcceptedWords) {
    try {
        parseSweepParam("cbr-route=msaa,multiview");
        ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()), "--param cbr-route=msaa,multiview: unknown cbr-route 'msaa'; expected "
                                         "cbr-route=W1,W2,... with W one of auto, msaa-jitter, msaa-locations, "
                                         "multiview, layers");
    }
}

TEST(SweepExpand, LodBiasAndRouteMultiplyTheCheckerboardVariantsInTableOrder) {
    // Given route before lod: labels still follow the table (lod, then route).
    auto configs = expandSweep({parseSweepParam("cbr-route=multiview,auto"), parseSweepParam("cbr-lod-bias=-1,0")},
                               {"cbr-aso", "drr"});
    std::vector<std::string> labels;
    for (const auto& c : configs) labels.push_back(c.label);
    EXPECT_EQ(labels, (std::vector<std::string>{"full", "drr", "cbr-aso_lod=-1_route=multiview", "cbr-aso_lod=-1_route=auto",
                                                "cbr-aso_lod=0_route=multiview", "cbr-aso_lod=0_route=auto"}));
    ASSERT_EQ(configs[2].settings.size(), 2u);
    EXPECT_EQ(configs[2].settings[0].name, "cbr-lod-bias");
    EXPECT_EQ(configs[2].settings[0].value, -1);
    EXPECT_EQ(configs[2].settings[1].word, "multiview");
    for (const auto& c : configs)
        for (char ch : c.label)
            EXPECT_TRUE((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || std::string(".=_-").find(ch) != std::string::npos)
                << c.label;
}

TEST(SweepExpand, ModeAndFilterApplyToTheirOwnVariantsAndTheReferenceToNone) {
    auto configs = expandSweep({parseSweepParam("cso-tolerance=0.1"), parseSweepParam("cso-mode=relative,absolute"),
                                parseSweepParam("drr-filter=bilinear,catmull-rom"), parseSweepParam("reference=full,ssaa")},
                               {});
    std::vector<std::string> labels;
    for (const auto& c : configs) labels.push_back(c.label);
    EXPECT_EQ(labels, (std::vector<std::string>{"full", "drr_filter=bilinear", "drr_filter=catmull-rom", "cbr-aso",
                                                "cbr-cso_tol=0.1_mode=relative", "cbr-cso_tol=0.1_mode=absolute", "cbr-clip",
                                                "taau"}));
}

TEST(SweepExpand, RefusesASettingNoWantedVariantUsesNamingWhichWould) {
    try {
        expandSweep({parseSweepParam("cbr-lod-bias=-1,0")}, {"drr"});
        ADD_FAILURE() << "accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()), "--param cbr-lod-bias: no swept variant uses it; expected cbr-aso or cbr-cso or cbr-clip in "
                                         "--variants");
    }
    EXPECT_THROW(expandSweep({parseSweepParam("cso-mode=absolute")}, {"cbr-aso"}), std::invalid_argument);
    EXPECT_THROW(expandSweep({parseSweepParam("drr-filter=bilinear")}, {"cbr-cso"}), std::invalid_argument);
}

TEST(SweepOuter, PathsAndReferencesEachGetADirectoryAndLeaveTheInnerParams) {
    auto outer = outerSweeps({"flythrough", "paths/orbit.json"}, "full", {"cbr-lod-bias=-1,0", "reference=full,ssaa"});
    ASSERT_EQ(outer.size(), 4u);
    EXPECT_EQ(outer[0].dir, "flythrough_ref=full");
    EXPECT_EQ(outer[1].dir, "flythrough_ref=ssaa");
    EXPECT_EQ(outer[3].dir, "orbit_ref=ssaa");
    EXPECT_EQ(outer[3].path, "paths/orbit.json");
    EXPECT_EQ(outer[3].reference, "ssaa");
    EXPECT_EQ(outer[3].params, (std::vector<std::string>{"cbr-lod-bias=-1,0"}));
    auto paths_only = outerSweeps({"flythrough", "orbit"}, "ssaa", {});
    ASSERT_EQ(paths_only.size(), 2u);
    EXPECT_EQ(paths_only[1].dir, "orbit");
    EXPECT_EQ(paths_only[1].reference, "ssaa");
    auto one = outerSweeps({"flythrough"}, "full", {"reference=ssaa"});
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0].dir, "");  // a single sweep writes into --out itself
    EXPECT_EQ(one[0].reference, "ssaa");
    EXPECT_TRUE(one[0].params.empty());
}

TEST(SweepOuter, RefusesRepeatedPathsAndReferences) {
    using Paths = std::vector<std::string>;
    for (auto [paths, params] : std::vector<std::pair<Paths, std::vector<std::string>>>{
             {{"orbit", "orbit"}, {}}, {{"a/orbit.json", "b/orbit.json"}, {}}, {{"orbit", ""}, {}},
             {{"orbit"}, {"reference=full", "reference=ssaa"}}, {{"orbit"}, {"reference=msaa"}}}) {
        try {
            outerSweeps(paths, "full", params);
            ADD_FAILURE() << paths.front() << " accepted";
        } catch (const std::invalid_argument& e) {
            std::string what = e.what();
            EXPECT_TRUE(what.rfind("--path", 0) == 0 || what.rfind("--param", 0) == 0) << what;
            EXPECT_NE(what.find("expected"), std::string::npos) << what;
        }
    }
}

namespace {

SweepPoint lodPoint(const std::string& path, double lod, double ms, double psnr, double ssim = 0.9, double eci = 0.02) {
    SweepPoint p = point("cbr-aso", ms, psnr, eci);
    p.config = "cbr-aso_lod=" + cbr::harness::formatParamValue(lod);
    p.path = path;
    p.reference = "full";
    p.ssim = ssim;
    p.numbers["cbr_lod_bias"] = lod;
    p.words["cbr_route"] = "auto";
    return p;
}

}  // namespace

TEST(SweepRecommendSettings, HighestPsnrOnTheFrontWithinTheMarginOfItsFastest) {
    std::vector<SweepPoint> pts{lodPoint("a", -1.5, 5.0, 30.0), lodPoint("a", -1, 5.1, 30.6),
                                lodPoint("a", -0.5, 5.6, 31.0),  // best PSNR, but 12% dearer than the fastest
                                lodPoint("a", 0, 5.2, 30.5)};    // dominated by -1
    auto choices = cbr::reports::recommendSettings(pts, kRoles);
    ASSERT_EQ(choices.size(), 1u);  // cbr-route has one value: not swept
    EXPECT_EQ(choices[0].setting, "cbr-lod-bias");
    EXPECT_EQ(choices[0].value, "-1");
    EXPECT_EQ(choices[0].config, "cbr-aso_lod=-1");
    EXPECT_NE(choices[0].sentence.find("the highest sequence PSNR"), std::string::npos) << choices[0].sentence;
    EXPECT_EQ(choices[0].sentence.find('\n'), std::string::npos);
}

TEST(SweepRecommendSettings, OverlappingTimeIntervalsCountAsNotSlower) {
    // 8% dearer by the median, but the intervals overlap: noise, not cost.
    std::vector<SweepPoint> pts{lodPoint("a", -0.25, 5.0, 30.0), lodPoint("a", -1, 5.4, 31.0)};
    pts[0].gpu_ms_low = 4.6, pts[0].gpu_ms_high = 5.5;
    pts[1].gpu_ms_low = 5.3, pts[1].gpu_ms_high = 6.0;
    EXPECT_EQ(cbr::reports::recommendSettings(pts, kRoles)[0].value, "-1");
    pts[1].gpu_ms_low = 5.6;  // measurably slower now
    EXPECT_EQ(cbr::reports::recommendSettings(pts, kRoles)[0].value, "-0.25");
}

TEST(SweepRecommendSettings, PsnrTiesGoToHigherSsimThenLowerEciThenLowerTime) {
    std::vector<SweepPoint> ssim{lodPoint("a", -1, 5.0, 30.00, 0.90), lodPoint("a", 0, 5.1, 30.01, 0.95)};
    EXPECT_EQ(cbr::reports::recommendSettings(ssim, kRoles)[0].value, "0");
    std::vector<SweepPoint> eci{lodPoint("a", -1, 5.0, 30.00, 0.9, 0.030), lodPoint("a", 0, 5.1, 30.01, 0.9, 0.020)};
    EXPECT_EQ(cbr::reports::recommendSettings(eci, kRoles)[0].value, "0");
    // Routes give the same image: the faster wins.
    std::vector<SweepPoint> routes{lodPoint("a", -1, 5.0, 30.0), lodPoint("a", -1, 4.9, 30.0)};
    routes[0].words["cbr_route"] = "multiview", routes[1].words["cbr_route"] = "msaa-locations";
    auto c = cbr::reports::recommendSettings(routes, kRoles);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].setting, "cbr-route");
    EXPECT_EQ(c[0].value, "msaa-locations");
}

TEST(SweepRecommendSettings, ASettingWhoseConfigurationsAllSkippedGetsNoValue) {
    std::vector<SweepPoint> pts{lodPoint("a", -1, 5.0, 30.0), lodPoint("a", -1, 5.0, 30.0)};
    pts[0].words["cbr_route"] = "msaa-jitter", pts[0].status = "skipped", pts[0].gpu_ms.reset();
    pts[1].words["cbr_route"] = "multiview";
    auto c = cbr::reports::recommendSettings(pts, kRoles);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].value, "multiview");  // the skipped route is no candidate
    pts[1].status = "failed", pts[1].gpu_ms.reset();
    c = cbr::reports::recommendSettings(pts, kRoles);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].value, "");
    EXPECT_NE(c[0].sentence.find("none of its configurations ran"), std::string::npos) << c[0].sentence;
}

TEST(SweepRecommendSettings, WarnsWhenPathsDisagree) {
    std::vector<SweepPoint> pts{lodPoint("flythrough", -1, 5.0, 30.5), lodPoint("flythrough", 0, 5.0, 30.0),
                                lodPoint("orbit", -1, 5.0, 28.0), lodPoint("orbit", 0, 5.0, 28.4)};
    auto choices = cbr::reports::recommendSettings(pts, kRoles);
    ASSERT_EQ(choices.size(), 2u);
    auto warnings = cbr::reports::pathDisagreements(choices);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_EQ(warnings[0].rfind("the recommended cbr-lod-bias differs between paths: -1 on flythrough, 0 on orbit", 0), 0u)
        << warnings[0];
    bool printed = false;
    for (const auto& line : cbr::reports::sweepSummaryLines(pts, kRoles))
        printed = printed || line.rfind("warning: the recommended cbr-lod-bias differs", 0) == 0;
    EXPECT_TRUE(printed);
    pts[3].psnr_db = 27.0;  // orbit now agrees: -1
    EXPECT_TRUE(cbr::reports::pathDisagreements(cbr::reports::recommendSettings(pts, kRoles)).empty());
}

TEST(SweepRecommendSettings, ToleranceKeepsItsOwnRule) {
    std::vector<SweepPoint> pts{point("cbr-aso", 6, 30, 0.02), point("cbr-cso", 6, 30.01, 0.030, 0.01),
                                point("cbr-cso", 6, 30.00, 0.025, 0.1), point("cbr-cso", 6, 30.00, 0.025, 0.3)};
    auto c = cbr::reports::recommendSettings(pts, kRoles);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].setting, "cso-tolerance");
    EXPECT_EQ(c[0].value, "0.3");  // the plateau's edge, as recommendTolerance
}

TEST(SweepEqualCost, OneConfigurationPerCheckerboardVariantItsBestPsnr) {
    std::vector<SweepPoint> pts{point("drr", 4, 26, 0.05, {}, 0.5), point("drr", 8, 30, 0.03, {}, 1.0),
                                lodPoint("a", 0, 6, 28), lodPoint("a", -1, 6, 29)};
    for (auto& p : pts) p.path = "a";
    auto eq = cbr::reports::equalCost(pts, {}, kRoles);
    ASSERT_EQ(eq.size(), 1u);
    EXPECT_EQ(eq[0].config, "cbr-aso_lod=-1");
}

namespace {

SweepPoint withJod(SweepPoint p, double jod) {
    p.jod = jod;
    return p;
}

}  // namespace

// ColorVideoVDP (reports/jod.h): where sweep.csv has JODs the recommendation ranks by them,
// higher being better; without them it ranks by PSNR as before.
TEST(SweepJod, SettingsRankByJodWherePresent) {
    std::vector<SweepPoint> pts{lodPoint("a", -1, 5.0, 30.6), lodPoint("a", 0, 5.05, 30.0)};
    EXPECT_EQ(cbr::reports::recommendSettings(pts, kRoles)[0].value, "-1");  // by PSNR
    EXPECT_FALSE(cbr::reports::sweepRanksByJod(pts));
    pts[0].jod = 9.1, pts[1].jod = 9.5;
    ASSERT_TRUE(cbr::reports::sweepRanksByJod(pts));
    const auto c = cbr::reports::recommendSettings(pts, kRoles);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].value, "0");
    EXPECT_NE(c[0].sentence.find("(cbr-aso_lod=0: 5.05 ms, 9.50 JOD, 30.00 dB, SSIM 0.9000, ECI 0.0200): the highest JOD"),
              std::string::npos) << c[0].sentence;
    EXPECT_NE(c[0].sentence.find("cbr-aso_lod=-1 scores 0.40 JOD less"), std::string::npos) << c[0].sentence;
    EXPECT_NE(cbr::reports::settingRule(kRoles, true).find("the highest JOD, a JOD within 0.02 JOD counting as a tie"),
              std::string::npos);
    bool rule = false, meaning = false;
    for (const auto& line : cbr::reports::sweepSummaryLines(pts, kRoles)) {
        rule = rule || (line.rfind("rule: ", 0) == 0 && line.find("against JOD (ColorVideoVDP") != std::string::npos);
        meaning = meaning || line == "quality: " + std::string(cbr::reports::kJodMeaning);
    }
    EXPECT_TRUE(rule);
    EXPECT_TRUE(meaning);
}

TEST(SweepJod, ToleranceRanksByJodWherePresent) {
    std::vector<SweepPoint> pts{point("cbr-aso", 6, 30, 0.02), point("cbr-cso", 6.0, 30.5, 0.02, 0.01),
                                point("cbr-cso", 6.1, 30.0, 0.02, 0.1)};
    EXPECT_DOUBLE_EQ(*cbr::reports::recommendTolerance(pts, kRoles)[0].tolerance, 0.01);  // by PSNR
    pts[0].jod = 9.3, pts[1].jod = 9.2, pts[2].jod = 9.4;
    const auto c = cbr::reports::recommendTolerance(pts, kRoles);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_DOUBLE_EQ(*c[0].tolerance, 0.1);
    EXPECT_NE(c[0].sentence.find("the best JOD, 9.40 JOD against cbr-aso's 9.30 JOD"), std::string::npos)
        << c[0].sentence;
    EXPECT_NE(c[0].sentence.find("while tolerance 0.01 loses 0.20 JOD"), std::string::npos) << c[0].sentence;
}

TEST(SweepJod, EqualCostComparesJods) {
    std::vector<SweepPoint> pts{withJod(point("drr", 4, 26, 0.05, {}, 0.5), 8.5),
                                withJod(point("drr", 8, 30, 0.03, {}, 1.0), 9.5),
                                withJod(point("cbr-aso", 6, 29, 0.02), 8.8)};
    auto eq = cbr::reports::equalCost(pts, {}, kRoles);
    ASSERT_EQ(eq.size(), 1u);
    EXPECT_NEAR(*eq[0].drr_jod, 9.0, 1e-12);
    // By PSNR checkerboard wins by 1 dB; by JOD it loses.
    EXPECT_NE(eq[0].verdict.find("with 9.00 JOD, PSNR 28.00 dB, SSIM 0.9000, ECI 0.0400, against 8.80 JOD, 29.00 dB"),
              std::string::npos) << eq[0].verdict;
    EXPECT_NE(eq[0].verdict.find(": checkerboard is worse by 0.20 JOD at equal cost."), std::string::npos)
        << eq[0].verdict;
    pts[2].jod = 8.95;
    eq = cbr::reports::equalCost(pts, {}, kRoles);
    EXPECT_NE(eq[0].verdict.find(": the same JOD at equal cost (within 0.10 JOD)."), std::string::npos) << eq[0].verdict;
}

namespace {

// A sweep's directory with only sweep.csv: the checkerboard variants, drr at two scales and
// full; `column`: sweep.csv has cvvdp_jod (sweeps from before ColorVideoVDP do not), `jods`: its cells.
std::filesystem::path sweepDir(const std::string& name, bool column, bool jods) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("cbr-sweep-jod-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::vector<std::string> columns = cbr::rundir::sweep::columns();
    if (!column) std::erase(columns, std::string(cbr::reports::kJodColumn));
    cbr::reports::CsvTable table(columns);
    struct Row {
        const char *config, *variant;
        double ms, psnr, jod;
        const char* setting;
        double value;
    };
    const Row rows[] = {{"full", "full", 10, INFINITY, 10, nullptr, 0},
                        {"drr_scale=0.5", "drr", 4, 26, 8.5, "drr_scale", 0.5},
                        {"drr_scale=1", "drr", 8, 30, 9.5, "drr_scale", 1},
                        {"cbr-aso", "cbr-aso", 6, 30, 9.3, nullptr, 0},
                        {"cbr-cso_tol=0.01", "cbr-cso", 6.0, 30.5, 9.2, "cso_tolerance", 0.01},
                        {"cbr-cso_tol=0.1", "cbr-cso", 6.1, 30.0, 9.4, "cso_tolerance", 0.1}};
    for (const auto& r : rows) {
        std::map<std::string, cbr::reports::Cell> row = {
            {"config", r.config}, {"variant", r.variant}, {"path", "orbit"},   {"reference", "full"},
            {"status", "ok"},     {"shading_cost", 1},    {"gpu_ms_median", r.ms}, {"psnr_db", r.psnr},
            {"ssim", 0.9},        {"eci", 0.02}};
        if (r.setting) row[r.setting] = r.value;
        if (jods) row[cbr::reports::kJodColumn] = r.jod;
        table.addRow(row);
    }
    std::ofstream(dir / "sweep.csv") << table.str();
    std::ofstream(dir / "run.json") << R"({"scene": {"name": "blocks"}, "path": {"name": "orbit"}})";
    return dir;
}

}  // namespace

// sweep.html: a JOD column, the JOD plane and rule where sweep.csv has JODs; a sweep.csv
// without the column, or with it empty, renders as before.
TEST(SweepJod, PageShowsJodWherePresentAndElseReadsAsBefore) {
    const auto old_dir = sweepDir("old", false, false), empty = sweepDir("empty", true, false);
    const std::string old_html = cbr::reports::sweepHtml(old_dir, kRoles);
    EXPECT_EQ(old_html.find("JOD"), std::string::npos);
    EXPECT_NE(old_html.find("cso-tolerance 0.01"), std::string::npos);  // by PSNR
    EXPECT_EQ(cbr::reports::sweepHtml(empty, kRoles), old_html);
    const auto dir = sweepDir("jod", true, true);
    const std::string html = cbr::reports::sweepHtml(dir, kRoles);
    for (const char* needle : {"cso-tolerance 0.1: the best JOD, 9.40 JOD against cbr-aso&#39;s 9.30 JOD",
                               "<th class=\"num\">ColorVideoVDP</th>", "<td class=\"num\">9.40 JOD</td>",
                               "JOD against median GPU time", "a higher JOD)", "those within 0.02 JOD of the best JOD",
                               "ColorVideoVDP (JOD, higher is better)", "checkerboard is better by 0.30 JOD at equal cost",
                               "<th class=\"num\">JOD</th>"})
        EXPECT_NE(html.find(needle), std::string::npos) << needle;
    EXPECT_NE(html.find(cbr::reports::esc(cbr::reports::kJodMeaning)), std::string::npos);
    for (const auto& d : {old_dir, empty, dir}) std::filesystem::remove_all(d);
}

namespace cbr::harness {
namespace {

// taau-scale and taau-blend change only taau (issue 17), and are checked like drr-scale.
TEST(SweepExpand, TaauParametersApplyOnlyToTaau) {
    auto configs = expandSweep({parseSweepParam("taau-scale=0.5,0.7071"), parseSweepParam("taau-blend=0.05,0.2")},
                               {"drr", "taau"});
    std::vector<std::string> labels;
    for (const auto& c : configs) labels.push_back(c.label);
    EXPECT_EQ(labels, (std::vector<std::string>{"full", "drr", "taau_tscale=0.5_blend=0.05", "taau_tscale=0.5_blend=0.2",
                                                "taau_tscale=0.7071_blend=0.05", "taau_tscale=0.7071_blend=0.2"}));
    EXPECT_THROW(parseSweepParam("taau-blend=0,0.5"), std::invalid_argument);
    EXPECT_THROW(parseSweepParam("taau-scale=1.5"), std::invalid_argument);
}

// --param cbr-history=quarter,full (issue 17): one configuration per history for each
// checkerboard variant that reads it; drr is not split, and cbr-clip (always the full
// history) does not take the parameter.
TEST(SweepExpand, CbrHistorySplitsTheCheckerboardVariantsOnly) {
    auto configs = expandSweep({parseSweepParam("cbr-history=quarter,full")}, {"drr", "cbr-aso", "cbr-cso"});
    std::vector<std::string> labels;
    for (const auto& c : configs) labels.push_back(c.label);
    EXPECT_EQ(labels, (std::vector<std::string>{"full", "drr", "cbr-aso_history=quarter", "cbr-aso_history=full",
                                                "cbr-cso_history=quarter", "cbr-cso_history=full"}));
    for (const auto& c : configs) {
        if (c.variant != "cbr-aso" && c.variant != "cbr-cso") {
            EXPECT_TRUE(c.settings.empty()) << c.label;
            continue;
        }
        ASSERT_EQ(c.settings.size(), 1u) << c.label;
        EXPECT_EQ(c.settings[0].name, "cbr-history") << c.label;
        EXPECT_EQ(c.settings[0].text(), c.label.substr(c.label.find('=') + 1)) << c.label;
    }
    EXPECT_THROW(parseSweepParam("cbr-history=half"), std::invalid_argument);
}

}  // namespace
}  // namespace cbr::harness
