// Shared by the fuzz targets: a per-process scratch file, and the checks that turn a broken
// contract into a crash libFuzzer records (with the input that caused it).
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <unistd.h>

namespace cbr::fuzz {

[[noreturn]] inline void bug(const std::string& what) {
    std::fprintf(stderr, "\ncbr-fuzz: contract broken: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

inline void require(bool ok, const std::string& what) {
    if (!ok) bug(what);
}

// One directory per process (libFuzzer -jobs/-fork run several), removed at exit.
// Never destroyed, so the exit handler can still read it.
inline const std::filesystem::path& scratchDir() {
    static const std::filesystem::path* dir = [] {
        std::string templ = (std::filesystem::temp_directory_path() / "cbr-fuzz-XXXXXX").string();
        if (!mkdtemp(templ.data())) bug("cannot create a scratch directory like " + templ);
        auto* made = new std::filesystem::path(templ);
        std::atexit([] { std::error_code ec; std::filesystem::remove_all(scratchDir(), ec); });
        return made;
    }();
    return *dir;
}

inline std::filesystem::path writeScratch(const std::string& name, const uint8_t* data, size_t size) {
    const std::filesystem::path file = scratchDir() / name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) bug("cannot write " + file.string());
    return file;
}

// The error contract (STYLE.md): one non-empty line.
inline void checkMessage(const std::invalid_argument& e) {
    const std::string what = e.what();
    require(!what.empty(), "std::invalid_argument with an empty message");
    require(what.find_first_of("\n\r") == std::string::npos, "message is not one line: " + what);
}

// Any exception other than std::invalid_argument escaping a parser is a bug.
template <class F>
void expectOnlyInvalidArgument(const char* call, F&& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        checkMessage(e);
    } catch (const std::exception& e) {
        bug(std::string(call) + " threw " + typeid(e).name() + " (not std::invalid_argument): " + e.what());
    } catch (...) {
        bug(std::string(call) + " threw a non-std exception");
    }
}

inline bool finite(double v) { return std::isfinite(v); }

}  // namespace cbr::fuzz
