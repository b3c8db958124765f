// Listing and matching image sequences for score-seq (sequence_files.h).
#include "harness/score/sequence_files.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>

namespace cbr::harness {

namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// One %d or %0Nd in a file name: what comes before and after, and the field width (0: any).
struct Pattern {
    std::string prefix, suffix;
    size_t width = 0;
};

bool parsePattern(const std::string& name, Pattern& p, const std::string& spec, const std::string& what) {
    size_t pos = name.find('%');
    if (pos == std::string::npos) return false;
    size_t i = pos + 1;
    size_t width = 0;
    if (i < name.size() && name[i] == '0') {
        ++i;
        while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i]))) width = width * 10 + size_t(name[i++] - '0');
        if (width == 0 || width > 9) i = name.size();  // refused below
    }
    if (i >= name.size() || name[i] != 'd' || name.find('%', i + 1) != std::string::npos)
        throw SequenceError(kSeqBadOption, what + " " + spec +
                                               ": a pattern needs exactly one %d or %0Nd (N 1 to 9) in the file name, "
                                               "e.g. frames/frame_%04d.png");
    p.prefix = name.substr(0, pos);
    p.suffix = name.substr(i + 1);
    p.width = width;
    return true;
}

bool matchNumber(const std::string& name, const Pattern& p, long& number) {
    if (name.size() <= p.prefix.size() + p.suffix.size()) return false;
    if (name.compare(0, p.prefix.size(), p.prefix) != 0) return false;
    if (name.compare(name.size() - p.suffix.size(), p.suffix.size(), p.suffix) != 0) return false;
    const std::string digits = name.substr(p.prefix.size(), name.size() - p.prefix.size() - p.suffix.size());
    if (digits.empty() || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); }))
        return false;
    // %04d writes at least 4 digits, with leading zeros only up to that width.
    if (p.width && (digits.size() < p.width || (digits.size() > p.width && digits[0] == '0'))) return false;
    if (!p.width && digits.size() > 1 && digits[0] == '0') return false;
    number = std::stol(digits);
    return true;
}

}  // namespace

const std::vector<std::string>& sequenceExtensions() {
    static const std::vector<std::string> kExt = {".png", ".exr", ".tif", ".tiff", ".jpg", ".jpeg", ".hdr",
                                                  ".bmp", ".tga", ".dpx", ".webp", ".ppm", ".pgm", ".pnm"};
    return kExt;
}

bool naturalLess(const std::string& a, const std::string& b) {
    size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        const bool da = std::isdigit(static_cast<unsigned char>(a[i])), db = std::isdigit(static_cast<unsigned char>(b[j]));
        if (da && db) {
            size_t i0 = i, j0 = j;
            while (i < a.size() && std::isdigit(static_cast<unsigned char>(a[i]))) ++i;
            while (j < b.size() && std::isdigit(static_cast<unsigned char>(b[j]))) ++j;
            std::string x = a.substr(i0, i - i0), y = b.substr(j0, j - j0);
            x.erase(0, std::min(x.find_first_not_of('0'), x.size()));
            y.erase(0, std::min(y.find_first_not_of('0'), y.size()));
            if (x.size() != y.size()) return x.size() < y.size();
            if (x != y) return x < y;
            continue;
        }
        if (a[i] != b[j]) return a[i] < b[j];
        ++i, ++j;
    }
    if ((a.size() - i) != (b.size() - j)) return a.size() - i < b.size() - j;
    return a < b;
}

Sequence listSequence(const std::string& spec, const std::string& what) {
    Sequence s;
    s.spec = spec;
    std::error_code ec;
    if (spec.empty()) throw SequenceError(kSeqBadOption, what + ": empty; accepted: a folder or a %04d pattern");
    const fs::path given(spec);
    Pattern p;
    if (parsePattern(given.filename().string(), p, spec, what)) {
        s.pattern = true;
        fs::path dir = given.parent_path().empty() ? fs::path(".") : given.parent_path();
        if (!fs::is_directory(dir, ec))
            throw SequenceError(kSeqFile, what + " " + spec + ": folder " + dir.string() + " does not exist");
        for (const auto& e : fs::directory_iterator(dir, ec)) {
            long n = 0;
            if (e.is_regular_file(ec) && matchNumber(e.path().filename().string(), p, n)) s.frames.push_back({n, e.path()});
        }
        std::sort(s.frames.begin(), s.frames.end(),
                  [](const SequenceFrame& a, const SequenceFrame& b) { return a.number < b.number; });
        for (size_t i = 1; i < s.frames.size(); ++i)
            if (s.frames[i].number == s.frames[i - 1].number)
                throw SequenceError(kSeqFile, what + " " + spec + ": frame " + std::to_string(s.frames[i].number) +
                                                  " matches two files (" + s.frames[i - 1].file.filename().string() +
                                                  ", " + s.frames[i].file.filename().string() + ")");
    } else {
        if (!fs::exists(given, ec)) throw SequenceError(kSeqFile, what + " " + spec + ": no such folder");
        if (!fs::is_directory(given, ec))
            throw SequenceError(kSeqFile, what + " " + spec +
                                              ": not a folder; accepted: a folder of images or a pattern with %04d "
                                              "(one image pair: cbrbench score)");
        std::vector<fs::path> files;
        for (const auto& e : fs::directory_iterator(given, ec)) {
            const auto& ext = sequenceExtensions();
            if (e.is_regular_file(ec) && std::find(ext.begin(), ext.end(), lower(e.path().extension().string())) != ext.end())
                files.push_back(e.path());
        }
        std::sort(files.begin(), files.end(),
                  [](const fs::path& a, const fs::path& b) { return naturalLess(a.filename().string(), b.filename().string()); });
        for (size_t i = 0; i < files.size(); ++i) s.frames.push_back({long(i), files[i]});
    }
    if (s.frames.empty())
        throw SequenceError(kSeqFile, what + " " + spec + ": no images" +
                                          (s.pattern ? std::string(" match the pattern")
                                                     : " (files ending .png, .exr, .tif, .jpg, ...)"));
    return s;
}

std::vector<fs::path> matchSequence(const Sequence& reference, const Sequence& other, const std::string& what) {
    std::vector<fs::path> out;
    if (reference.pattern && other.pattern) {
        std::map<long, fs::path> by_number;
        for (const auto& f : other.frames) by_number[f.number] = f.file;
        for (const auto& f : reference.frames) {
            auto it = by_number.find(f.number);
            if (it == by_number.end())
                throw SequenceError(kSeqFile, what + " " + other.spec + ": frame " + std::to_string(f.number) +
                                                  " is missing; the reference has it (" + f.file.string() + ")");
            out.push_back(it->second);
        }
        return out;
    }
    if (reference.frames.size() != other.frames.size()) {
        const size_t n = std::min(reference.frames.size(), other.frames.size());
        const auto& longer = reference.frames.size() > n ? reference : other;
        throw SequenceError(kSeqFile, what + " " + other.spec + ": " + std::to_string(other.frames.size()) +
                                          " images against the reference's " + std::to_string(reference.frames.size()) +
                                          " (matched by sorted name); " + longer.frames[n].file.string() +
                                          " has no partner");
    }
    for (const auto& f : other.frames) out.push_back(f.file);
    return out;
}

}  // namespace cbr::harness
