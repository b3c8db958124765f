// The settings table's rows as CLI11 options (options.h).
#include "settings/options.h"

#include <stdexcept>

namespace cbr::settings {

std::string optionHelp(const Row& row) { return std::string(row.help) + " (" + accepted(row) + ")"; }

CLI::Option* addOption(CLI::App* cmd, const Row& row, Tunables& t) {
    auto* opt = cmd->add_option_function<std::string>(
        "--" + std::string(row.name),
        [&row, &t](const std::string& value) {
            try {
                setText(row, t, value);
            } catch (const std::invalid_argument& e) {
                throw CLI::ValidationError(e.what());
            }
        },
        optionHelp(row));
    opt->default_str(text(row, Tunables{}));
    opt->type_name(row.type == Type::Text ? "SPEC" : row.type == Type::Word ? "WORD" : row.type == Type::Int ? "INT" : "FLOAT");
    return opt;
}

void addOptions(CLI::App* cmd, Tunables& t) {
    for (const auto& row : table()) addOption(cmd, row, t);
}

}  // namespace cbr::settings
