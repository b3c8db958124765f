// A run's frame rows streamed through the spill into frames.csv: the same bytes, NaN count
// and NaN places as a table of the same rows held in memory (how frames.csv was written
// before rows were streamed), and the digest's numbers the rows' own.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "harness/output/frame_rows.h"

namespace cbr::harness {
namespace {

std::string slurp(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Rows as a run makes them, with what frames.csv must carry through: passes that differ per
// variant and first appear late, invocation counts on some passes only, stats on checkerboard
// rows, NaN and +inf, notes to be quoted, failed rows without passes, a variant with no ok row.
std::vector<FrameRow> sampleRows() {
    std::vector<FrameRow> rows;
    int n = 0;
    for (int rep = 0; rep < 2; ++rep)
        for (const char* variant : {"full", "cbr-aso", "drr", "broken"})
            for (int frame = 0; frame < 7; ++frame, ++n) {
                FrameRow r;
                r.variant = variant;
                r.repeat = rep;
                r.frame = frame;
                r.time_s = frame / 60.0;
                if (std::string(variant) == "broken") {
                    r.status = "failed";
                    r.note = "device lost, \"vkQueueSubmit\"";
                    rows.push_back(r);
                    continue;
                }
                r.render_width = 64;
                r.render_height = 36;
                r.gpu_ms = n % 9 == 0 ? std::nan("") : 1.0 + 0.01 * n;
                r.timing_ok = n % 5 != 0;
                r.passes.push_back({"opaque", 0.5 + 0.001 * n, std::string(variant) == "drr" ? -1 : 1000 + n});
                if (frame >= 3 || rep == 1) r.passes.push_back({"tonemap_" + std::string(variant), 0.1, -1});
                if (std::string(variant) == "cbr-aso") r.stats = {{"px_shaded", 0.5}, {"px_reused", n % 4 ? 0.25 : NAN}};
                if (rep == 0) {
                    r.quality.psnr_db = std::string(variant) == "full" ? INFINITY : 30.0 + frame;
                    r.quality.ssim = frame == 4 ? std::nan("") : 0.9;
                    r.quality.mse = 0.001 * frame;
                    if (frame > 0) r.quality.eci = 0.01 * frame, r.quality.crawl_numerator = frame, r.quality.crawl_denominator = 10;
                    if (frame == 2) r.quality.note = "no reference edges, so no crawl;\nsee metrics.md";
                }
                if (!r.timing_ok) r.note = "pass times do not sum to the frame time";
                rows.push_back(r);
            }
    return rows;
}

TEST(FrameRows, StreamedFramesCsvIsTheTableOfTheRows) {
    const auto dir = std::filesystem::path(::testing::TempDir()) / "frame_rows_test";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    const auto rows = sampleRows();

    FrameDigest digest;
    {
        FramesSpill spill(dir / kFramesSpill, 64, 36);
        for (const auto& r : rows) spill.append(r), digest.add(r);
        spill.close();
    }
    const NanCells nan = writeFramesCsv(dir / "frames.csv", dir / kFramesSpill, digest.columns);
    EXPECT_FALSE(std::filesystem::exists(dir / kFramesSpill));
    EXPECT_FALSE(std::filesystem::exists(dir / "frames.csv.tmp"));

    reports::CsvTable held(framesCsvColumns(digest.columns));
    for (const auto& r : rows) held.addRow(frameCells(r, 64, 36));
    EXPECT_EQ(slurp(dir / "frames.csv"), held.str());
    EXPECT_EQ(nan.count, held.nanCells());
    EXPECT_EQ(nan.where, held.nanWhere());
    EXPECT_GT(nan.count, 10u);  // more than the ten places named

    // The columns: stats and passes in first-seen order; invocations only where reported.
    EXPECT_EQ(digest.columns.stats, (std::vector<std::string>{"px_shaded", "px_reused"}));
    EXPECT_EQ(digest.columns.passes,
              (std::vector<std::string>{"opaque", "tonemap_full", "tonemap_cbr-aso", "tonemap_drr"}));
    EXPECT_EQ(digest.columns.fs_reported, (std::set<std::string>{"opaque"}));
    EXPECT_EQ(digest.rows, rows.size());
    EXPECT_EQ(digest.find("broken"), nullptr);  // no ok row: "no frame completed"

    // The digest holds each ok row's numbers in row order.
    const VariantSamples* aso = digest.find("cbr-aso");
    ASSERT_NE(aso, nullptr);
    std::vector<double> ms;
    for (const auto& r : rows)
        if (r.variant == "cbr-aso") ms.push_back(r.gpu_ms);
    ASSERT_EQ(aso->ms.size(), ms.size());
    for (size_t i = 0; i < ms.size(); ++i)
        EXPECT_TRUE(aso->ms[i] == ms[i] || (std::isnan(aso->ms[i]) && std::isnan(ms[i]))) << i;
    EXPECT_EQ(aso->repeat.size(), ms.size());
    EXPECT_EQ(aso->eci.size(), 6u);
    EXPECT_DOUBLE_EQ(aso->crawl_num, 21.0);
}

TEST(FrameRows, ACutShortSpillIsAnErrorNamingIt) {
    const auto dir = std::filesystem::path(::testing::TempDir()) / "frame_rows_cut";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    FrameDigest digest;
    {
        FramesSpill spill(dir / kFramesSpill, 64, 36);
        for (const auto& r : sampleRows()) spill.append(r), digest.add(r);
        spill.close();
    }
    std::filesystem::resize_file(dir / kFramesSpill, std::filesystem::file_size(dir / kFramesSpill) - 3);
    try {
        writeFramesCsv(dir / "frames.csv", dir / kFramesSpill, digest.columns);
        FAIL() << "a cut spill was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(kFramesSpill), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "frames.csv"));
    EXPECT_FALSE(std::filesystem::exists(dir / "frames.csv.tmp"));
}

}  // namespace
}  // namespace cbr::harness
