// glTF materials and textures: image checks and parallel decoding, metallic-roughness factors and maps, alpha modes, RGBA8 conversion.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "renderer/scene/gltf_internal.h"
#include "renderer/scene/png_decode.h"

namespace cbr::scene {
namespace {

// Largest image side gltfTexture accepts; checked here too, before decoding.
constexpr uint32_t kMaxImageSide = 16384;
// Deflate cannot compress better than 1032:1 (RFC 1951: a 258-byte match in ~2 bits), so
// a complete PNG holds at least its raw scanlines / 1032 bytes.
constexpr double kMaxDeflateRatio = 1032;
// Every 8x8 block of a JPEG's full-resolution component costs at least one bit (its DC
// code), so a complete JPEG holds at least width * height / 512 bytes.
constexpr double kMaxJpegPixelsPerByte = 512;

uint32_t bigEndian(const unsigned char* p, int bytes) {
    uint32_t v = 0;
    for (int i = 0; i < bytes; ++i) v = v << 8 | p[i];
    return v;
}

struct ImageHeader {
    const char* format = nullptr;  // null: neither PNG nor JPEG
    uint32_t width = 0, height = 0;
    double min_bytes = 0;          // the least a complete file of this size can take
};

ImageHeader readImageHeader(const unsigned char* bytes, size_t size) {
    ImageHeader h;
    static const unsigned char kPng[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size >= 33 && std::memcmp(bytes, kPng, 8) == 0 && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
        h.format = "PNG";
        h.width = bigEndian(bytes + 16, 4);
        h.height = bigEndian(bytes + 20, 4);
        const int depth = bytes[24], colour = bytes[25];
        const int channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;
        const double row = 1 + std::ceil(double(h.width) * channels * depth / 8);  // filter byte + samples
        h.min_bytes = row * h.height / kMaxDeflateRatio;
        return h;
    }
    if (size >= 4 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) {
        h.format = "JPEG";
        size_t i = 2;
        while (i + 4 <= size && bytes[i] == 0xff) {
            const int marker = bytes[i + 1];
            if (marker == 0xff) { ++i; continue; }  // fill byte
            if (marker == 0xd8 || marker == 0x01 || (marker >= 0xd0 && marker <= 0xd7)) { i += 2; continue; }
            if (marker == 0xd9 || marker == 0xda) break;  // end of image or start of scan: no frame seen
            const bool frame = marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
            if (frame && i + 9 <= size) {
                h.height = bigEndian(bytes + i + 5, 2);
                h.width = bigEndian(bytes + i + 7, 2);
                h.min_bytes = double(h.width) * h.height / kMaxJpegPixelsPerByte;
                return h;
            }
            i += 2 + bigEndian(bytes + i + 2, 2);
        }
        return h;  // no frame header: 0x0, refused below
    }
    return h;
}

}  // namespace

bool gltfLoadImage(tinygltf::Image*, int image_index, std::string*, std::string*, int req_width, int req_height,
                   const unsigned char* bytes, int size, void* images) {
    GltfImages& batch = *static_cast<GltfImages*>(images);
    const std::string& label = batch.file;
    const std::string where = gltfAt("images", size_t(image_index < 0 ? 0 : image_index));
    const ImageHeader h = readImageHeader(bytes, size_t(size < 0 ? 0 : size));
    if (!h.format) gltfFail(label, where, "data is neither PNG nor JPEG", "image/png or image/jpeg data (glTF 2.0 images)");
    if (h.width < 1 || h.height < 1 || h.width > kMaxImageSide || h.height > kMaxImageSide)
        gltfFail(label, where, std::string(h.format) + " header says " + std::to_string(h.width) + "x" + std::to_string(h.height),
                 "an image from 1x1 up to 16384x16384");
    if (double(size) < h.min_bytes)
        gltfFail(label, where, std::string(h.format) + " of " + std::to_string(size) + " bytes cannot hold the " + std::to_string(h.width) +
                                   "x" + std::to_string(h.height) + " pixels its header claims (truncated)",
                 "a complete image (at least " + std::to_string(uint64_t(std::ceil(h.min_bytes))) + " bytes)");
    // Kept, not decoded: tinygltf parses one image after another on one thread, and a
    // scene's PNGs take seconds to inflate. The bytes of a uri image die with the call.
    batch.encoded.push_back({image_index, req_width, req_height, std::vector<unsigned char>(bytes, bytes + size)});
    return true;
}

std::string gltfDecodeImages(GltfImages& images, tinygltf::Model& model) {
    const size_t count = images.encoded.size();
    size_t threads = std::max(1u, std::thread::hardware_concurrency());
    if (const char* env = std::getenv("CBR_DECODE_THREADS")) {
        char* end = nullptr;
        const long n = std::strtol(env, &end, 10);
        if (!*env || *end || n < 1 || n > 256)
            throw std::invalid_argument(std::string("CBR_DECODE_THREADS=") + env + ": expected 1 to 256 threads");
        threads = size_t(n);
    }
    threads = std::min(threads, count);
    bool fast_png = true;
    if (const char* env = std::getenv("CBR_PNG_DECODER")) {
        const std::string v = env;
        if (v != "fast" && v != "stb")
            throw std::invalid_argument("CBR_PNG_DECODER=" + v + ": expected fast (libdeflate, the default) or stb");
        fast_png = v == "fast";
    }
    // tinygltf's LoadImageData for what decodePngRgba8 takes: RGBA8, the size checked against
    // the one asked for (a mismatch goes to tinygltf for its own error text).
    auto decodeFast = [](const GltfImages::Encoded& e, tinygltf::Image& image) {
        int w = 0, h = 0;
        std::vector<unsigned char> pixels;
        if (!decodePngRgba8(e.bytes.data(), e.bytes.size(), w, h, pixels)) return false;
        if ((e.req_width > 0 && e.req_width != w) || (e.req_height > 0 && e.req_height != h)) return false;
        image.width = w;
        image.height = h;
        image.component = 4;
        image.bits = 8;
        image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
        image.image = std::move(pixels);
        return true;
    };
    std::vector<std::string> errors(count);
    std::atomic<size_t> next{0};
    auto work = [&] {
        for (size_t i; (i = next.fetch_add(1)) < count;) {
            GltfImages::Encoded& e = images.encoded[i];
            try {
                std::string warn;  // tinygltf's decoder never warns
                if (e.index < 0 || size_t(e.index) >= model.images.size()) {
                    errors[i] = "image[" + std::to_string(e.index) + "] is missing after the parse";
                } else if (fast_png && decodeFast(e, model.images[size_t(e.index)])) {
                    // decoded
                } else if (!tinygltf::LoadImageData(&model.images[size_t(e.index)], e.index, &errors[i], &warn, e.req_width,
                                                    e.req_height, e.bytes.data(), int(e.bytes.size()), nullptr) &&
                           errors[i].empty()) {
                    errors[i] = "image[" + std::to_string(e.index) + "] could not be decoded";
                }
            } catch (const std::exception& e) {  // std::bad_alloc, as the parse's catch reported it
                errors[i] = e.what();
            }
            e.bytes = {};
        }
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    // The lowest image index, as the serial parse (which stopped there) reported it.
    size_t first = count;
    for (size_t i = 0; i < count; ++i)
        if (!errors[i].empty() && (first == count || images.encoded[i].index < images.encoded[first].index)) first = i;
    return first == count ? std::string() : errors[first];
}

// Decoded images may have 1-4 channels of 8 or 16 bits; the renderer takes RGBA8.
int gltfTexture(GltfContext& ctx, int index, bool srgb, const std::string& used_by) {
    const auto& textures = ctx.model.textures;
    if (index < 0 || size_t(index) >= textures.size())
        gltfError(ctx, used_by + "/index", std::to_string(index) + " does not exist", gltfIndexRange("textures", textures.size()));
    const int source = textures[size_t(index)].source;
    const std::string tex_pointer = gltfAt("textures", size_t(index));
    if (source < 0)
        gltfError(ctx, tex_pointer, "has no source image", "a source (image extensions such as KHR_texture_basisu are not supported)");
    if (size_t(source) >= ctx.model.images.size())
        gltfError(ctx, tex_pointer + "/source", std::to_string(source) + " does not exist", gltfIndexRange("images", ctx.model.images.size()));
    // One image used both as colour (sRGB) and as data (linear) becomes two textures.
    if (auto it = ctx.textures.find({source, srgb}); it != ctx.textures.end()) return it->second;

    // An image whose pixels the texture of the other colour space took: a copy of that one.
    if (auto moved = ctx.moved_images.find(source); moved != ctx.moved_images.end()) {
        Texture copy = ctx.scene.textures[size_t(moved->second)];
        copy.srgb = srgb;
        ctx.scene.textures.push_back(std::move(copy));
        return ctx.textures[{source, srgb}] = int(ctx.scene.textures.size()) - 1;
    }

    tinygltf::Image& image = ctx.model.images[size_t(source)];
    const std::string pointer = gltfAt("images", size_t(source));
    const int w = image.width, h = image.height, channels = image.component, bits = image.bits;
    if (w <= 0 || h <= 0 || w > int(kMaxImageSide) || h > int(kMaxImageSide) || channels < 1 || channels > 4 || (bits != 8 && bits != 16))
        gltfError(ctx, pointer, "decoded to " + std::to_string(w) + "x" + std::to_string(h) + " with " + std::to_string(channels) +
                               " channels of " + std::to_string(bits) + " bits",
             "an image up to 16384x16384 with 1 to 4 channels of 8 or 16 bits");
    const size_t pixels = size_t(w) * size_t(h), bytes_per_channel = size_t(bits / 8);
    if (image.image.size() != pixels * size_t(channels) * bytes_per_channel)
        gltfError(ctx, pointer, "decoded pixel data has " + std::to_string(image.image.size()) + " bytes",
             std::to_string(pixels * size_t(channels) * bytes_per_channel) + " bytes for its size");
    Texture texture;
    texture.name = !image.name.empty() ? image.name : !image.uri.empty() && image.uri.rfind("data:", 0) != 0 ? image.uri
                                                                                                             : "image " + std::to_string(source);
    texture.width = w;
    texture.height = h;
    texture.srgb = srgb;
    auto channel = [&](size_t pixel, int c) -> uint8_t {
        const uint8_t* p = image.image.data() + (pixel * size_t(channels) + size_t(c)) * bytes_per_channel;
        if (bits == 8) return *p;
        uint16_t v;
        std::memcpy(&v, p, 2);
        return uint8_t((uint32_t(v) * 255u + 32767u) / 65535u);
    };
    const bool as_is = channels == 4 && bits == 8;  // what tinygltf's decoder gives for 8-bit files
    // As is: the decoded pixels move (the scene and the model held a copy each at the peak).
    if (as_is) texture.rgba8 = std::move(image.image);
    else texture.rgba8.resize(pixels * 4);
    for (size_t i = 0; i < pixels && !as_is; ++i) {
        uint8_t* out = &texture.rgba8[i * 4];
        if (channels <= 2) {  // grey (+ alpha)
            out[0] = out[1] = out[2] = channel(i, 0);
            out[3] = channels == 2 ? channel(i, 1) : 255;
        } else {
            for (int c = 0; c < 3; ++c) out[c] = channel(i, c);
            out[3] = channels == 4 ? channel(i, 3) : 255;
        }
    }
    ctx.scene.textures.push_back(std::move(texture));
    const int result = int(ctx.scene.textures.size()) - 1;
    ctx.textures[{source, srgb}] = result;
    if (as_is) ctx.moved_images[source] = result;
    return result;
}

namespace {

float finiteFactor(const GltfContext& ctx, double value, const std::string& where) {
    if (!std::isfinite(value)) gltfError(ctx, where, "is not finite", "a finite number");
    return float(value);
}

}  // namespace

int gltfMaterial(GltfContext& ctx, int index, const std::string& used_by) {
    if (index < 0) {  // glTF's default material: white, metallic 1, roughness 1
        if (ctx.default_material < 0) {
            Material m;
            m.name = "default";
            ctx.scene.materials.push_back(m);
            ctx.default_material = int(ctx.scene.materials.size()) - 1;
        }
        return ctx.default_material;
    }
    const auto& materials = ctx.model.materials;
    if (size_t(index) >= materials.size())
        gltfError(ctx, used_by + "/material", std::to_string(index) + " does not exist", gltfIndexRange("materials", materials.size()));
    if (ctx.materials[size_t(index)] >= 0) return ctx.materials[size_t(index)];

    const tinygltf::Material& src = materials[size_t(index)];
    const std::string p = gltfAt("materials", size_t(index));
    const auto& pbr = src.pbrMetallicRoughness;
    Material m;
    m.name = src.name.empty() ? "material " + std::to_string(index) : src.name;
    if (pbr.baseColorFactor.size() == 4)
        for (int c = 0; c < 4; ++c) m.base_color_factor[c] = finiteFactor(ctx, pbr.baseColorFactor[size_t(c)], p + "/pbrMetallicRoughness/baseColorFactor");
    m.metallic_factor = finiteFactor(ctx, pbr.metallicFactor, p + "/pbrMetallicRoughness/metallicFactor");
    m.roughness_factor = finiteFactor(ctx, pbr.roughnessFactor, p + "/pbrMetallicRoughness/roughnessFactor");
    if (src.emissiveFactor.size() == 3)
        for (int c = 0; c < 3; ++c) m.emissive_factor[c] = finiteFactor(ctx, src.emissiveFactor[size_t(c)], p + "/emissiveFactor");
    if (auto it = src.extensions.find("KHR_materials_emissive_strength"); it != src.extensions.end() &&
                                                                            it->second.Has("emissiveStrength"))
        m.emissive_factor *= finiteFactor(ctx, it->second.Get("emissiveStrength").GetNumberAsDouble(),
                                          p + "/extensions/KHR_materials_emissive_strength/emissiveStrength");
    m.normal_scale = finiteFactor(ctx, src.normalTexture.scale, p + "/normalTexture/scale");
    m.occlusion_strength = finiteFactor(ctx, src.occlusionTexture.strength, p + "/occlusionTexture/strength");
    m.alpha_cutoff = finiteFactor(ctx, src.alphaCutoff, p + "/alphaCutoff");
    if (src.alphaMode == "MASK") m.alpha_mode = AlphaMode::Mask;
    else if (src.alphaMode == "BLEND") m.alpha_mode = AlphaMode::Blend;
    else if (src.alphaMode.empty() || src.alphaMode == "OPAQUE") m.alpha_mode = AlphaMode::Opaque;
    else gltfError(ctx, p + "/alphaMode", "is \"" + src.alphaMode + "\"", "\"OPAQUE\", \"MASK\" or \"BLEND\"");
    m.double_sided = src.doubleSided;
    if (pbr.baseColorTexture.index >= 0)
        m.base_color_texture = gltfTexture(ctx, pbr.baseColorTexture.index, true, p + "/pbrMetallicRoughness/baseColorTexture");
    if (pbr.metallicRoughnessTexture.index >= 0)
        m.metallic_roughness_texture = gltfTexture(ctx, pbr.metallicRoughnessTexture.index, false, p + "/pbrMetallicRoughness/metallicRoughnessTexture");
    if (src.normalTexture.index >= 0) m.normal_texture = gltfTexture(ctx, src.normalTexture.index, false, p + "/normalTexture");
    if (src.occlusionTexture.index >= 0) m.occlusion_texture = gltfTexture(ctx, src.occlusionTexture.index, false, p + "/occlusionTexture");
    if (src.emissiveTexture.index >= 0) m.emissive_texture = gltfTexture(ctx, src.emissiveTexture.index, true, p + "/emissiveTexture");
    ctx.scene.materials.push_back(std::move(m));
    ctx.materials[size_t(index)] = int(ctx.scene.materials.size()) - 1;
    return ctx.materials[size_t(index)];
}

}  // namespace cbr::scene
