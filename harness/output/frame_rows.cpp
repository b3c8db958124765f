#include "harness/output/frame_rows.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "harness/output/output_cells.h"  // optional(): an absent score, an empty cell
#include "metrics/cvvdp.h"
#include "rundir/frames_csv.h"

namespace cbr::harness {

void VariantSamples::add(const FrameRow& row) {
    ms.push_back(row.gpu_ms);
    repeat.push_back(row.repeat);
    frame.push_back(row.frame);
    widths.push_back(row.render_width);
    heights.push_back(row.render_height);
    for (const auto& [name, value] : row.stats) {
        if (!stat_values.count(name)) stat_order.push_back(name);
        stat_values[name].push_back(value);
    }
    double frame_fs = 0;
    bool any_fs = false;
    for (const auto& pt : row.passes) {
        if (!pass_ms.count(pt.name)) pass_order.push_back(pt.name);
        pass_ms[pt.name].push_back(pt.gpu_ms);
        if (pt.fs_invocations >= 0) {
            frame_fs += double(pt.fs_invocations);
            any_fs = true;
        }
    }
    if (any_fs) fs.push_back(frame_fs);
    const Quality& q = row.quality;
    if (q.mse) mse.push_back(*q.mse);
    if (q.psnr_db) psnr.push_back(*q.psnr_db);
    if (q.ssim) ssim.push_back(*q.ssim);
    if (q.ssim_luma) ssim_luma.push_back(*q.ssim_luma);
    if (q.flip_mean) flip.push_back(*q.flip_mean);
    if (q.cvvdp_q) cvvdp_q.push_back(*q.cvvdp_q);
    if (q.eci) {
        eci.push_back(*q.eci);
        crawl_num += q.crawl_numerator;
        crawl_den += q.crawl_denominator;
    }
    if (q.flicker_ratio) flicker.push_back(*q.flicker_ratio);
}

void FrameColumns::add(const FrameRow& row) {
    for (const auto& [name, value] : row.stats)
        if (std::find(stats.begin(), stats.end(), name) == stats.end()) stats.push_back(name);
    for (const auto& p : row.passes) {
        if (std::find(passes.begin(), passes.end(), p.name) == passes.end()) passes.push_back(p.name);
        if (p.fs_invocations >= 0) fs_reported.insert(p.name);
    }
}

void FrameDigest::add(const FrameRow& row) {
    ++rows;
    columns.add(row);
    if (row.status == "ok") samples[row.variant].add(row);
}

std::map<std::string, reports::Cell> frameCells(const FrameRow& row, uint32_t width, uint32_t height) {
    using namespace rundir::frames;
    std::map<std::string, reports::Cell> m;
    m[kVariant] = row.variant;
    m[kRepeat] = row.repeat;
    m[kFrame] = row.frame;
    m[kTimeS] = row.time_s;
    m[kWidth] = unsigned(width);
    m[kHeight] = unsigned(height);
    m[kStatus] = row.status;
    std::string note = row.note;
    if (!row.quality.note.empty()) note += (note.empty() ? "" : "; ") + row.quality.note;
    m[kNote] = note;
    if (row.status != "ok") return m;
    m[kRenderWidth] = unsigned(row.render_width);
    m[kRenderHeight] = unsigned(row.render_height);
    m[kRenderScale] = row.render_scale;
    m[kGpuMs] = row.gpu_ms;
    m[kTimingOk] = row.timing_ok;
    m[kPsnrDb] = optional(row.quality.psnr_db);
    m[kSsim] = optional(row.quality.ssim);
    m[kSsimLuma] = optional(row.quality.ssim_luma);
    m[kMse] = optional(row.quality.mse);
    m[kEci] = optional(row.quality.eci);
    m[kFlickerRatio] = optional(row.quality.flicker_ratio);
    m[kCrawlValidFraction] = optional(row.quality.crawl_valid_fraction);
    m[kFlipMean] = optional(row.quality.flip_mean);
    m[kFlipQ1] = optional(row.quality.flip_q1);
    m[kFlipMedian] = optional(row.quality.flip_median);
    m[kFlipQ3] = optional(row.quality.flip_q3);
    if (row.quality.cvvdp_q) m[kCvvdpJod] = metrics::cvvdpJod(*row.quality.cvvdp_q);
    for (const auto& [name, value] : row.stats) m[name] = value;
    long long fs = 0;
    bool any = false;
    for (const auto& pt : row.passes) {
        m[passTime(pt.name)] = pt.gpu_ms;
        if (pt.fs_invocations >= 0) {
            m[passInvocations(pt.name)] = (long long)pt.fs_invocations;
            fs += pt.fs_invocations;
            any = true;
        }
    }
    if (any) m[kFsInvocations] = fs;
    return m;
}

std::vector<std::string> framesCsvColumns(const FrameColumns& c) {
    return rundir::frames::columns(c.stats, c.passes, c.fs_reported);
}

namespace {

template <typename T>
void put(std::string& out, T v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

void putText(std::string& out, const std::string& s) {
    put(out, uint32_t(s.size()));
    out += s;
}

}  // namespace

FramesSpill::FramesSpill(std::filesystem::path file, uint32_t width, uint32_t height)
    : file_(std::move(file)), width_(width), height_(height) {
    out_ = std::fopen(file_.c_str(), "wb");
    if (!out_) throw std::runtime_error("cannot write " + file_.string());
}

FramesSpill::~FramesSpill() {
    if (out_) std::fclose(out_);
}

void FramesSpill::append(const FrameRow& row) {
    if (!out_) throw std::logic_error("frame row appended to a closed spill " + file_.string());
    const auto cells = frameCells(row, width_, height_);
    buffer_.clear();
    for (const auto& [name, cell] : cells)
        if (ids_.emplace(name, uint16_t(ids_.size())).second) {
            buffer_ += 'N';
            put(buffer_, ids_[name]);
            putText(buffer_, name);
        }
    buffer_ += 'R';
    put(buffer_, uint16_t(cells.size()));
    for (const auto& [name, cell] : cells) {
        put(buffer_, ids_.at(name));
        put(buffer_, uint8_t(cell.wasNaN()));
        putText(buffer_, cell.text());
    }
    if (std::fwrite(buffer_.data(), 1, buffer_.size(), out_) != buffer_.size())
        throw std::runtime_error("cannot write " + file_.string());
}

void FramesSpill::close() {
    if (!out_) return;
    const bool ok = std::ferror(out_) == 0;
    const bool closed = std::fclose(out_) == 0;
    out_ = nullptr;
    if (!ok || !closed) throw std::runtime_error("cannot write " + file_.string());
}

namespace {

// Reads the spill's records; throws naming the file when a record is cut short.
class SpillReader {
public:
    explicit SpillReader(const std::filesystem::path& file) : file_(file), in_(std::fopen(file.c_str(), "rb")) {
        if (!in_) throw std::runtime_error("cannot read " + file.string());
    }
    ~SpillReader() { std::fclose(in_); }
    SpillReader(const SpillReader&) = delete;
    SpillReader& operator=(const SpillReader&) = delete;

