// Writes the large test scene through tinygltf: geometry in one .bin, textures as PNG files.
#include "tests/support/big_scene.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <thread>
#include <vector>

#include <tiny_gltf.h>

#include "metrics/image_io.h"

namespace cbr::testsupport {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Deterministic per-pixel noise (a 32-bit integer hash), in [0, 1).
float hashNoise(uint32_t x, uint32_t y, uint32_t seed) {
    uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    h *= 0x297a2d39u;
    h ^= h >> 15;
    return float(h >> 8) / float(1u << 24);
}

metrics::Rgba8Image texture(int index, int size) {
    metrics::Rgba8Image img{size, size, std::vector<uint8_t>(size_t(size) * size_t(size) * 4)};
    const float hue = float(index) * 0.618034f;
    const float rings = 3.0f + float(index % 7);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float u = (float(x) + 0.5f) / float(size), v = (float(y) + 0.5f) / float(size);
            const float r = std::sqrt((u - 0.5f) * (u - 0.5f) + (v - 0.5f) * (v - 0.5f));
            const float ring = 0.5f + 0.5f * std::cos(2.0f * float(kPi) * rings * r);
            const float noise = hashNoise(uint32_t(x), uint32_t(y), uint32_t(index)) - 0.5f;
            uint8_t* p = &img.pixels[(size_t(y) * size_t(size) + size_t(x)) * 4];
            for (int c = 0; c < 3; ++c) {
                const float base = 0.5f + 0.5f * std::sin(2.0f * float(kPi) * (hue + float(c) / 3.0f));
                const float value = 0.15f + 0.55f * base * (0.4f + 0.6f * ring) + 0.25f * u * v + 0.12f * noise;
                p[c] = uint8_t(std::clamp(value, 0.0f, 1.0f) * 255.0f + 0.5f);
            }
            p[3] = 255;
        }
    return img;
}

template <typename T>
size_t append(std::vector<unsigned char>& buffer, const std::vector<T>& values) {
    while (buffer.size() % 4) buffer.push_back(0);  // accessors need aligned offsets
    const size_t offset = buffer.size();
    buffer.resize(offset + values.size() * sizeof(T));
    std::memcpy(buffer.data() + offset, values.data(), values.size() * sizeof(T));
    return offset;
}

int addView(tinygltf::Model& model, size_t offset, size_t bytes, int target) {
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = offset;
    view.byteLength = bytes;
    view.target = target;
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size()) - 1;
}

int addAccessor(tinygltf::Model& model, int view, int component_type, int type, size_t count,
                std::vector<double> min = {}, std::vector<double> max = {}) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = component_type;
    a.type = type;
    a.count = count;
    a.minValues = std::move(min);
    a.maxValues = std::move(max);
    model.accessors.push_back(a);
    return int(model.accessors.size()) - 1;
}

