// glTF animations (node translation, rotation, scale channels) and cameras, checked and
// converted into Scene::animations and Scene::cameras.
#include <algorithm>
#include <cmath>
#include <limits>

#include "renderer/scene/gltf_internal.h"

namespace cbr::scene {
namespace {

bool nodePath(const std::string& path) { return path == "translation" || path == "rotation" || path == "scale"; }

AnimationChannel::Interpolation interpolation(const GltfContext& ctx, const std::string& text, const std::string& where) {
    if (text.empty() || text == "LINEAR") return AnimationChannel::Interpolation::Linear;
    if (text == "STEP") return AnimationChannel::Interpolation::Step;
    if (text == "CUBICSPLINE") return AnimationChannel::Interpolation::CubicSpline;
    gltfError(ctx, where, "is \"" + text + "\"", "LINEAR, STEP or CUBICSPLINE");
}

// Key times: scalar floats, finite (readFloats), strictly increasing.
std::vector<double> keyTimes(const GltfContext& ctx, int accessor, const std::string& used_by) {
    const View view = viewAccessor(ctx, accessor, used_by, TINYGLTF_TYPE_SCALAR, {TINYGLTF_COMPONENT_TYPE_FLOAT});
    const std::vector<float> raw = readFloats(ctx, view);
    std::vector<double> times(raw.begin(), raw.end());
    for (size_t k = 1; k < times.size(); ++k)
        if (!(times[k] > times[k - 1]))
            gltfError(ctx, view.pointer, "key time " + std::to_string(times[k]) + " at element " + std::to_string(k) +
                                             " is not after " + std::to_string(times[k - 1]) + " (used by " + used_by + ")",
                      "strictly increasing key times");
    if (times.front() < 0)
        gltfError(ctx, view.pointer, "key time " + std::to_string(times.front()) + " is negative (used by " + used_by + ")",
                  "key times >= 0");
    return times;
}

AnimationChannel channel(const GltfContext& ctx, const tinygltf::Animation& animation, size_t a, size_t c, int node) {
    const tinygltf::AnimationChannel& src = animation.channels[c];
    const std::string cp = gltfAt("animations", a) + "/channels/" + std::to_string(c);
    const auto& samplers = animation.samplers;
    if (src.sampler < 0 || size_t(src.sampler) >= samplers.size())
        gltfError(ctx, cp + "/sampler", std::to_string(src.sampler) + " does not exist",
                  samplers.empty() ? "a sampler in /animations/" + std::to_string(a) + "/samplers"
                                   : "an index into /animations/" + std::to_string(a) + "/samplers (0.." +
                                         std::to_string(samplers.size() - 1) + ")");
    const tinygltf::AnimationSampler& sampler = samplers[size_t(src.sampler)];
    const std::string sp = gltfAt("animations", a) + "/samplers/" + std::to_string(src.sampler);
    AnimationChannel out;
    out.node = node;
    out.path = src.target_path == "translation" ? AnimationChannel::Path::Translation
               : src.target_path == "rotation"  ? AnimationChannel::Path::Rotation
                                                : AnimationChannel::Path::Scale;
    out.interpolation = interpolation(ctx, sampler.interpolation, sp + "/interpolation");
    out.times = keyTimes(ctx, sampler.input, sp + "/input");
    const bool rotation = out.path == AnimationChannel::Path::Rotation;
    const View values = rotation ? viewAccessor(ctx, sampler.output, sp + "/output", TINYGLTF_TYPE_VEC4,
                                                {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT})
                                 : viewAccessor(ctx, sampler.output, sp + "/output", TINYGLTF_TYPE_VEC3,
                                                {TINYGLTF_COMPONENT_TYPE_FLOAT});
    if (values.component_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !values.normalized)
        gltfError(ctx, values.pointer + "/normalized", "is false for integer rotations (used by " + sp + "/output)",
                  "normalized: true");
    const bool cubic = out.interpolation == AnimationChannel::Interpolation::CubicSpline;
    const size_t expected = out.times.size() * (cubic ? 3 : 1);
    if (values.count != expected)
        gltfError(ctx, sp + "/output", std::to_string(values.count) + " values for " + std::to_string(out.times.size()) +
                                           " key times (" + values.pointer + ")",
                  cubic ? "3 per key time for CUBICSPLINE (in-tangent, value, out-tangent)" : "one per key time");
    const std::vector<float> raw = readFloats(ctx, values);
    out.values.assign(raw.begin(), raw.end());
    if (rotation)  // the key values (not tangents) must be rotations
        for (size_t k = 0; k < out.times.size(); ++k) {
            const size_t at = (cubic ? 3 * k + 1 : k) * 4;
            const double len2 = out.values[at] * out.values[at] + out.values[at + 1] * out.values[at + 1] +
                                out.values[at + 2] * out.values[at + 2] + out.values[at + 3] * out.values[at + 3];
            if (!(len2 > 1e-12))
                gltfError(ctx, values.pointer, "key " + std::to_string(k) + " is a zero quaternion (used by " + sp + "/output)",
                          "unit quaternions (x, y, z, w)");
        }
    return out;
}

// Animated world transforms must fit a float as the flattened ones do (flattenNodes): checked
// at every key time and half way between keys (a cubic overshoots between them), at most
// kMaxChecks times per animation, with every animation playing.
void checkAnimatedTransforms(const GltfContext& ctx) {
    constexpr size_t kMaxChecks = 4096;
    const Scene& scene = ctx.scene;
    for (size_t a = 0; a < scene.animations.size(); ++a) {
        std::vector<double> times;
        for (const AnimationChannel& c : scene.animations[a].channels)
            for (size_t k = 0; k < c.times.size(); ++k) {
                times.push_back(c.times[k]);
                if (k) times.push_back(0.5 * (c.times[k - 1] + c.times[k]));
            }
        std::sort(times.begin(), times.end());
        times.erase(std::unique(times.begin(), times.end()), times.end());
        const size_t step = std::max<size_t>(1, times.size() / kMaxChecks);
        for (size_t i = 0; i < times.size(); i += step) {
            const std::vector<glm::dmat4> world = nodeTransforms(scene, times[i]);
            for (size_t n = 0; n < world.size(); ++n) {
                bool ok = true;
                for (int col = 0; col < 4; ++col)
                    for (int row = 0; row < 3; ++row)
                        ok = ok && std::abs(world[n][col][row]) <= double(std::numeric_limits<float>::max());
                if (!ok)
                    gltfError(ctx, gltfAt("nodes", size_t(scene.nodes[n].gltf_index)),
                              "its animated world transform overflows a float at t = " + std::to_string(times[i]) +
                                  " s (" + gltfAt("animations", size_t(scene.animations[a].gltf_index)) + ")",
                              "translations and scales whose products along the node path stay below 3.4e38");
            }
        }
    }
}

}  // namespace

std::vector<bool> gltfAnimatedNodes(const GltfContext& ctx) {
    std::vector<bool> animated(ctx.model.nodes.size(), false);
    for (const tinygltf::Animation& a : ctx.model.animations)
        for (const tinygltf::AnimationChannel& c : a.channels)
            if (nodePath(c.target_path) && c.target_node >= 0 && size_t(c.target_node) < animated.size())
                animated[size_t(c.target_node)] = true;
    return animated;
}

void gltfAnimations(GltfContext& ctx, const std::vector<int>& scene_node) {
    Scene& scene = ctx.scene;
    int weight_channels = 0;
    for (size_t a = 0; a < ctx.model.animations.size(); ++a) {
        const tinygltf::Animation& src = ctx.model.animations[a];
        NodeAnimation out;
        out.name = src.name.empty() ? "animation " + std::to_string(a) : src.name;
        out.gltf_index = int(a);
        for (size_t c = 0; c < src.channels.size(); ++c) {
            const tinygltf::AnimationChannel& ch = src.channels[c];
            const std::string cp = gltfAt("animations", a) + "/channels/" + std::to_string(c) + "/target";
            if (ch.target_path == "weights") {
                ++weight_channels;
                continue;
            }
            if (!nodePath(ch.target_path))
                gltfError(ctx, cp + "/path", "is \"" + ch.target_path + "\"", "translation, rotation, scale or weights");
            if (ch.target_node < 0) continue;  // no node: an extension's target
            if (size_t(ch.target_node) >= ctx.model.nodes.size())
                gltfError(ctx, cp + "/node", std::to_string(ch.target_node) + " does not exist",
                          gltfIndexRange("nodes", ctx.model.nodes.size()));
            const int node = scene_node[size_t(ch.target_node)];
            AnimationChannel channel_out = channel(ctx, src, a, c, node);  // checked even when unused
            if (node < 0) continue;  // a node outside the scene
            out.length = std::max(out.length, channel_out.times.back());
            out.channels.push_back(std::move(channel_out));
        }
        if (!out.channels.empty()) scene.animations.push_back(std::move(out));
    }
    scene.info.animations = int(scene.animations.size());
    checkAnimatedTransforms(ctx);
    if (weight_channels)
        scene.warnings.push_back("/animations: " + std::to_string(weight_channels) +
                                 " morph-weight channel(s) ignored (morph targets are not animated)");
}

void gltfCamera(GltfContext& ctx, const tinygltf::Node& node, size_t node_index, int scene_node) {
    const auto& cameras = ctx.model.cameras;
    const std::string where = gltfAt("nodes", node_index) + "/camera";
    if (size_t(node.camera) >= cameras.size())
        gltfError(ctx, where, std::to_string(node.camera) + " does not exist", gltfIndexRange("cameras", cameras.size()));
    const tinygltf::Camera& src = cameras[size_t(node.camera)];
    SceneCamera cam;
    cam.name = !src.name.empty() ? src.name : !node.name.empty() ? node.name : "camera " + std::to_string(node.camera);
    cam.node = scene_node;
    cam.perspective = src.type == "perspective";
    if (cam.perspective) {
        cam.yfov_rad = src.perspective.yfov;
        cam.znear = src.perspective.znear;
        cam.zfar = src.perspective.zfar;
    } else {
        cam.znear = src.orthographic.znear;
        cam.zfar = src.orthographic.zfar;
    }
    ctx.scene.cameras.push_back(std::move(cam));
}

}  // namespace cbr::scene