    int tag() { return std::fgetc(in_); }
    template <typename T>
    T get() {
        T v{};
        need(std::fread(&v, sizeof v, 1, in_) == 1);
        return v;
    }
    std::string text() {
        std::string s(get<uint32_t>(), '\0');
        need(s.empty() || std::fread(s.data(), 1, s.size(), in_) == s.size());
        return s;
    }
    void need(bool ok) const {
        if (!ok) throw std::runtime_error(file_.string() + ": a frame row cut short; the run's spill is damaged");
    }

private:
    std::filesystem::path file_;
    std::FILE* in_;
};

}  // namespace

void readFramesSpill(const std::filesystem::path& file,
                     const std::function<void(const std::map<std::string, reports::Cell>&)>& row) {
    SpillReader in(file);
    std::vector<std::string> names;
    for (int tag = in.tag(); tag != EOF; tag = in.tag()) {
        if (tag == 'N') {
            const auto id = in.get<uint16_t>();
            in.need(id == names.size());
            names.push_back(in.text());
            continue;
        }
        in.need(tag == 'R');
        std::map<std::string, reports::Cell> cells;
        for (uint16_t n = in.get<uint16_t>(); n > 0; --n) {
            const auto id = in.get<uint16_t>();
            const bool nan = in.get<uint8_t>() != 0;
            std::string text = in.text();
            in.need(id < names.size());
            cells.emplace(names[id], nan ? reports::Cell(std::nan("")) : reports::Cell(std::move(text)));
        }
        row(cells);
    }
}

NanCells writeFramesCsv(const std::filesystem::path& csv, const std::filesystem::path& spill,
                        const FrameColumns& columns) {
    reports::CsvStream table(csv, framesCsvColumns(columns));
    readFramesSpill(spill, [&](const std::map<std::string, reports::Cell>& cells) { table.addRow(cells); });
    table.commit();
    std::filesystem::remove(spill);
    return {table.nanCells(), table.nanWhere()};
}

}  // namespace cbr::harness
