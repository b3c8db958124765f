// The settings table: one row per tunable, with every fact the command line, the checks,
// sweep, the CSV and JSON writers, compare's key, the plan hash and the docs read. Adding a
// setting is adding a row here and its field in settings.h (tests/unit/settings_table_test.cpp
// checks each of those places for every row).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "settings/settings.h"

namespace cbr::settings {

enum class Type { Int, Real, Word, Text };  // Text: a structured value (the display model)

// How a row enters the plan hash (harness/matrix.cpp): settings added after plans were first
// hashed enter it only away from their default, so older plans keep their hash.
enum class Hash { Always, UnlessDefault, Never };

// How a row reads and writes its Tunables field: numbers as themselves, words as their index.
struct Field {
    double (*get)(const Tunables&);
    void (*set)(Tunables&, double);
};
// A Text row's field: its text (parsed back by set, which throws std::invalid_argument with the
// accepted forms) and what run.json writes.
struct TextField {
    std::string (*get)(const Tunables&) = nullptr;
    void (*set)(Tunables&, const std::string&) = nullptr;
    nlohmann::json (*json)(const Tunables&) = nullptr;
};

struct Row {
    const char* name;    // --NAME and sweep's --param NAME (kebab-case)
    const char* column;  // CSV column and JSON key (snake_case)
    const char* help;
    Type type;
    std::vector<const char*> words;  // Word: the accepted words, in the enum's order
    double min = 0, max = 0;         // Int, Real: the accepted range...
    bool min_open = false, max_open = false;  // ...with open ends where set
    std::vector<double> only;        // Int: the accepted values, where only a few are
    std::vector<const char*> variants;  // the variants it changes (empty: every variant)
    const char* sweep = nullptr;     // its short name in sweep's configuration labels; null: not swept
    bool outer = false;              // swept as one sweep per value (the reference is rendered once a run)
    int compare_key = 0;             // its place in compare's key (compare.csv's settings cell); 0: not in it
    Hash hash = Hash::Always;
    bool run_json = true;            // in run.json's settings object
    bool json_float = false;         // the renderer holds it as a float: run.json writes that float
    Field field{};
    TextField text_field{};  // Text rows only (their `field` is unset)
};

// Every row, in the order the help, sweep's labels and the columns list them.
const std::vector<Row>& table();
// The row named NAME (--NAME), or null.
const Row* find(std::string_view name);

// The rows in compare's key, in its order.
std::vector<const Row*> compareKey();

// "a, b or c" for a word row; "a number in (0, 1]" for a number row: what --NAME accepts.
std::string accepted(const Row& row);

// A value as the help and messages write it: a word as typed, a number as the shortest text
// that reads back as it.
std::string text(const Row& row, const Tunables& t);
// A value as run.json and the plan hash write it: an integer, a number or a word.
nlohmann::json toJson(const Row& row, const Tunables& t);
bool isDefault(const Row& row, const Tunables& t);

// Sets the row's field from what the user typed. Throws std::invalid_argument with one line:
// "--NAME TEXT: expected ... (default D)".
void setText(const Row& row, Tunables& t, const std::string& text);
// Sets a number row's field; throws like setText where the value is outside the range.
void setNumber(const Row& row, Tunables& t, double value);
// Whether a number is what the row accepts (range, integers, `only`).
bool acceptsNumber(const Row& row, double value);

// Every row's value checked against what it accepts (for Tunables made in code); throws like
// setText for the first that is not.
void check(const Tunables& t);

// Whether the row changes `variant` (outer rows change none).
bool appliesTo(const Row& row, std::string_view variant);

}  // namespace cbr::settings
