// sweep.csv's ordered columns (sweep_csv.h).
#include "rundir/sweep_csv.h"

#include <algorithm>

#include "rundir/pixel_classes.h"
#include "rundir/setting_columns.h"

namespace cbr::rundir::sweep {

const char* referenceColumn() { return settingColumn("reference"); }
const char* shadingCostColumn() { return settingColumn("shading-cost"); }

const std::vector<const settings::Row*>& settingRows() {
    static const std::vector<const settings::Row*> rows = [] {
        std::vector<const settings::Row*> out;
        for (const auto& row : settings::table())
            if (row.sweep && !row.outer && !row.variants.empty()) out.push_back(&row);
        return out;
    }();
    return rows;
}

const std::vector<std::string>& columns() {
    static const std::vector<std::string> cols = [] {
        std::vector<std::string> out = {kConfig, kVariant, kPath, referenceColumn(), kPipeline, shadingCostColumn()};
        for (const settings::Row* row : settingRows()) out.push_back(row->column);
        for (const char* c : {kStatus, kNote, kFrames, kRepeats, kGpuMsMedian, kGpuMsCiLow, kGpuMsCiHigh, kNoiseCv,
                              kSpeedup, kSpeedupLow, kSpeedupHigh, kPsnrDb, kSsim, kEci, kFlickerRatio, kCvvdpJod})
            out.push_back(c);
        for (const char* c : pixels::kClasses) out.push_back(c);
        return out;
    }();
    return cols;
}

bool isTextColumn(const std::string& column) {
    for (const char* c : {kConfig, kVariant, kPath, referenceColumn(), kPipeline, kStatus, kNote})
        if (column == c) return true;
    return std::any_of(settingRows().begin(), settingRows().end(), [&](const settings::Row* row) {
        return row->type == settings::Type::Word && column == row->column;
    });
}

}  // namespace cbr::rundir::sweep
