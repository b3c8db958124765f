// `cbrbench stress`'s child runs and generated inputs (see stress_runs.h).
#include "harness/stress/stress_runs.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "camera_paths/path.h"
#include "metrics/image_io.h"
#include "metrics/metrics.h"
#include "harness/base/process.h"
#include "rundir/files.h"
#include "rundir/run_json.h"
#include "rundir/summary_csv.h"

namespace cbr::harness::stress {
namespace {

std::string readText(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

// This very binary in a child process (runChildProcess), stdout and stderr to files beside the run's directory.
void runChild(const fs::path& self, Child& c, const std::vector<std::string>& common) {
    std::vector<std::string> argv = {self.string(), "run"};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    argv.insert(argv.end(), common.begin(), common.end());
    argv.insert(argv.end(), {"--out", c.dir.string()});
    if (c.save_frames) argv.push_back("--save-frames");
    const fs::path out_log = c.dir.string() + ".stdout.txt", err_log = c.dir.string() + ".stderr.txt";
    {
        std::ofstream cmd(c.dir.string() + ".command.txt");
        for (const auto& a : argv) cmd << a << ' ';
        cmd << '\n';
    }
    const ChildExit end = runChildProcess(argv, out_log, err_log);
    c.exit_code = end.code;
    c.signal = end.signal;
    c.err = readText(err_log);
    if (c.exit_code == 0) {
        try {
            c.frames = reports::readCsv(c.dir / rundir::kFramesCsv, reports::isReportNumericColumn,
                                        {rundir::frames::kVariant, rundir::frames::kFrame});
            c.summary = reports::readCsv(c.dir / rundir::kSummaryCsv, reports::isReportNumericColumn,
                                         {rundir::summary::kVariant});
            c.run = json::parse(readText(c.dir / rundir::kRunJson));
            c.loaded = true;
        } catch (const std::exception& e) {
            c.err += std::string("stress: reading the run's files: ") + e.what() + "\n";
        }
    }
}

std::optional<double> summaryValue(const Child& c, const std::string& variant, const std::string& col) {
    for (size_t r = 0; r < c.summary.size(); ++r)
        if (c.summary.text(r, rundir::summary::kVariant) == variant) return c.summary.num(r, col);
    return std::nullopt;
}

std::optional<double> frameValue(const Child& c, const std::string& variant, int frame, const std::string& col) {
    for (size_t r = 0; r < c.frames.size(); ++r)
        if (c.frames.text(r, rundir::frames::kVariant) == variant && c.frames.num(r, rundir::frames::kFrame) == frame &&
            c.frames.num(r, rundir::frames::kRepeat).value_or(0) == 0)
            return c.frames.num(r, col);
    return std::nullopt;
}

std::vector<double> frameSeries(const Child& c, const std::string& variant, const std::string& col) {
    std::map<int, double> by_frame;
    for (size_t r = 0; r < c.frames.size(); ++r)
        if (c.frames.text(r, rundir::frames::kVariant) == variant && c.frames.num(r, rundir::frames::kRepeat).value_or(0) == 0)
            if (auto v = c.frames.num(r, col)) by_frame[int(*c.frames.num(r, rundir::frames::kFrame))] = *v;
    std::vector<double> out;
    for (auto& [f, v] : by_frame) out.push_back(v);
    return out;
}

// Every number the run wrote is finite (PSNR's documented inf aside) and every variant ran.
bool finiteAndOk(const Child& c, std::string& why) {
    if (c.signal) return why = "crashed (signal " + std::to_string(c.signal) + ")", false;
    if (c.exit_code != 0) return why = "exit " + std::to_string(c.exit_code) + ": " + c.err.substr(0, 200), false;
    if (!c.loaded) return why = c.err, false;
    if (c.run.value(rundir::run::kNonFiniteCells, 0) != 0)
        return why = std::to_string(c.run.value(rundir::run::kNonFiniteCells, 0)) + " non-finite cells", false;
    for (const auto* t : {&c.frames, &c.summary})
        for (size_t r = 0; r < t->size(); ++r) {
            // unsteady: the machine disturbed the timing, which says nothing about soundness.
            const std::string status = t->text(r, rundir::frames::kStatus);
            if (status != "ok" && status != "unsteady") return why = t->text(r, rundir::frames::kVariant) + " " + status, false;
            for (const auto& h : t->header) {
                if (!reports::isReportNumericColumn(h)) continue;
                auto v = t->num(r, h);
                if (v && std::isinf(*v) && h.rfind(rundir::frames::kPsnrDb, 0) != 0)
                    return why = h + " is infinite in " + t->file.filename().string(), false;
            }
        }
    return true;
}

// Sequence PSNR between two runs' saved display images of one variant (mean MSE over frames).
std::optional<double> imagePsnr(const Child& a, const Child& b, const std::string& variant, int first_frame) {
    double mse_sum = 0;
    int n = 0;
    for (int f = first_frame;; ++f) {
        char name[64];
        std::snprintf(name, sizeof name, "%s_%04d.png", variant.c_str(), f);
        fs::path pa = a.dir / "frames" / name, pb = b.dir / "frames" / name;
        if (!fs::exists(pa) || !fs::exists(pb)) break;
        auto ia = metrics::readPng(pa), ib = metrics::readPng(pb);
        if (ia.width != ib.width || ia.height != ib.height) return std::nullopt;
        auto x = metrics::fromRgba8(ia.pixels.data(), ia.width, ia.height, size_t(ia.width) * 4);
        auto y = metrics::fromRgba8(ib.pixels.data(), ib.width, ib.height, size_t(ib.width) * 4);
        mse_sum += metrics::mse(x, y);
        ++n;
    }
    if (n == 0) return std::nullopt;
    return metrics::psnrFromMse(mse_sum / n);
}

std::string db(std::optional<double> v) {
    if (!v) return "n/a";
    if (std::isinf(*v)) return "inf";
    char b[32];
    std::snprintf(b, sizeof b, "%.1f", *v);
    return b;
}
std::string num(std::optional<double> v, int digits) {
    if (!v) return "n/a";
    char b[32];
    std::snprintf(b, sizeof b, "%.*f", digits, *v);
    return b;
}

// A camera path file: keyframes at frame times of a 30 fps clock.
fs::path writePath(const fs::path& dir, const std::string& name, double fov_deg,
                   const std::vector<std::tuple<int, glm::dvec3, glm::dquat, bool>>& keys) {
    paths::CameraPath p;
    p.name = name;
    p.fps = 30;
    p.interpolation = paths::Interpolation::Linear;
    for (const auto& [frame, pos, q, cut] : keys) {
        paths::Keyframe k;
        k.time = frame / 30.0;
        k.position = pos;
        k.orientation = q;
        k.fov_y_deg = fov_deg;
        k.cut = cut;
        p.keys.push_back(k);
    }
    fs::path file = dir / (name + ".json");
    std::ofstream(file) << paths::toJson(p).dump(2) << "\n";
    return file;
}

// RFC 4648 base64 with padding, for the generated glTF files' data: URIs.
std::string base64(const std::string& bin) {
    static const char* b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string enc;
    for (size_t i = 0; i < bin.size(); i += 3) {
        uint32_t v = uint32_t(uint8_t(bin[i])) << 16;
        if (i + 1 < bin.size()) v |= uint32_t(uint8_t(bin[i + 1])) << 8;
        if (i + 2 < bin.size()) v |= uint32_t(uint8_t(bin[i + 2]));
        enc += b64[(v >> 18) & 63];
        enc += b64[(v >> 12) & 63];
        enc += i + 1 < bin.size() ? b64[(v >> 6) & 63] : '=';
        enc += i + 2 < bin.size() ? b64[v & 63] : '=';
    }
    return enc;
}

// A glTF document with one mesh of one primitive (material 0) and one node, its arrays
// (positions, normals, uvs: float; indices: uint32) in an embedded base64 buffer.
json meshGltf(const std::vector<float>& pos, const std::vector<float>& nrm, const std::vector<float>& uv,
              const std::vector<uint32_t>& idx) {
    std::string bin;
    auto put = [&](const void* d, size_t n) { bin.append(static_cast<const char*>(d), n); };
    put(pos.data(), pos.size() * 4);
    put(nrm.data(), nrm.size() * 4);
    put(uv.data(), uv.size() * 4);
    put(idx.data(), idx.size() * 4);
    const size_t vn = pos.size() / 3;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (size_t i = 0; i < vn; ++i) {
        lo = glm::min(lo, glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
        hi = glm::max(hi, glm::vec3(pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
    }
    json g;
    g["asset"] = {{"version", "2.0"}};
    g["buffers"] = json::array({{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
    g["bufferViews"] = json::array({{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", vn * 12}},
                                    {{"buffer", 0}, {"byteOffset", vn * 12}, {"byteLength", vn * 12}},
                                    {{"buffer", 0}, {"byteOffset", vn * 24}, {"byteLength", vn * 8}},
                                    {{"buffer", 0}, {"byteOffset", vn * 32}, {"byteLength", idx.size() * 4}}});
    g["accessors"] = json::array({{{"bufferView", 0}, {"componentType", 5126}, {"count", vn}, {"type", "VEC3"},
                                   {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}},
                                  {{"bufferView", 1}, {"componentType", 5126}, {"count", vn}, {"type", "VEC3"}},
                                  {{"bufferView", 2}, {"componentType", 5126}, {"count", vn}, {"type", "VEC2"}},
                                  {{"bufferView", 3}, {"componentType", 5125}, {"count", idx.size()}, {"type", "SCALAR"}}});
    json prim = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}, {"material", 0}};
    g["meshes"] = json::array({{{"primitives", json::array({prim})}}});
    g["nodes"] = json::array({{{"mesh", 0}}});
    g["scenes"] = json::array({{{"nodes", {0}}}});
    g["scene"] = 0;
    return g;
}

// A quad of two triangles plus a zero-area (collinear) one; `missing_texture` adds a
// base colour texture whose image file does not exist.
fs::path writeDegenerateGltf(const fs::path& dir, const std::string& name, bool missing_texture,
                            const json& emissive) {
    // Positions (4 corners + 3 collinear points), normals (one zero-length), uvs.
    std::vector<float> pos = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 0, 0.5f, 0.5f, 0.5f, 0.5f, 1, 1, 0.5f};
    std::vector<float> nrm = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    std::vector<float> uv = {0, 0, 1, 0, 1, 1, 0, 1, 0, 0, 0, 0, 0, 0};
    json g = meshGltf(pos, nrm, uv, {0, 1, 2, 0, 2, 3, 4, 5, 6});
    json mat = {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.6, 0.4, 1}}}}};
    if (missing_texture) {
        mat["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
        g["textures"] = json::array({{{"source", 0}}});
        g["images"] = json::array({{{"uri", "no-such-texture.png"}}});
    }
    if (!emissive.is_null()) {
        // An emitter: emissiveFactor, and KHR_materials_emissive_strength beyond 1.
        mat["emissiveFactor"] = emissive.value("factor", json::array({1, 1, 1}));
        if (emissive.contains("strength")) {
            mat["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", emissive["strength"]}}}};
            g["extensionsUsed"] = json::array({"KHR_materials_emissive_strength"});
        }
    }
    g["materials"] = json::array({mat});
    fs::path file = dir / (name + ".gltf");
    std::ofstream(file) << g.dump(1) << "\n";
    return file;
}

fs::path writeBlocksGltf(const fs::path& dir, const std::string& name, glm::dvec3 bake) {
    // Boxes (min, max) on a 1/16 grid: with |bake| < 2^20 every baked coordinate is a float.
    const std::vector<std::pair<glm::dvec3, glm::dvec3>> boxes = {
        {{-8, -0.25, -12}, {8, 0, 4}},  // ground
        {{-5, 0, -4}, {-4.25, 1.5, -3.25}},     {{-3, 0, -6}, {-2.25, 2.25, -5.25}},
        {{-1, 0, -8}, {-0.25, 0.75, -7.25}},    {{1, 0, -4}, {1.75, 1.25, -3.25}},
        {{3, 0, -6}, {3.75, 2.5, -5.25}},       {{5, 0, -8}, {5.75, 1.75, -7.25}},
        {{-0.0625, 0, -2}, {0, 3, -1.9375}},    {{2, 0, -2.5}, {2.0625, 2.5, -2.4375}},  // poles, 1/16 wide
        {{-6, 2.5, -10}, {6, 2.5625, -9.9375}},  // a thin beam
    };
    std::vector<float> pos, nrm, uv;
    std::vector<uint32_t> idx;
    for (const auto& [mn, mx] : boxes)
        for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                glm::dvec3 n(0);
                n[axis] = side ? 1 : -1;
                const uint32_t first = uint32_t(pos.size() / 3);
                for (int corner = 0; corner < 4; ++corner) {
                    glm::dvec3 p;
                    p[axis] = side ? mx[axis] : mn[axis];
                    p[u] = (corner == 1 || corner == 2) ? mx[u] : mn[u];
                    p[v] = corner >= 2 ? mx[v] : mn[v];
                    const glm::vec3 f(p + bake);
                    pos.insert(pos.end(), {f.x, f.y, f.z});
                    nrm.insert(nrm.end(), {float(n.x), float(n.y), float(n.z)});
                    uv.insert(uv.end(), {float(corner == 1 || corner == 2), float(corner >= 2)});
                }
                // Counter-clockwise seen from outside: (u, v) is right-handed with the axis.
                if (side) idx.insert(idx.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
                else idx.insert(idx.end(), {first, first + 2, first + 1, first, first + 3, first + 2});
            }
    json g = meshGltf(pos, nrm, uv, idx);
    g["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {0.7, 0.7, 0.65, 1}}, {"metallicFactor", 0}}}}});
    fs::path file = dir / (name + ".gltf");
    std::ofstream(file) << g.dump(1) << "\n";
    return file;
}

}  // namespace cbr::harness::stress
