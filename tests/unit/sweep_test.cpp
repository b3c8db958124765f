// Sweep specs, their expansion, the tolerance recommendation and quality at equal cost.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "harness/sweep.h"
#include "reports/sweep.h"

using cbr::harness::expandSweep;
using cbr::harness::parseSweepParam;
using cbr::reports::SweepPoint;

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
                            "drr-scale=inf", "cso-tolerance=0.1:1:lin:2.5"}) {
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
                                                "cbr-cso_tol=0.1", "cbr-cso_tol=1"}));
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
    p.cso_tolerance = tol;
    p.drr_scale = scale;
    return p;
}

}  // namespace

TEST(SweepRecommend, BestPsnrWithinTheCostMarginOfAso) {
    std::vector<SweepPoint> pts{point("full", 10, INFINITY, 0), point("cbr-aso", 6, 30, 0.02),
                                point("cbr-cso", 6.1, 30.2, 0.02, 0.01), point("cbr-cso", 6.2, 30.5, 0.02, 0.1),
                                point("cbr-cso", 7.0, 31.0, 0.02, 1)};  // best PSNR but 17% dearer
    auto choices = cbr::reports::recommendTolerance(pts);
    ASSERT_EQ(choices.size(), 1u);
    EXPECT_DOUBLE_EQ(*choices[0].tolerance, 0.1);
    EXPECT_NE(choices[0].sentence.find("within 5% of cbr-aso"), std::string::npos) << choices[0].sentence;
    EXPECT_EQ(choices[0].sentence.find('\n'), std::string::npos);
}

TEST(SweepRecommend, PsnrTiesGoToLowerEciThenLargerTolerance) {
    std::vector<SweepPoint> pts{point("cbr-aso", 6, 30, 0.02), point("cbr-cso", 6, 30.01, 0.030, 0.01),
                                point("cbr-cso", 6, 30.00, 0.025, 0.1), point("cbr-cso", 6, 30.00, 0.025, 0.3)};
    auto choices = cbr::reports::recommendTolerance(pts);
    ASSERT_EQ(choices.size(), 1u);
    EXPECT_DOUBLE_EQ(*choices[0].tolerance, 0.3);
}

TEST(SweepEqualCost, InterpolatesTheDrrScaleAtTheCheckerboardTime) {
    std::vector<SweepPoint> pts{point("drr", 4, 26, 0.05, {}, 0.5), point("drr", 8, 30, 0.03, {}, 1.0),
                                point("cbr-aso", 6, 29, 0.02)};
    auto eq = cbr::reports::equalCost(pts, {});
    ASSERT_EQ(eq.size(), 1u);
    EXPECT_TRUE(eq[0].matched);
    EXPECT_NEAR(*eq[0].drr_scale, 0.75, 1e-12);
    EXPECT_NEAR(*eq[0].drr_psnr, 28, 1e-12);
    EXPECT_NE(eq[0].verdict.find("better by 1.00 dB"), std::string::npos) << eq[0].verdict;
}

TEST(SweepEqualCost, OutsideTheDrrRangeMakesNoClaim) {
    std::vector<SweepPoint> pts{point("drr", 4, 26, 0.05, {}, 0.5), point("drr", 8, 30, 0.03, {}, 1.0),
                                point("cbr-aso", 12, 29, 0.02)};
    auto eq = cbr::reports::equalCost(pts, {});
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
