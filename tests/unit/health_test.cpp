// Measurement health: warm-up steadiness, drift against the same poses, the machine's load
// per timed pass (harness/figures/health.h), on made-up series whose answer is known.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "harness/figures/health.h"
#include "harness/base/nvml.h"
#include "harness/figures/results.h"

namespace cbr::harness {
namespace {

// `repeats` repetitions of `frames` poses: a pose cost pattern times noise of relative sd `noise`.
VariantSamples series(int repeats, int frames, double noise, uint32_t seed = 7) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0, noise);
    VariantSamples c;
    for (int r = 0; r < repeats; ++r)
        for (int f = 0; f < frames; ++f) {
            const double pose = 10.0 + 3.0 * std::sin(f * 0.3);  // the path's own cost, the same every repetition
            c.ms.push_back(pose * std::exp(n(rng)));
            c.repeat.push_back(r);
            c.frame.push_back(f);
        }
    return c;
}

DriftResult drift(const VariantSamples& c) { return analyseDrift(c.ms, c.repeat, c.frame); }

TEST(WarmUp, SteadyOnlyWhenTheLastWindowMatchesTheOneBefore) {
    HealthRule rule;
    rule.warm_window = 4;
    rule.warm_tolerance = 0.03;
    EXPECT_FALSE(warmUpSteady({10, 10, 10, 10, 10, 10, 10}, rule));  // fewer than two windows
    EXPECT_TRUE(warmUpSteady({10, 10, 10, 10, 10.2, 9.9, 10.1, 10}, rule));
    // A GPU ramping its clocks: each window faster than the one before.
    EXPECT_FALSE(warmUpSteady({35, 33, 34, 32, 17.8, 8.1, 5.4, 5.4}, rule));
    EXPECT_FALSE(warmUpSteady({35, 33, 34, 32, 17.8, 8.1, 5.4, 5.4, 5.4, 5.3, 5.4, 5.4}, rule));  // 6.75 against 5.4
    EXPECT_TRUE(warmUpSteady({35, 33, 34, 32, 17.8, 8.1, 5.4, 5.4, 5.4, 5.3, 5.4, 5.4, 5.5, 5.4, 5.3, 5.4}, rule));
}

TEST(Drift, QuietRepetitionsAreSteady) {
    for (uint32_t seed = 1; seed <= 20; ++seed) {
        const DriftResult d = drift(series(5, 60, 0.03, seed));
        ASSERT_TRUE(d.tested);
        EXPECT_FALSE(d.unsteady) << "seed " << seed << ": " << d.note;
        EXPECT_NEAR(d.noise, 0.03, 0.012);
    }
}

TEST(Drift, ARepetitionAtTwiceTheTimeIsUnsteadyAndNamed) {
    VariantSamples c = series(5, 60, 0.03);
    for (size_t i = 0; i < c.ms.size(); ++i)
        if (c.repeat[i] == 0) c.ms[i] *= 2.0;  // a busy machine during the first repetition
    const DriftResult d = drift(c);
    ASSERT_TRUE(d.unsteady);
    ASSERT_TRUE(d.worst);
    EXPECT_TRUE(d.worst->whole_repetition);
    EXPECT_EQ(d.worst->repeat, 0);
    EXPECT_NEAR(d.worst->ratio, 2.0, 0.1);
    EXPECT_NE(d.note.find("repetition 1 of 5"), std::string::npos) << d.note;
}

TEST(Drift, AClockRampInTheFirstFramesIsUnsteady) {
    VariantSamples c = series(5, 30, 0.003);
    const double ramp[] = {6.0, 5.0, 4.8, 3.0, 1.5};  // full's first frames after the GPU idled
    for (size_t i = 0; i < c.ms.size(); ++i)
        if (c.repeat[i] == 0 && c.frame[i] < 5) c.ms[i] *= ramp[c.frame[i]];
    const DriftResult d = drift(c);
    ASSERT_TRUE(d.unsteady);
    EXPECT_FALSE(d.worst->whole_repetition);
    EXPECT_EQ(d.worst->repeat, 0);
    EXPECT_EQ(d.worst->first_frame, 0);
    EXPECT_GT(d.worst->ratio, 3.0);
}

