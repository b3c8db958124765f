// The largest scene the tests make (issue 16): 1M triangles and 50 PNG textures through
// `cbrbench run` on lavapipe with the validation layer on; run.json's and the report's
// load figures. CBR_BIG_SCENE_DIR=DIR writes the scene there for measurements (docs/history).
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "renderer/vk/sanitizers.h"
#include "tests/render/bench_runner.h"
#include "tests/support/big_scene.h"

namespace cbr::test {
namespace {

// The "Loading large scenes" figures (docs/history/development-record.md) use this spec (texture size 512 and 1024).
testsupport::BigSceneSpec bigSpec() {
    testsupport::BigSceneSpec spec;  // 50 meshes of 100x100 quads: 1,000,000 triangles
    spec.textures = 50;
    spec.texture_size = 512;
    if (const char* size = std::getenv("CBR_BIG_SCENE_TEXTURE_SIZE")) spec.texture_size = std::atoi(size);
    return spec;
}

TEST(BigScene, LoadFiguresInRunJsonReportAndStderr) {
    const auto work = scratchDir("big-scene-files");
    const testsupport::BigSceneSpec spec = bigSpec();
    const auto files = testsupport::writeBigScene(work, "big", spec);
    ASSERT_EQ(files.triangles, 1000000);
    auto r = runValidated("big-scene", {"--scene", files.gltf.string(), "--res", "96x54", "--frames", "2", "--variants",
                                        "full", "--path", "orbit"});
    ASSERT_EQ(r.result.exit_code, 0) << r.result.err;
    const auto& s = r.run["scene"];
    EXPECT_EQ(s["triangles"], 1000000);
    EXPECT_EQ(s["draws"], 50);
    EXPECT_EQ(s["materials"], 50);
    EXPECT_EQ(s["textures"], 50);
    const uint64_t texture_bytes = uint64_t(spec.textures) * uint64_t(spec.texture_size) * uint64_t(spec.texture_size) * 4;
    EXPECT_EQ(s["texture_bytes"].get<uint64_t>(), texture_bytes);
    EXPECT_GT(s["texture_gpu_bytes"].get<uint64_t>(), texture_bytes);
    EXPECT_GT(s["load_s"].get<double>(), 0.0);
    EXPECT_GT(s["upload_s"].get<double>(), 0.0);
    // The decoded textures and the 32-byte vertices stay resident while loading.
    const double held_mib = double(texture_bytes + 50ull * 101 * 101 * 32) / 1048576.0;
    EXPECT_GT(s["peak_rss_mib_loaded"].get<double>(), held_mib);
    EXPECT_GE(s["peak_rss_mib_end"].get<double>(), s["peak_rss_mib_loaded"].get<double>());
    EXPECT_NE(r.result.err.find("scene big: 1000000 triangles, 50 draws, 50 materials, 50 textures"), std::string::npos)
        << r.result.err;
    const std::string report = slurp(r.dir / "report.html");
    EXPECT_NE(report.find("texture MiB (RGBA8 / with mips)"), std::string::npos);
    EXPECT_NE(report.find("peak RSS loaded / at end (MiB)"), std::string::npos);
    std::filesystem::remove_all(work);
}

// The kernel's transparent-huge-page mode, "" where unknown.
std::string thpMode() {
    const std::string line = slurp("/sys/kernel/mm/transparent_hugepage/enabled");
    size_t open = line.find('['), close = line.find(']');
    return open != std::string::npos && close > open ? line.substr(open + 1, close - open - 1) : "";
}

// cbrbench asks for huge pages where the kernel gives them only to memory that asks
// ("madvise"), by starting itself again with glibc's tunable, and not when told not to.
TEST(ProcessMemory, HeapHugePagesWhereTheKernelWantsThemAskedForAndOffOnRequest) {
    const std::string mode = thpMode();
#if defined(CBR_SANITIZED)
    const bool sanitized = true;  // the sanitizer's allocator, not glibc's: nothing to ask
#else
    const bool sanitized = false;
#endif
    const auto work = scratchDir("process-memory");
    for (const bool off : {false, true}) {
        const auto out = work / (off ? "off" : "on");
        auto r = runBench({"run", "--scene", "blocks", "--res", "64x48", "--frames", "2", "--repeat", "1", "--warmup",
                           "0", "--variants", "full", "--validate", "--quiet", "--out", out.string()},
                          work, off ? std::vector<std::string>{"CBR_HUGE_PAGES=0"} : std::vector<std::string>{});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const auto m = readJson(out / "run.json")["host"]["memory"];
        EXPECT_EQ(m["keeps_freed_memory"], true);
        EXPECT_EQ(m["transparent_huge_pages"], mode.empty() ? "unknown" : mode);
        const bool expected = mode == "always" || (mode == "madvise" && !off && !sanitized);
        EXPECT_EQ(m["heap_huge_pages"], expected) << "THP mode " << mode << (off ? ", CBR_HUGE_PAGES=0" : "");
    }
    std::filesystem::remove_all(work);
}

// Not a check: writes the scene for the load measurements and skips otherwise.
TEST(BigScene, WriteForMeasurement) {
    const char* dir = std::getenv("CBR_BIG_SCENE_DIR");
    if (!dir || !*dir) GTEST_SKIP() << "set CBR_BIG_SCENE_DIR=DIR (and CBR_BIG_SCENE_TEXTURE_SIZE) to write the scene";
    const auto files = testsupport::writeBigScene(dir, "big", bigSpec());
    std::printf("wrote %s: %d triangles, %d textures, %.1f MiB of files\n", files.gltf.c_str(), files.triangles,
                files.textures, double(files.file_bytes) / 1048576.0);
}

}  // namespace
}  // namespace cbr::test
