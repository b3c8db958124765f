// Every run.json key of the schema as a flattened path, for the tests that hold real runs to it
// (tests/render/rundir_schema_test.cpp): "device.name", "variants[].passes[].ran", "x[]" for an
// array. A placeholder in angle brackets ("variants[].settings.<param>") stands for any one key.
#pragma once

#include <string>
#include <vector>

namespace cbr::rundir::run {

struct KeyPath {
    std::string path;
    const char* only_when = nullptr;  // null: every run writes it; else when it is written
};

// A run's run.json (`cbrbench run`, sweep's runs).
std::vector<KeyPath> runJsonKeys();
// score-seq's run.json.
std::vector<KeyPath> sequenceJsonKeys();

// Whether a written path is the schema's (a placeholder matching any one key).
bool matches(const std::string& schema_path, const std::string& written_path);

}  // namespace cbr::rundir::run
