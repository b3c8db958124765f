// glTF node animation: sampling channels (LINEAR, STEP, CUBICSPLINE), node world transforms
// per frame, and which animations play.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "renderer/scene/scene.h"

namespace cbr::scene {
namespace {

using Path = AnimationChannel::Path;
using Interp = AnimationChannel::Interpolation;

int components(const AnimationChannel& c) { return c.path == Path::Rotation ? 4 : 3; }

// Value v of key k; CUBICSPLINE keys hold (in-tangent, value, out-tangent), so part 0, 1, 2.
glm::dvec4 keyPart(const AnimationChannel& c, size_t k, int part) {
    const int n = components(c);
    const size_t stride = c.interpolation == Interp::CubicSpline ? 3 : 1;
    const size_t base = (k * stride + size_t(c.interpolation == Interp::CubicSpline ? part : 0)) * size_t(n);
    glm::dvec4 v(0.0);
    for (int i = 0; i < n; ++i) v[i] = c.values[base + size_t(i)];
    return v;
}

glm::dquat asQuat(const glm::dvec4& v) { return glm::dquat(v.w, v.x, v.y, v.z); }

// A channel's value at local time t: clamped to its first and last keys.
glm::dvec4 sample(const AnimationChannel& c, double t) {
    const std::vector<double>& times = c.times;
    if (t <= times.front()) return keyPart(c, 0, 1);
    if (t >= times.back()) return keyPart(c, times.size() - 1, 1);
    const size_t k1 = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin());
    const size_t k0 = k1 - 1;
    const double dt = times[k1] - times[k0];
    const double s = (t - times[k0]) / dt;
    if (c.interpolation == Interp::Step) return keyPart(c, k0, 1);
    if (c.interpolation == Interp::Linear) {
        const glm::dvec4 a = keyPart(c, k0, 1), b = keyPart(c, k1, 1);
        if (c.path != Path::Rotation) return glm::mix(a, b, s);
        // Shortest-arc slerp (glTF 2.0 appendix: the quaternions are not re-signed in the
        // file, so the player takes the short way).
        const glm::dquat q = glm::slerp(glm::normalize(asQuat(a)), glm::normalize(asQuat(b)), s);
        return {q.x, q.y, q.z, q.w};
    }
    // Cubic Hermite with tangents scaled by the key interval (glTF 2.0 appendix C).
    const double s2 = s * s, s3 = s2 * s;
    const glm::dvec4 p0 = keyPart(c, k0, 1), m0 = dt * keyPart(c, k0, 2);
    const glm::dvec4 p1 = keyPart(c, k1, 1), m1 = dt * keyPart(c, k1, 0);
    return (2 * s3 - 3 * s2 + 1) * p0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * p1 + (s3 - s2) * m1;
}

// Time inside an animation of this length: looped, with whole lengths past zero on the end.
double localTime(double t, double length) {
    if (!(length > 0)) return 0.0;
    if (t <= length) return t;  // before zero: the first value holds (sample clamps)
    const double r = std::fmod(t, length);
    return r == 0.0 ? length : r;
}

glm::dmat4 compose(const Node& n) {
    if (n.has_matrix) return n.matrix;
    glm::dquat r = n.rotation;
    const double len = glm::length(r);
    r = len > 1e-12 ? r / len : glm::dquat(1, 0, 0, 0);
    return glm::translate(glm::dmat4(1.0), n.translation) * glm::mat4_cast(r) * glm::scale(glm::dmat4(1.0), n.scale);
}

}  // namespace

std::vector<glm::dmat4> nodeTransforms(const Scene& scene, double t) {
    std::vector<Node> nodes = scene.nodes;  // local TRS at time t
    for (const NodeAnimation& a : scene.animations) {
        if (!a.played) continue;
        const double local = localTime(t, a.length);
        for (const AnimationChannel& c : a.channels) {
            const glm::dvec4 v = sample(c, local);
            Node& n = nodes[size_t(c.node)];
            switch (c.path) {
                case Path::Translation: n.translation = glm::dvec3(v); break;
                case Path::Scale: n.scale = glm::dvec3(v); break;
                case Path::Rotation: n.rotation = asQuat(v); break;
            }
        }
    }
    std::vector<glm::dmat4> world(nodes.size());
    for (size_t i = 0; i < nodes.size(); ++i) {
        const glm::dmat4 local = compose(nodes[i]);
        world[i] = nodes[i].parent >= 0 ? world[size_t(nodes[i].parent)] * local : scene.placement * local;
    }
    return world;
}

std::vector<glm::dmat4> instanceTransforms(const Scene& scene, double t) {
    std::vector<glm::dmat4> out;
    out.reserve(scene.instances.size());
    const bool any_node = std::any_of(scene.instances.begin(), scene.instances.end(), [](const Instance& i) { return i.node >= 0; });
    const std::vector<glm::dmat4> world = any_node ? nodeTransforms(scene, t) : std::vector<glm::dmat4>();
    for (const Instance& inst : scene.instances)
        out.push_back(inst.node >= 0 ? world[size_t(inst.node)] * inst.model : instanceTransform(inst, t));
    return out;
}

bool instanceMoves(const Scene& scene, const Instance& instance) {
    if (instance.animation.kind != Animation::Kind::None) return true;
    return instance.node >= 0 && scene.nodes[size_t(instance.node)].animated;
}

void selectAnimations(Scene& scene, const std::string& spec) {
    std::string names;
    for (size_t i = 0; i < scene.animations.size(); ++i)
        names += (i ? ", " : "") + std::to_string(scene.animations[i].gltf_index) + " (" + scene.animations[i].name + ")";
    const std::string accepted = "all, none, or a comma list of animation names or indices" +
                                 (scene.animations.empty() ? std::string(" (this scene has none)") : " among " + names);
    if (spec.empty()) throw std::invalid_argument("--animation: empty; expected " + accepted);
    if (spec == "all" || spec == "none") {
        for (NodeAnimation& a : scene.animations) a.played = spec == "all";
    } else {
        for (NodeAnimation& a : scene.animations) a.played = false;
        size_t start = 0;
        while (start <= spec.size()) {
            const size_t comma = std::min(spec.find(',', start), spec.size());
            const std::string item = spec.substr(start, comma - start);
            bool found = false;
            for (NodeAnimation& a : scene.animations)
                if (item == a.name || item == std::to_string(a.gltf_index)) found = a.played = true;
            if (!found) throw std::invalid_argument("--animation " + spec + ": \"" + item + "\" is not an animation of " +
                                                    scene.source + "; expected " + accepted);
            start = comma + 1;
        }
    }
    for (Node& n : scene.nodes) n.animated = false;
    for (const NodeAnimation& a : scene.animations)
        if (a.played)
            for (const AnimationChannel& c : a.channels) scene.nodes[size_t(c.node)].animated = true;
    for (Node& n : scene.nodes)  // parents first: one pass carries the flag down
        if (n.parent >= 0 && scene.nodes[size_t(n.parent)].animated) n.animated = true;
    int moving = 0;
    for (const Instance& inst : scene.instances) moving += instanceMoves(scene, inst);
    scene.info.animated_instances = moving;
}

double animationLength(const Scene& scene, int node) {
    double length = 0;
    for (const NodeAnimation& a : scene.animations) {
        if (!a.played) continue;
        bool moves = false;
        for (const AnimationChannel& c : a.channels)
            for (int n = node; n >= 0 && !moves; n = scene.nodes[size_t(n)].parent) moves = c.node == n;
        if (moves) length = std::max(length, a.length);
    }
    return length;
}

}  // namespace cbr::scene