// A tile of grid x grid quads, 1 unit wide, heights a sum of two sines (phases per mesh).
void addGridMesh(tinygltf::Model& model, std::vector<unsigned char>& buffer, int mesh_index, int grid) {
    const int n = grid + 1;
    const float a = 0.04f, k1 = 2.0f * float(kPi) * (2.0f + float(mesh_index % 3)), k2 = 2.0f * float(kPi) * 3.0f;
    const float phase = 0.7f * float(mesh_index);
    std::vector<float> positions, normals, uvs;
    positions.reserve(size_t(n) * n * 3);
    normals.reserve(size_t(n) * n * 3);
    uvs.reserve(size_t(n) * n * 2);
    float ymin = 1e30f, ymax = -1e30f;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const float x = float(i) / float(grid) - 0.5f, z = float(j) / float(grid) - 0.5f;
            const float y = a * std::sin(k1 * x + phase) + a * std::sin(k2 * z);
            const float dx = a * k1 * std::cos(k1 * x + phase), dz = a * k2 * std::cos(k2 * z);
            const float len = std::sqrt(dx * dx + 1.0f + dz * dz);
            positions.insert(positions.end(), {x, y, z});
            normals.insert(normals.end(), {-dx / len, 1.0f / len, -dz / len});
            uvs.insert(uvs.end(), {float(i) / float(grid), float(j) / float(grid)});
            ymin = std::min(ymin, y);
            ymax = std::max(ymax, y);
        }
    std::vector<uint32_t> indices;
    indices.reserve(size_t(grid) * grid * 6);
    for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) {
            const uint32_t v = uint32_t(j * n + i);
            // Counter-clockwise seen from +y (glTF front faces).
            indices.insert(indices.end(), {v, v + uint32_t(n), v + 1, v + 1, v + uint32_t(n), v + uint32_t(n) + 1});
        }
    const size_t count = size_t(n) * n;
    const int pos = addAccessor(model, addView(model, append(buffer, positions), positions.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count, {-0.5, ymin, -0.5}, {0.5, ymax, 0.5});
    const int nrm = addAccessor(model, addView(model, append(buffer, normals), normals.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count);
    const int uv = addAccessor(model, addView(model, append(buffer, uvs), uvs.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, count);
    const int idx = addAccessor(model, addView(model, append(buffer, indices), indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size());
    tinygltf::Primitive prim;
    prim.attributes = {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", uv}};
    prim.indices = idx;
    prim.material = mesh_index;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = "tile " + std::to_string(mesh_index);
    mesh.primitives.push_back(prim);
    model.meshes.push_back(mesh);
}

}  // namespace

BigSceneFiles writeBigScene(const std::filesystem::path& dir, const std::string& name, const BigSceneSpec& spec) {
    if (spec.meshes < 1 || spec.grid < 1 || spec.grid > 2000 || spec.textures < 0 || spec.textures > spec.meshes ||
        spec.texture_size < 1 || spec.texture_size > 16384)
        throw std::invalid_argument("writeBigScene: meshes >= 1, grid 1..2000, textures 0..meshes, texture_size 1..16384");
    std::filesystem::create_directories(dir);
    auto pngName = [&](int t) {
        char suffix[24];
        std::snprintf(suffix, sizeof suffix, "_%02d.png", t);
        return name + suffix;
    };

    // Textures first, in parallel: PNG encoding is most of the writing time.
    std::atomic<int> next{0};
    std::vector<std::string> errors(size_t(spec.textures));
    auto work = [&] {
        for (int t; (t = next.fetch_add(1)) < spec.textures;) try {
                metrics::writePng(dir / pngName(t), texture(t, spec.texture_size));
            } catch (const std::exception& e) {
                errors[size_t(t)] = e.what();
            }
    };
    std::vector<std::thread> pool;
    for (unsigned i = 1; i < std::max(1u, std::thread::hardware_concurrency()); ++i) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    for (const auto& e : errors)
        if (!e.empty()) throw std::runtime_error("writeBigScene: " + e);

    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "cbrbench tests/support/big_scene.cpp";
    std::vector<unsigned char> buffer;
    const int columns = int(std::ceil(std::sqrt(double(spec.meshes))));
    tinygltf::Scene scene;
    for (int m = 0; m < spec.meshes; ++m) {
        addGridMesh(model, buffer, m, spec.grid);
        tinygltf::Material material;
        material.name = "material " + std::to_string(m);
        material.pbrMetallicRoughness.metallicFactor = 0.0;
        material.pbrMetallicRoughness.roughnessFactor = 0.6;
        if (spec.textures > 0) material.pbrMetallicRoughness.baseColorTexture.index = m % spec.textures;
        model.materials.push_back(material);
        tinygltf::Node node;
        node.name = "tile " + std::to_string(m);
        node.mesh = m;
        node.translation = {double(m % columns) - 0.5 * (columns - 1), 0.0, double(m / columns) - 0.5 * (columns - 1)};
        model.nodes.push_back(node);
        scene.nodes.push_back(m);
    }
    for (int t = 0; t < spec.textures; ++t) {
        tinygltf::Image image;
        image.uri = pngName(t);
        image.mimeType = "image/png";
        model.images.push_back(image);
        tinygltf::Texture texture;
        texture.source = t;
        model.textures.push_back(texture);
    }
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    tinygltf::Buffer bin;
    bin.uri = name + ".bin";
    bin.data = std::move(buffer);
    model.buffers.push_back(std::move(bin));

    BigSceneFiles files;
    files.gltf = dir / (name + ".gltf");
    tinygltf::TinyGLTF writer;
    // The PNGs are written already: the writer keeps each image's uri.
    writer.SetImageWriter(nullptr, nullptr);
    if (!writer.WriteGltfSceneToFile(&model, files.gltf.string(), /*embedImages=*/false, /*embedBuffers=*/false,
                                     /*prettyPrint=*/false, /*writeBinary=*/false))
        throw std::runtime_error("writeBigScene: tinygltf could not write " + files.gltf.string());
    files.triangles = spec.meshes * spec.grid * spec.grid * 2;
    files.textures = spec.textures;
    files.file_bytes = std::filesystem::file_size(files.gltf) + std::filesystem::file_size(dir / (name + ".bin"));
    for (int t = 0; t < spec.textures; ++t) files.file_bytes += std::filesystem::file_size(dir / pngName(t));
    return files;
}

}  // namespace cbr::testsupport
