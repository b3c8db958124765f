// The settings' columns from the settings table (setting_columns.h).
#include "rundir/setting_columns.h"

#include <stdexcept>
#include <string>

namespace cbr::rundir {

const char* settingColumn(std::string_view setting) {
    const settings::Row* row = settings::find(setting);
    if (!row) throw std::logic_error("rundir: no setting " + std::string(setting) + " in the settings table");
    return row->column;
}

std::vector<const settings::Row*> runJsonSettings() {
    std::vector<const settings::Row*> out;
    for (const auto& row : settings::table())
        if (row.run_json) out.push_back(&row);
    return out;
}

bool isNumber(const settings::Row& row) { return row.type == settings::Type::Int || row.type == settings::Type::Real; }

}  // namespace cbr::rundir
