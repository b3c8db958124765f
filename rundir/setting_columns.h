// The settings' CSV columns and run.json keys are the settings table's (settings/table.h,
// Row::column): the run directory's schema names them through the table, never again.
#pragma once

#include <string_view>
#include <vector>

#include "settings/table.h"

namespace cbr::rundir {

// The column of the setting --NAME (kebab-case, as the table names it). Throws std::logic_error
// for a name the table lacks: a schema that names a setting the table dropped.
const char* settingColumn(std::string_view setting);

// The settings run.json's settings object holds (Row::run_json), in the table's order.
std::vector<const settings::Row*> runJsonSettings();
// Whether run.json holds a setting as a number (Int and Real rows), else a word or an object.
bool isNumber(const settings::Row& row);

}  // namespace cbr::rundir
