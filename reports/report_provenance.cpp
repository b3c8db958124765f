// Report section with provenance and settings from run.json: device, build, settings, routes, validation.
#include <cstdio>
#include <set>

#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report_sections.h"
#include "rundir/setting_columns.h"
#include "settings/table.h"

namespace cbr::reports {

namespace {

using Rows = std::vector<std::pair<std::string, std::string>>;

std::string kvTable(const std::string& title, const Rows& rows) {
    std::string out = "<div><h3>" + esc(title) + "</h3><table class=\"kv\">";
    for (const auto& [k, v] : rows) out += "<tr><th>" + esc(k) + "</th><td>" + esc(v) + "</td></tr>";
    return out + "</table></div>";
}

namespace rj = run_json;

template <typename... Keys>
std::string at(const RunData& d, const Keys&... keys) {
    return jsonText(runAt(d, keys...));
}

template <typename... Keys>
std::string hexAt(const RunData& d, const Keys&... keys) {
    const nlohmann::json* j = runAt(d, keys...);
    if (!j || !j->is_number_integer()) return jsonText(j);
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%04llx", static_cast<unsigned long long>(j->get<long long>()));
    return buf;
}

// A number at run.json's keys scaled and rounded ("12.3"), or a dash.
template <typename... Keys>
std::string numberAt(const RunData& d, double scale, int decimals, const Keys&... keys) {
    const nlohmann::json* j = runAt(d, keys...);
    return j && j->is_number() ? fmt(j->get<double>() * scale, decimals) : std::string(kDash);
}

std::string joined(const std::string& a, const std::string& b, const std::string& sep) {
    if (a == kDash) return b;
    if (b == kDash) return a;
    return a + sep + b;
}

// Every scalar under an object, as "key" or "parent.key", skipping `skip`.
void flatten(const nlohmann::json& j, const std::string& prefix, const std::set<std::string>& skip, Rows& rows) {
    for (auto it = j.begin(); it != j.end(); ++it) {
        std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
        if (skip.count(key)) continue;
        if (it->is_object()) flatten(*it, key, skip, rows);
        else rows.push_back({key, jsonText(&*it)});
    }
}

// The display model ColorVideoVDP's JODs hold for (run.json settings.display); nothing in runs
// from before it.
std::string displayTable(const RunData& d) {
    const auto* display = runAt(d, rj::kSettings, rundir::settingColumn("display"));
    if (!display || !display->is_object()) return {};
    Rows rows = {{"display", displayModelText(display)},
                 {"description", at(d, rj::kSettings, rundir::settingColumn("display"), rj::settings::display::kDescription)},
                 {"frames per second scored", at(d, rj::kSettings, rj::settings::kCvvdpFps)},
                 {"metric", at(d, rj::kMetrics, rj::metrics::kCvvdp)},
                 {"JOD", kJodMeaning}};
    return kvTable("Display model (ColorVideoVDP)", rows);
}

// Key-value tables of where and how the run ran: device, build and run, benchmark settings.
std::string runTables(const RunData& d) {
    auto dev = [&](const char* key) { return at(d, rj::kDevice, key); };
    namespace kd = rj::device;
    std::string out = kvTable("Device", {
                                 {"name", dev(kd::kName)},
                                 {"type", dev(kd::kType)},
                                 {"driver", joined(dev(kd::kDriverName), dev(kd::kDriverInfo), ", ")},
                                 {"driver id", dev(kd::kDriverId)},
                                 {"driver version", dev(kd::kDriverVersion)},
                                 {"Vulkan API version", dev(kd::kApiVersion)},
                                 {"vendor / device id",
                                  hexAt(d, rj::kDevice, kd::kVendorId) + " / " + hexAt(d, rj::kDevice, kd::kDeviceId)},
                                 {"timestamp period (ns)", dev(kd::kTimestampPeriodNs)},
                                 {"timestamp valid bits", dev(kd::kTimestampValidBits)},
                                 {"pipeline statistics", dev(kd::kPipelineStatistics)},
                                 {"target clears", joined(dev(kd::kTargetClear), dev(kd::kTargetClearRule), ": ")},
                                 {"timing note", dev(kd::kTimingNote)},
                             });
    std::string res = at(d, rj::kSettings, rj::settings::kWidth) + "\u00d7" + at(d, rj::kSettings, rj::settings::kHeight);
    std::string cmd;
    if (const auto* c = runAt(d, rj::kCommandLine); c && c->is_array())
        for (const auto& a : *c) {
            if (!cmd.empty()) cmd += ' ';
            cmd += jsonText(&a);
        }
    out += kvTable("Build and run", {
                                        {"tool", joined(at(d, rj::kTool, rj::tool::kName), at(d, rj::kTool, rj::tool::kVersion), " ")},
                                        {"build commit", at(d, rj::kTool, rj::tool::kCommit)},
                                        {"date", at(d, rj::kDate)},
                                        {"command line", cmd.empty() ? kDash : cmd},
                                        {"wall time (s)", at(d, rj::kWallSeconds)},
                                        {"wall time to the first frame (s)", numberAt(d, 1, 3, rj::kFirstFrameWallSeconds)},
                                        {"image I/O", at(d, rj::kMetrics, rj::metrics::kImageIo)},
                                    });
    out += kvTable("Benchmark", {
                                    {"pipeline", at(d, rj::kSettings, rj::settings::kPipeline)},
                                    {"resolution (px)", res},
                                    {"frames per repetition", at(d, rj::kSettings, rj::settings::kFrames)},
                                    {"repetitions", at(d, rj::kSettings, rj::settings::kRepeat)},
                                    {"warm-up frames", at(d, rj::kSettings, rj::settings::kWarmupFrames)},
                                    {"warm-up rule", at(d, rj::kSettings, rj::settings::kWarmupRule)},
                                    {"variant order", at(d, rj::kSettings, rj::settings::kVariantOrder)},
                                    {"shading cost (x)", at(d, rj::kSettings, rundir::settingColumn("shading-cost"))},
                                    {"checkerboard route (requested)", at(d, rj::kSettings, rundir::settingColumn("cbr-route"))},
                                });
    out += displayTable(d);
    Rows other;
    namespace ks = rj::settings;
    if (const auto* s = runAt(d, rj::kSettings); s && s->is_object())
        flatten(*s, "", {ks::kPipeline, ks::kWidth, ks::kHeight, ks::kFrames, ks::kRepeat, ks::kWarmupFrames,
                         ks::kWarmupRule, ks::kVariantOrder, rundir::settingColumn("shading-cost"),
                         rundir::settingColumn("cbr-route"), rundir::settingColumn("display"), ks::kCvvdpFps},
                other);
    if (!other.empty()) out += kvTable("Other settings", other);
    return out;
}

// Key-value tables of what it rendered: scene, camera path, and the validation layer's count.
std::string contentTables(const RunData& d) {
    std::string out = kvTable("Scene", {
                                {"name", at(d, rj::kScene, rj::scene::kName)},
                                {"source", at(d, rj::kScene, rj::scene::kSource)},
                                {"content hash", at(d, rj::kScene, rj::scene::kHash)},
                                {"triangles", at(d, rj::kScene, rj::scene::kTriangles)},
                                {"draws opaque / masked / blend", at(d, rj::kScene, rj::scene::kOpaqueDraws) + " / " +
                                                                       at(d, rj::kScene, rj::scene::kMaskedDraws) + " / " +
                                                                       at(d, rj::kScene, rj::scene::kBlendDraws)},
                                {"animated instances", at(d, rj::kScene, rj::scene::kAnimatedInstances)},
                                {"lights", at(d, rj::kScene, rj::scene::kLights)},
                                {"default light added", at(d, rj::kScene, rj::scene::kDefaultLight)},
                                {"meshes moved to their own origin", at(d, rj::kScene, rj::scene::kRecentredMeshes)},
                                {"draws", at(d, rj::kScene, rj::scene::kDraws)},
                                {"materials", at(d, rj::kScene, rj::scene::kMaterials)},
                                {"textures", at(d, rj::kScene, rj::scene::kTextures)},
                                {"texture MiB (RGBA8 / with mips)",
                                 numberAt(d, 1.0 / 1048576, 1, rj::kScene, rj::scene::kTextureBytes) + " / " +
                                     numberAt(d, 1.0 / 1048576, 1, rj::kScene, rj::scene::kTextureGpuBytes)},
                                {"load / upload (s)", numberAt(d, 1, 3, rj::kScene, rj::scene::kLoadS) + " / " +
                                                          numberAt(d, 1, 3, rj::kScene, rj::scene::kUploadS)},
                                {"peak RSS loaded / at end (MiB)", numberAt(d, 1, 0, rj::kScene, rj::scene::kPeakRssMibLoaded) +
                                                                       " / " +
                                                                       numberAt(d, 1, 0, rj::kScene, rj::scene::kPeakRssMibEnd)},
                                {"cost note", at(d, rj::kScene, rj::scene::kCostNote)},
                            });
    out += kvTable("Camera path", {
                                      {"name", at(d, rj::kPath, rj::path::kName)},
                                      {"source", at(d, rj::kPath, rj::path::kSource)},
                                      {"pose hash", at(d, rj::kPath, rj::path::kHash)},
                                      {"fps", at(d, rj::kPath, rj::path::kFps)},
                                      {"duration (s)", at(d, rj::kPath, rj::path::kDurationS)},
                                      {"frames", at(d, rj::kPath, rj::path::kFrames)},
                                      {"cuts", at(d, rj::kPath, rj::path::kCuts)},
                                  });
    out += kvTable("Validation layer", {
                                           {"enabled", at(d, rj::kValidation, rj::validation::kEnabled)},
                                           {"errors", at(d, rj::kValidation, rj::validation::kErrors)},
                                           {"warnings", at(d, rj::kValidation, rj::validation::kWarnings)},
                                           {"messages", at(d, rj::kValidation, rj::validation::kMessages)},
                                       });
    return out;
}

std::string validationMessages(const RunData& d) {
    std::string out;
    if (const auto* m = runAt(d, rj::kValidation, rj::validation::kFirstMessages); m && m->is_array() && !m->empty()) {
        out += "<h3>First validation messages</h3><ul class=\"messages\">";
        for (const auto& msg : *m) out += "<li><code>" + esc(jsonText(&msg)) + "</code></li>";
        out += "</ul>";
    }
    return out;
}

// A checkerboard variant's texture LOD bias, a number as the settings table has it: a sweep
// configuration's own (variants[].settings, by --param name), else the run's (settings); runs
// from before run.json held it show the renderer's description.
std::string lodBias(const RunData& d, const nlohmann::json& vj) {
    const settings::Row& row = *settings::find("cbr-lod-bias");
    const auto* value = jsonAt(vj, rundir::pointer(rj::variant::kSettings, row.name));
    if (!value) value = runAt(d, rj::kSettings, row.column);
    if (rundir::isNumber(row) && value && value->is_number()) return jsonText(value);
    return jsonText(jsonAt(vj, rundir::pointer(rj::variant::kLodBias)));
}

// Per checkerboard variant: the resolve's bandwidth and class statistics, and the route the
// device allowed, and why.
std::string checkerboardTables(const RunData& d) {
    namespace kv = rj::variant;
    std::string out;
    std::string routes;
    for (const auto& v : d.variants) {
        const auto* vj = variantJson(d, v);
        if (!isCheckerboard(d, v) || !vj) continue;
        auto f = [&](const char* key) { return esc(jsonText(jsonAt(*vj, rundir::pointer(key)))); };
        routes += "<tr><td>" + esc(v) + "</td><td><b>" + f(kv::kRoute) + "</b></td><td>" + f(kv::kRouteReason) +
                  "</td><td>" + f(kv::kQuarterResolution) + "</td><td>" + f(kv::kOcclusionRule) + "</td><td>" +
                  f(kv::kMotion) + "</td><td>" + f(kv::kLostBorder) + "</td><td class=\"num\">" +
                  esc(lodBias(d, *vj)) + "</td></tr>";
    }
    // The reconstruction's effective bandwidth against the device's measured copy (issue 14).
    std::string resolve;
    for (const auto& v : d.variants) {
        const auto* vj = variantJson(d, v);
        if (!isCheckerboard(d, v) || !vj || !jsonAt(*vj, rundir::pointer(kv::kResolveBandwidth))) continue;
        namespace rb = kv::resolve_bandwidth;
        auto f = [&](const char* key) { return esc(jsonText(jsonAt(*vj, rundir::pointer(kv::kResolveBandwidth, key)))); };
        auto g = [&](const char* key) { return esc(jsonText(jsonAt(*vj, rundir::pointer(key)))); };
        resolve += "<tr><td>" + esc(v) + "</td><td>" + f(rb::kPass) + "</td><td class=\"num\">" + f(rb::kMbPerFrame) +
                   "</td><td class=\"num\">" + f(rb::kPassMsMedian) + "</td><td class=\"num\">" + f(rb::kGbPerS) +
                   "</td><td class=\"num\">" + f(rb::kFractionOfCopy) + "</td><td>" + g(kv::kClassStats) + "</td><td>" +
                   g(kv::kClassMap) + "</td></tr>";
    }
    if (!resolve.empty())
        out += "<h3>Checkerboard resolve: bandwidth and class statistics</h3><p>Bytes the pass must move (its inputs "
               "and outputs at their formats) over its median time, against the device's copy bandwidth measured "
               "in this run (" + esc(at(d, rj::kDevice, rj::device::kCopyBandwidthGbPerS)) +
               " GB/s, read + write).</p><div class=\"scroll\"><table><tr><th>variant</th><th>pass</th>"
               "<th class=\"num\">MB / frame</th><th class=\"num\">median ms</th><th class=\"num\">GB/s</th>"
               "<th class=\"num\">of copy</th><th>class statistics</th><th>class map</th></tr>" +
               resolve + "</table></div>";
    if (!routes.empty())
        out += "<h3>Checkerboard routes</h3><div class=\"scroll\"><table><tr><th>variant</th><th>route</th>"
               "<th>reason</th><th>quarter res (px)</th><th>occlusion rule</th><th>motion</th><th>lost border</th>"
               "<th class=\"num\">LOD bias</th></tr>" +
               routes + "</table></div>";
    return out;
}

// Frame alignment (metrics.md): PSNR against the same reference frame must beat the neighbours'.
std::string alignmentTable(const RunData& d) {
    std::string out;
    std::string align;
    for (const auto& v : d.variants) {
        const auto* vj = variantJson(d, v);
        namespace ka = rj::variant::frame_alignment;
        const auto* fa = vj ? jsonAt(*vj, rundir::pointer(rj::variant::kFrameAlignment)) : nullptr;
        if (!fa || !fa->is_object()) continue;
        const auto* ok = jsonAt(*fa, rundir::pointer(ka::kOk));
        bool good = ok && ok->is_boolean() && ok->get<bool>();
        auto num = [&](const char* key) {
            const auto* j = jsonAt(*fa, rundir::pointer(key));
            return j && j->is_number() ? fmt(j->get<double>(), 2) : std::string(kDash);
        };
        align += "<tr><td>" + esc(v) + "</td><td class=\"num\">" + esc(jsonText(jsonAt(*fa, rundir::pointer(ka::kFrame)))) +
                 "</td><td class=\"num\">" + num(ka::kPsnrDbSame) + "</td><td class=\"num\">" + num(ka::kPsnrDbPrev) +
                 "</td><td class=\"num\">" + num(ka::kPsnrDbNext) + "</td><td class=\"" + (good ? "ok" : "bad") + "\">" +
                 (ok ? (good ? "ok" : "misaligned") : kDash) + "</td></tr>";
    }
    if (!align.empty())
        out += "<h3>Frame alignment check</h3><table><tr><th>variant</th><th class=\"num\">frame</th>"
               "<th class=\"num\">PSNR same (dB)</th><th class=\"num\">PSNR previous (dB)</th>"
               "<th class=\"num\">PSNR next (dB)</th><th>result</th></tr>" +
               align + "</table>";
    return out;
}

std::string metricConventions(const RunData& d) {
    std::string out;
    if (const auto* m = runAt(d, rj::kMetrics); m && m->is_object()) {
        Rows rows;
        flatten(*m, "", {rj::metrics::kImageIo}, rows);
        if (!rows.empty()) {
            out += "<h3>Metric conventions</h3><table class=\"kv\">";
            for (const auto& [k, v] : rows) out += "<tr><th>" + esc(k) + "</th><td>" + esc(v) + "</td></tr>";
            out += "</table>";
        }
    }
    return out;
}

// Where the run's wall time went (run.json wall): the main thread's parts, which add up to
// the total, then the workers' CPU time, which overlaps them. The page is written before the
// account closes, so its own part reads as not yet known.
std::string wallTable(const RunData& d) {
    namespace kw = rj::wall;
    const auto* wall = runAt(d, rj::kWall);
    if (!wall || !wall->is_object()) return {};
    Rows rows;
    // In the order a run meets them (harness/base/wall_account.h); report and other close after this page.
    for (size_t i = 0; i < kw::kPartsBeforeReport; ++i) {
        const char* key = kw::kParts[i];
        const auto* value = jsonAt(*wall, rundir::pointer(kw::kPartsS, key));
        if (value && value->is_number() && value->get<double>() >= 0.005)
            rows.push_back({key, fmt(value->get<double>(), 2)});
    }
    rows.push_back({"report, other", "written after this page (run.json has them)"});
    if (const auto* workers = jsonAt(*wall, rundir::pointer(kw::kWorkerCpuS)); workers && workers->is_object())
        for (const auto& [key, value] : workers->items())
            if (value.is_number() && value.get<double>() >= 0.005)
                rows.push_back({"worker CPU: " + key, fmt(value.get<double>(), 2)});
    rows.push_back({"scorer", joined(at(d, rj::kMetrics, rj::metrics::kScorer), at(d, rj::kMetrics, rj::metrics::kScorerNote), ": ")});
    return kvTable("Wall time (s)", rows);
}

// What the run was estimated to need before its first frame, against its limits, and what it
// used (run.json memory; the report phase's own reading is written after this page).
std::string memoryTable(const RunData& d) {
    namespace km = rj::memory;
    const auto* memory = runAt(d, rj::kMemory);
    if (!memory || !memory->is_object()) return {};
    auto mib = [&](const char* key) {
        const auto* v = jsonAt(*memory, rundir::pointer(key));
        return v && v->is_number() ? fmt(v->get<double>(), 0) : std::string("-");
    };
    auto text = [&](const char* key) {
        const auto* v = jsonAt(*memory, rundir::pointer(key));
        return v && v->is_string() ? v->get<std::string>() : std::string();
    };
    Rows rows = {{"host: estimate / limit", mib(km::kEstimateHostMib) + " / " + mib(km::kHostLimitMib) + " (" +
                                               text(km::kHostLimitFrom) + ")"},
                 {"host: peak RSS", mib(km::kPeakRssMib)},
                 {"device: estimate / limit", mib(km::kEstimateDeviceMib) + " / " + mib(km::kDeviceLimitMib) + " (" +
                                                  text(km::kDeviceLimitFrom) + ")"},
                 {"device: cbrbench's allocations at most", mib(km::kDeviceAllocatedPeakMib)},
                 {"device: the driver's usage at most", mib(km::kDeviceUsagePeakMib)},
                 {"mapped (host-visible) allocations at most", mib(km::kHostVisibleAllocatedPeakMib)}};
    return kvTable("Memory (MiB)", rows);
}

// Per variant (run.json health.variants[]): its warm-up frames, frame noise and note.
void healthVariantRows(const nlohmann::json& health, Rows& rows) {
    namespace kv = rj::health::variant;
    const auto* variants = jsonAt(health, rundir::pointer(rj::health::kVariants));
    if (!variants || !variants->is_array()) return;
    for (const auto& v : *variants) {
        const std::string name = v.value(kv::kName, std::string());
        std::string warm;
        if (const auto* frames = jsonAt(v, rundir::pointer(kv::kWarmUpFrames)); frames && frames->is_array())
            for (const auto& f : *frames) warm += (warm.empty() ? "" : ", ") + jsonText(&f);
        const auto* noise = jsonAt(v, rundir::pointer(kv::kDrift, rj::health::drift::kNoise));
        std::string text = "warm-up frames " + (warm.empty() ? std::string(kDash) : warm);
        if (noise && noise->is_number()) text += "; frame noise " + fmt(noise->get<double>() * 100, 2) + "%";
        const auto* note = jsonAt(v, rundir::pointer(kv::kNote));
        if (note && note->is_string() && !note->get<std::string>().empty()) text += "; " + note->get<std::string>();
        rows.push_back({name, text});
    }
}

// The GPU's clocks, temperature, power and throttling while frames were timed (NVML).
void gpuHealthRows(const RunData& d, Rows& rows) {
    namespace kh = rj::health;
    namespace kg = kh::machine::gpu;
    namespace clk = kg::clock;
    auto gpu = [&](double scale, int decimals, auto... keys) {
        return numberAt(d, scale, decimals, rj::kHealth, kh::kMachine, kh::machine::kGpu, keys...);
    };
    const auto* nvml = runAt(d, rj::kHealth, kh::kMachine, kh::machine::kGpu, kg::kNvml);
    if (!(nvml && nvml->is_boolean() && nvml->get<bool>())) {
        rows.push_back({"GPU (NVML)", "not available: " + at(d, rj::kHealth, kh::kMachine, kh::machine::kGpu, kg::kNote)});
        return;
    }
    rows.push_back({"GPU: SM MHz before / during / after",
                    gpu(1, 0, kg::kSmMhz, clk::kBefore) + " / " + gpu(1, 0, kg::kSmMhz, clk::kMin) + "-" +
                        gpu(1, 0, kg::kSmMhz, clk::kMax) + " (median " + gpu(1, 0, kg::kSmMhz, clk::kMedian) + ") / " +
                        gpu(1, 0, kg::kSmMhz, clk::kAfter)});
    rows.push_back({"GPU: memory MHz, temperature, power", gpu(1, 0, kg::kMemMhz, clk::kMax) + " MHz, at most " +
                                                               gpu(1, 0, kg::kTemperatureCMax) + " C, " +
                                                               gpu(1, 0, kg::kPowerWMax) + " W"});
    std::string reasons;
    if (const auto* r = runAt(d, rj::kHealth, kh::kMachine, kh::machine::kGpu, kg::kThrottleReasons); r && r->is_array())
        for (const auto& x : *r) reasons += (reasons.empty() ? "" : ", ") + jsonText(&x);
    rows.push_back({"GPU: throttle reasons while timed", reasons.empty() ? std::string("none") : reasons});
}

// Whether the machine held still while frames were timed (run.json health): warm-up frames
// per variant, drift against the same poses, other processes' load, the GPU's clocks.
std::string healthTable(const RunData& d) {
    namespace kh = rj::health;
    namespace kc = kh::machine::cpu;
    const auto* health = runAt(d, rj::kHealth);
    if (!health || !health->is_object()) return {};
    const auto* line = jsonAt(*health, rundir::pointer(kh::kLine));
    Rows rows = {{"verdict", line && line->is_string() && !line->get<std::string>().empty() ? line->get<std::string>()
                                                                                            : std::string("quiet: nothing disturbed the timed frames")}};
    healthVariantRows(*health, rows);
    auto cpu = [&](const char* key, int decimals) {
        return numberAt(d, 1, decimals, rj::kHealth, kh::kMachine, kh::machine::kCpu, key);
    };
    rows.push_back({"CPU: cores used by cbrbench / others",
                    cpu(kc::kOwnCores, 2) + " / " + cpu(kc::kOtherCores, 2) + " of " +
                        at(d, rj::kHealth, kh::kMachine, kh::machine::kCpu, kc::kCores) + " (others at most " +
                        cpu(kc::kOtherCoresMax, 2) + ")"});
    rows.push_back({"CPU: MHz before / during / after", cpu(kc::kMhzBefore, 0) + " / " + cpu(kc::kMhzMin, 0) + "-" +
                                                            cpu(kc::kMhzMax, 0) + " / " + cpu(kc::kMhzAfter, 0)});
    gpuHealthRows(d, rows);
    const auto* dev = runAt(d, rj::kHealth, kh::kMachine, kh::machine::kTimestampDeviationNs);
    rows.push_back({"calibrated timestamps: max deviation",
                    dev && dev->is_number() ? fmt(dev->get<double>(), 0) + " ns" : std::string("not available on this device")});
    return kvTable("Measurement health", rows);
}

}  // namespace

std::string provenanceSection(const RunData& d) {
    return "<section id=\"provenance\"><h2>Provenance and settings</h2><div class=\"kv-grid\">" + runTables(d) +
           contentTables(d) + healthTable(d) + wallTable(d) + memoryTable(d) + "</div>" + validationMessages(d) +
           checkerboardTables(d) + alignmentTable(d) + metricConventions(d) + "</section>";
}

}  // namespace cbr::reports
