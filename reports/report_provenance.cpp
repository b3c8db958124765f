// Report section with provenance and settings from run.json: device, build, settings, routes, validation.
#include <cstdio>
#include <set>

#include "reports/html.h"
#include "reports/jod.h"
#include "reports/report_sections.h"

namespace cbr::reports {

namespace {

using Rows = std::vector<std::pair<std::string, std::string>>;

std::string kvTable(const std::string& title, const Rows& rows) {
    std::string out = "<div><h3>" + esc(title) + "</h3><table class=\"kv\">";
    for (const auto& [k, v] : rows) out += "<tr><th>" + esc(k) + "</th><td>" + esc(v) + "</td></tr>";
    return out + "</table></div>";
}

std::string at(const RunData& d, const std::string& pointer) { return jsonText(jsonAt(d.run, pointer)); }

std::string hexAt(const RunData& d, const std::string& pointer) {
    const auto* j = jsonAt(d.run, pointer);
    if (!j || !j->is_number_integer()) return jsonText(j);
    char buf[32];
    std::snprintf(buf, sizeof buf, "0x%04llx", static_cast<unsigned long long>(j->get<long long>()));
    return buf;
}

// A number at `pointer` scaled and rounded ("12.3"), or a dash.
std::string numberAt(const RunData& d, const std::string& pointer, double scale, int decimals) {
    const auto* j = jsonAt(d.run, pointer);
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
    const auto* display = jsonAt(d.run, "/settings/display");
    if (!display || !display->is_object()) return {};
    Rows rows = {{"display", displayModelText(display)},
                 {"description", at(d, "/settings/display/description")},
                 {"frames per second scored", at(d, "/settings/cvvdp_fps")},
                 {"metric", at(d, "/metrics/cvvdp")},
                 {"JOD", kJodMeaning}};
    return kvTable("Display model (ColorVideoVDP)", rows);
}

// Key-value tables of where and how the run ran: device, build and run, benchmark settings.
std::string runTables(const RunData& d) {
    std::string out = kvTable("Device", {
                                 {"name", at(d, "/device/name")},
                                 {"type", at(d, "/device/type")},
                                 {"driver", joined(at(d, "/device/driver_name"), at(d, "/device/driver_info"), ", ")},
                                 {"driver id", at(d, "/device/driver_id")},
                                 {"driver version", at(d, "/device/driver_version")},
                                 {"Vulkan API version", at(d, "/device/api_version")},
                                 {"vendor / device id",
                                  hexAt(d, "/device/vendor_id") + " / " + hexAt(d, "/device/device_id")},
                                 {"timestamp period (ns)", at(d, "/device/timestamp_period_ns")},
                                 {"timestamp valid bits", at(d, "/device/timestamp_valid_bits")},
                                 {"pipeline statistics", at(d, "/device/pipeline_statistics")},
                                 {"target clears", joined(at(d, "/device/target_clear"),
                                                          at(d, "/device/target_clear_rule"), ": ")},
                                 {"timing note", at(d, "/device/timing_note")},
                             });
    std::string res = at(d, "/settings/width") + "\u00d7" + at(d, "/settings/height");
    std::string cmd;
    if (const auto* c = jsonAt(d.run, "/command_line"); c && c->is_array())
        for (const auto& a : *c) {
            if (!cmd.empty()) cmd += ' ';
            cmd += jsonText(&a);
        }
    out += kvTable("Build and run", {
                                        {"tool", joined(at(d, "/tool/name"), at(d, "/tool/version"), " ")},
                                        {"build commit", at(d, "/tool/commit")},
                                        {"date", at(d, "/date")},
                                        {"command line", cmd.empty() ? kDash : cmd},
                                        {"wall time (s)", at(d, "/wall_seconds")},
                                        {"wall time to the first frame (s)", numberAt(d, "/first_frame_wall_seconds", 1, 3)},
                                        {"image I/O", at(d, "/metrics/image_io")},
                                    });
    out += kvTable("Benchmark", {
                                    {"pipeline", at(d, "/settings/pipeline")},
                                    {"resolution (px)", res},
                                    {"frames per repetition", at(d, "/settings/frames")},
                                    {"repetitions", at(d, "/settings/repeat")},
                                    {"warm-up frames", at(d, "/settings/warmup_frames")},
                                    {"warm-up rule", at(d, "/settings/warmup_rule")},
                                    {"variant order", at(d, "/settings/variant_order")},
                                    {"shading cost (x)", at(d, "/settings/shading_cost")},
                                    {"checkerboard route (requested)", at(d, "/settings/cbr_route")},
                                });
    out += displayTable(d);
    Rows other;
    if (const auto* s = jsonAt(d.run, "/settings"); s && s->is_object())
        flatten(*s, "", {"pipeline", "width", "height", "frames", "repeat", "warmup_frames", "warmup_rule",
                         "variant_order", "shading_cost", "cbr_route", "display", "cvvdp_fps"},
                other);
    if (!other.empty()) out += kvTable("Other settings", other);
    return out;
}

// Key-value tables of what it rendered: scene, camera path, and the validation layer's count.
std::string contentTables(const RunData& d) {
    std::string out = kvTable("Scene", {
                                {"name", at(d, "/scene/name")},
                                {"source", at(d, "/scene/source")},
                                {"content hash", at(d, "/scene/hash")},
                                {"triangles", at(d, "/scene/triangles")},
                                {"draws opaque / masked / blend", at(d, "/scene/opaque_draws") + " / " +
                                                                       at(d, "/scene/masked_draws") + " / " +
                                                                       at(d, "/scene/blend_draws")},
                                {"animated instances", at(d, "/scene/animated_instances")},
                                {"lights", at(d, "/scene/lights")},
                                {"default light added", at(d, "/scene/default_light")},
                                {"meshes moved to their own origin", at(d, "/scene/recentred_meshes")},
                                {"draws", at(d, "/scene/draws")},
                                {"materials", at(d, "/scene/materials")},
                                {"textures", at(d, "/scene/textures")},
                                {"texture MiB (RGBA8 / with mips)",
                                 numberAt(d, "/scene/texture_bytes", 1.0 / 1048576, 1) + " / " +
                                     numberAt(d, "/scene/texture_gpu_bytes", 1.0 / 1048576, 1)},
                                {"load / upload (s)", numberAt(d, "/scene/load_s", 1, 3) + " / " +
                                                          numberAt(d, "/scene/upload_s", 1, 3)},
                                {"peak RSS loaded / at end (MiB)", numberAt(d, "/scene/peak_rss_mib_loaded", 1, 0) +
                                                                       " / " +
                                                                       numberAt(d, "/scene/peak_rss_mib_end", 1, 0)},
                                {"cost note", at(d, "/scene/cost_note")},
                            });
    out += kvTable("Camera path", {
                                      {"name", at(d, "/path/name")},
                                      {"source", at(d, "/path/source")},
                                      {"pose hash", at(d, "/path/hash")},
                                      {"fps", at(d, "/path/fps")},
                                      {"duration (s)", at(d, "/path/duration_s")},
                                      {"frames", at(d, "/path/frames")},
                                      {"cuts", at(d, "/path/cuts")},
                                  });
    out += kvTable("Validation layer", {
                                           {"enabled", at(d, "/validation/enabled")},
                                           {"errors", at(d, "/validation/errors")},
                                           {"warnings", at(d, "/validation/warnings")},
                                           {"messages", at(d, "/validation/messages")},
                                       });
    return out;
}

std::string validationMessages(const RunData& d) {
    std::string out;
    if (const auto* m = jsonAt(d.run, "/validation/first_messages"); m && m->is_array() && !m->empty()) {
        out += "<h3>First validation messages</h3><ul class=\"messages\">";
        for (const auto& msg : *m) out += "<li><code>" + esc(jsonText(&msg)) + "</code></li>";
        out += "</ul>";
    }
    return out;
}

// Per checkerboard variant: the resolve's bandwidth and class statistics, and the route the
// device allowed, and why.
std::string checkerboardTables(const RunData& d) {
    std::string out;
    std::string routes;
    for (const auto& v : d.variants) {
        const auto* vj = variantJson(d, v);
        if (!isCheckerboard(d, v) || !vj) continue;
        auto f = [&](const char* key) { return esc(jsonText(jsonAt(*vj, std::string("/") + key))); };
        routes += "<tr><td>" + esc(v) + "</td><td><b>" + f("route") + "</b></td><td>" + f("route_reason") + "</td><td>" +
                  f("quarter_resolution") + "</td><td>" + f("occlusion_rule") + "</td><td>" + f("motion") + "</td><td>" +
                  f("lost_border") + "</td><td class=\"num\">" + f("lod_bias") + "</td></tr>";
    }
    // The reconstruction's effective bandwidth against the device's measured copy (issue 14).
    std::string resolve;
    for (const auto& v : d.variants) {
        const auto* vj = variantJson(d, v);
        if (!isCheckerboard(d, v) || !vj || !jsonAt(*vj, "/resolve_bandwidth")) continue;
        auto f = [&](const char* key) { return esc(jsonText(jsonAt(*vj, std::string("/resolve_bandwidth/") + key))); };
        auto g = [&](const char* key) { return esc(jsonText(jsonAt(*vj, std::string("/") + key))); };
        resolve += "<tr><td>" + esc(v) + "</td><td>" + f("pass") + "</td><td class=\"num\">" + f("mb_per_frame") +
                   "</td><td class=\"num\">" + f("pass_ms_median") + "</td><td class=\"num\">" + f("gb_per_s") +
                   "</td><td class=\"num\">" + f("fraction_of_copy") + "</td><td>" + g("class_stats") + "</td><td>" +
                   g("class_map") + "</td></tr>";
    }
    if (!resolve.empty())
        out += "<h3>Checkerboard resolve: bandwidth and class statistics</h3><p>Bytes the pass must move (its inputs "
               "and outputs at their formats) over its median time, against the device's copy bandwidth measured "
               "in this run (" + esc(jsonText(jsonAt(d.run, "/device/copy_bandwidth_gb_per_s"))) +
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
        const auto* fa = vj ? jsonAt(*vj, "/frame_alignment") : nullptr;
        if (!fa || !fa->is_object()) continue;
        const auto* ok = jsonAt(*fa, "/ok");
        bool good = ok && ok->is_boolean() && ok->get<bool>();
        auto num = [&](const char* key) {
            const auto* j = jsonAt(*fa, std::string("/") + key);
            return j && j->is_number() ? fmt(j->get<double>(), 2) : std::string(kDash);
        };
        align += "<tr><td>" + esc(v) + "</td><td class=\"num\">" + esc(jsonText(jsonAt(*fa, "/frame"))) +
                 "</td><td class=\"num\">" + num("psnr_db_same") + "</td><td class=\"num\">" + num("psnr_db_prev") +
                 "</td><td class=\"num\">" + num("psnr_db_next") + "</td><td class=\"" + (good ? "ok" : "bad") + "\">" +
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
    if (const auto* m = jsonAt(d.run, "/metrics"); m && m->is_object()) {
        Rows rows;
        flatten(*m, "", {"image_io"}, rows);
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
    const auto* wall = jsonAt(d.run, "/wall");
    if (!wall || !wall->is_object()) return {};
    Rows rows;
    // In the order a run meets them (harness/base/wall_account.h); report and other close after this page.
    for (const char* key : {"scene_load", "device_open", "upload", "pipelines", "scorer_setup", "warm_up", "quality_render", "readback",
                            "scoring", "timed_frames", "worst_images", "bandwidth", "outputs"}) {
        const auto* value = jsonAt(*wall, std::string("/parts_s/") + key);
        if (value && value->is_number() && value->get<double>() >= 0.005)
            rows.push_back({key, fmt(value->get<double>(), 2)});
    }
    rows.push_back({"report, other", "written after this page (run.json has them)"});
    if (const auto* workers = jsonAt(*wall, "/worker_cpu_s"); workers && workers->is_object())
        for (const auto& [key, value] : workers->items())
            if (value.is_number() && value.get<double>() >= 0.005)
                rows.push_back({"worker CPU: " + key, fmt(value.get<double>(), 2)});
    rows.push_back({"scorer", joined(at(d, "/metrics/scorer"), at(d, "/metrics/scorer_note"), ": ")});
    return kvTable("Wall time (s)", rows);
}

// What the run was estimated to need before its first frame, against its limits, and what it
// used (run.json memory; the report phase's own reading is written after this page).
std::string memoryTable(const RunData& d) {
    const auto* memory = jsonAt(d.run, "/memory");
    if (!memory || !memory->is_object()) return {};
    auto mib = [&](const char* key) {
        const auto* v = jsonAt(*memory, key);
        return v && v->is_number() ? fmt(v->get<double>(), 0) : std::string("-");
    };
    auto text = [&](const char* key) {
        const auto* v = jsonAt(*memory, key);
        return v && v->is_string() ? v->get<std::string>() : std::string();
    };
    Rows rows = {{"host: estimate / limit", mib("/estimate_host_mib") + " / " + mib("/host_limit_mib") + " (" +
                                               text("/host_limit_from") + ")"},
                 {"host: peak RSS", mib("/peak_rss_mib")},
                 {"device: estimate / limit", mib("/estimate_device_mib") + " / " + mib("/device_limit_mib") + " (" +
                                                  text("/device_limit_from") + ")"},
                 {"device: cbrbench's allocations at most", mib("/device_allocated_peak_mib")},
                 {"device: the driver's usage at most", mib("/device_usage_peak_mib")},
                 {"mapped (host-visible) allocations at most", mib("/host_visible_allocated_peak_mib")}};
    return kvTable("Memory (MiB)", rows);
}

// Whether the machine held still while frames were timed (run.json health): warm-up frames
// per variant, drift against the same poses, other processes' load, the GPU's clocks.
std::string healthTable(const RunData& d) {
    const auto* health = jsonAt(d.run, "/health");
    if (!health || !health->is_object()) return {};
    const auto* line = jsonAt(*health, "/line");
    Rows rows = {{"verdict", line && line->is_string() && !line->get<std::string>().empty() ? line->get<std::string>()
                                                                                            : std::string("quiet: nothing disturbed the timed frames")}};
    if (const auto* variants = jsonAt(*health, "/variants"); variants && variants->is_array())
        for (const auto& v : *variants) {
            const std::string name = v.value("name", std::string());
            std::string warm;
            if (const auto* frames = jsonAt(v, "/warm_up_frames"); frames && frames->is_array())
                for (const auto& f : *frames) warm += (warm.empty() ? "" : ", ") + jsonText(&f);
            const auto* noise = jsonAt(v, "/drift/noise");
            std::string text = "warm-up frames " + (warm.empty() ? std::string(kDash) : warm);
            if (noise && noise->is_number()) text += "; frame noise " + fmt(noise->get<double>() * 100, 2) + "%";
            const auto* note = jsonAt(v, "/note");
            if (note && note->is_string() && !note->get<std::string>().empty()) text += "; " + note->get<std::string>();
            rows.push_back({name, text});
        }
    const std::string cpu = "/machine/cpu/";
    rows.push_back({"CPU: cores used by cbrbench / others",
                    numberAt(d, "/health" + cpu + "own_cores", 1, 2) + " / " + numberAt(d, "/health" + cpu + "other_cores", 1, 2) +
                        " of " + at(d, "/health" + cpu + "cores") + " (others at most " +
                        numberAt(d, "/health" + cpu + "other_cores_max", 1, 2) + ")"});
    rows.push_back({"CPU: MHz before / during / after", numberAt(d, "/health" + cpu + "mhz_before", 1, 0) + " / " +
                                                            numberAt(d, "/health" + cpu + "mhz_min", 1, 0) + "-" +
                                                            numberAt(d, "/health" + cpu + "mhz_max", 1, 0) + " / " +
                                                            numberAt(d, "/health" + cpu + "mhz_after", 1, 0)});
    const std::string gpu = "/health/machine/gpu/";
    const auto* nvml = jsonAt(d.run, gpu + "nvml");
    if (nvml && nvml->is_boolean() && nvml->get<bool>()) {
        rows.push_back({"GPU: SM MHz before / during / after",
                        numberAt(d, gpu + "sm_mhz/before", 1, 0) + " / " + numberAt(d, gpu + "sm_mhz/min", 1, 0) + "-" +
                            numberAt(d, gpu + "sm_mhz/max", 1, 0) + " (median " + numberAt(d, gpu + "sm_mhz/median", 1, 0) +
                            ") / " + numberAt(d, gpu + "sm_mhz/after", 1, 0)});
        rows.push_back({"GPU: memory MHz, temperature, power", numberAt(d, gpu + "mem_mhz/max", 1, 0) + " MHz, at most " +
                                                                   numberAt(d, gpu + "temperature_c_max", 1, 0) + " C, " +
                                                                   numberAt(d, gpu + "power_w_max", 1, 0) + " W"});
        std::string reasons;
        if (const auto* r = jsonAt(d.run, gpu + "throttle_reasons"); r && r->is_array())
            for (const auto& x : *r) reasons += (reasons.empty() ? "" : ", ") + jsonText(&x);
        rows.push_back({"GPU: throttle reasons while timed", reasons.empty() ? std::string("none") : reasons});
    } else {
        rows.push_back({"GPU (NVML)", "not available: " + at(d, gpu + "note")});
    }
    const auto* dev = jsonAt(d.run, "/health/machine/timestamp_deviation_ns");
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