TEST(Drift, OneRepetitionIsNotTestedAndSaysWhy) {
    const DriftResult d = drift(series(1, 30, 0.01));
    EXPECT_FALSE(d.tested);
    EXPECT_FALSE(d.unsteady);
    EXPECT_FALSE(d.why_not.empty());
}

TEST(Drift, NoiseRaisesTheLimitSoNoisyButSteadyRunsPass) {
    const DriftResult d = drift(series(5, 60, 0.08));
    EXPECT_FALSE(d.unsteady) << d.note;
    EXPECT_GT(d.span_limit, healthRule().span_floor);
}

TEST(MachineLoad, OtherProcessesAreTheMachineLessThisProcess) {
    // Two cores: cbrbench uses 1.8 of them for the first second, then another process takes
    // one core while cbrbench drops to 1.0.
    std::vector<MachineSample> s;
    double busy = 0, own = 0;
    for (int i = 0; i <= 20; ++i) {
        MachineSample m;
        m.t = i * 0.1;
        m.cpu_busy_s = busy;
        m.own_cpu_s = own;
        s.push_back(m);
        const bool contended = i >= 10;
        own += (contended ? 1.0 : 1.8) * 0.1;
        busy += (contended ? 2.0 : 1.85) * 0.1;
    }
    const WindowLoad quiet = windowLoad(s, {"full", 0, 0.0, 1.0});
    EXPECT_NEAR(quiet.own_cores, 1.8, 1e-9);
    EXPECT_NEAR(quiet.other_cores, 0.05, 1e-9);
    const WindowLoad contended = windowLoad(s, {"full", 1, 1.0, 2.0});
    EXPECT_NEAR(contended.own_cores, 1.0, 1e-9);
    EXPECT_NEAR(contended.other_cores, 1.0, 1e-9);
}

TEST(MachineLoad, ClocksAndSlowdownsInsideTheWindowOnly) {
    std::vector<MachineSample> s(5);
    const double sm[] = {345, 1980, 1755, 1980, 345};
    for (int i = 0; i < 5; ++i) {
        s[i].t = i;
        s[i].gpu.sm_clock_mhz = sm[i];
        s[i].gpu.throttle_reasons = i == 2 ? 0x40 : 0x1;  // hw thermal slowdown inside; idle outside
    }
    const WindowLoad w = windowLoad(s, {"full", 0, 0.5, 3.5});
    EXPECT_EQ(*w.sm_min_mhz, 1755);
    EXPECT_EQ(*w.sm_max_mhz, 1980);
    EXPECT_TRUE(w.slowdown);
}

TEST(Nvml, ThrottleReasonsAndUuid) {
    EXPECT_EQ(throttleReasonNames(0x41), (std::vector<std::string>{"gpu_idle", "hw_thermal_slowdown"}));
    EXPECT_FALSE(throttleSlowsDown(0x1 | 0x4));  // idle and the software power cap: not a slowdown
    EXPECT_TRUE(throttleSlowsDown(0x8));
    const uint8_t b[16] = {0x12, 0x34, 0x56, 0x78, 0x9a, 0xbc, 0xde, 0xf0, 0, 1, 2, 3, 4, 5, 6, 7};
    EXPECT_EQ(nvmlUuid(b), "GPU-12345678-9abc-def0-0001-020304050607");
    // No libnvidia-ml here (or no such GPU): not available, with a reason, never an error.
    Nvml nvml("GPU-00000000-0000-0000-0000-000000000000");
    EXPECT_FALSE(nvml.available());
    EXPECT_FALSE(nvml.reason().empty());
}

}  // namespace
}  // namespace cbr::harness
