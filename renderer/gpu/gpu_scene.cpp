// Uploads a CPU Scene: buffers, textures (mips by blits), material descriptor sets.
#include "renderer/gpu/gpu_scene.h"

#include <algorithm>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/shaders/shared.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"

namespace cbr::gpu {
namespace {

constexpr uint32_t kMaterialTextures = 5;

vk::Image solidTexture(vk::Context& ctx, const char* name, uint8_t r, uint8_t g, uint8_t b, bool srgb) {
    uint8_t px[4] = {r, g, b, 255};
    return vk::uploadTexture(ctx, name, px, 1, 1, srgb);
}

}  // namespace

std::vector<glm::mat4> instanceMatrices(const scene::Scene& scene, double t, glm::dvec3 origin) {
    std::vector<glm::mat4> out;
    out.reserve(scene.instances.size());
    const glm::dmat4 to_origin = glm::translate(glm::dmat4(1.0), -origin);
    for (const glm::dmat4& model : scene::instanceTransforms(scene, t)) out.push_back(glm::mat4(to_origin * model));
    return out;
}

namespace {

// One MaterialUniforms per material, each at an offset the device can bind a uniform buffer at.
void uploadMaterials(vk::Context& ctx, const scene::Scene& s, GpuScene& g) {
    VkDeviceSize align = ctx.properties.limits.minUniformBufferOffsetAlignment;
    g.material_stride = (sizeof(shaders::MaterialUniforms) + align - 1) / align * align;
    std::vector<uint8_t> material_bytes(g.material_stride * s.materials.size());
    for (size_t i = 0; i < s.materials.size(); ++i) {
        const auto& m = s.materials[i];
        shaders::MaterialUniforms u{};
        u.base_color = m.base_color_factor;
        u.emissive = glm::vec4(m.emissive_factor, m.normal_scale);
        u.params = glm::vec4(m.metallic_factor, m.roughness_factor, m.alpha_cutoff, m.occlusion_strength);
        uint32_t flags = 0;
        if (m.base_color_texture >= 0) flags |= CBR_TEX_BASE_COLOR;
        if (m.metallic_roughness_texture >= 0) flags |= CBR_TEX_METALLIC_ROUGHNESS;
        if (m.normal_texture >= 0) flags |= CBR_TEX_NORMAL;
        if (m.emissive_texture >= 0) flags |= CBR_TEX_EMISSIVE;
        if (m.occlusion_texture >= 0) flags |= CBR_TEX_OCCLUSION;
        u.flags = glm::uvec4(flags, 0, 0, 0);
        std::memcpy(material_bytes.data() + i * g.material_stride, &u, sizeof(u));
    }
    g.materials = vk::uploadBuffer(ctx, material_bytes.data(), material_bytes.size(),
                                   VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
}

// The scene's set layouts (frame, material) and a material set per material: its uniforms and its
// five textures, a stand-in where it has none.
void createSceneSets(vk::Context& ctx, const scene::Scene& s, GpuScene& g) {
    constexpr auto kFrag = VK_SHADER_STAGE_FRAGMENT_BIT;
    constexpr auto kAll = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    constexpr auto kSampler = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    g.frame_layout = vk::createSetLayout(ctx, {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kAll | VK_SHADER_STAGE_COMPUTE_BIT},
                                               {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kFrag | VK_SHADER_STAGE_COMPUTE_BIT},
                                               {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                                               {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_VERTEX_BIT}});
    std::initializer_list<vk::Binding> material_bindings = {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kFrag}, {1, kSampler, kFrag}, {2, kSampler, kFrag},
        {3, kSampler, kFrag}, {4, kSampler, kFrag}, {5, kSampler, kFrag}};
    g.material_layout = vk::createSetLayout(ctx, material_bindings);
    g.pool = vk::createPool(ctx, material_bindings, uint32_t(s.materials.size()));
    for (size_t i = 0; i < s.materials.size(); ++i) {
        const auto& m = s.materials[i];
        VkDescriptorSet set = vk::allocateSet(ctx, g.pool, g.material_layout);
        vk::writeBuffer(ctx, set, 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, g.materials.buffer, i * g.material_stride,
                        sizeof(shaders::MaterialUniforms));
        int slots[kMaterialTextures] = {m.base_color_texture, m.metallic_roughness_texture, m.normal_texture,
                                        m.emissive_texture, m.occlusion_texture};
        const vk::Image* fallback[kMaterialTextures] = {&g.white_srgb, &g.white_linear, &g.flat_normal,
                                                        &g.white_srgb, &g.white_linear};
        for (uint32_t k = 0; k < kMaterialTextures; ++k) {
            const vk::Image& img = slots[k] >= 0 ? g.textures.at(size_t(slots[k])) : *fallback[k];
            vk::writeImage(ctx, set, k + 1, kSampler, img.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                           g.sampler);
        }
        g.material_sets.push_back(set);
    }
}

// Each instance into its material's alpha mode's draw list; opaque and masked sorted by material.
void sortDraws(const scene::Scene& s, GpuScene& g) {
    for (size_t i = 0; i < s.instances.size(); ++i) {
        const auto& mesh = s.meshes.at(size_t(s.instances[i].mesh));
        DrawItem d{int(i), s.instances[i].mesh, mesh.material, scene::instanceMoves(s, s.instances[i])};
        switch (s.materials.at(size_t(mesh.material)).alpha_mode) {
            case scene::AlphaMode::Opaque: g.opaque.push_back(d); break;
            case scene::AlphaMode::Mask: g.masked.push_back(d); break;
            case scene::AlphaMode::Blend: g.blend.push_back(d); break;
        }
    }
    auto by_material = [](const DrawItem& a, const DrawItem& b) {
        return a.material != b.material ? a.material < b.material : a.instance < b.instance;
    };
    std::sort(g.opaque.begin(), g.opaque.end(), by_material);
    std::sort(g.masked.begin(), g.masked.end(), by_material);
}

}  // namespace

GpuScene uploadScene(vk::Context& ctx, const scene::Scene& s) {
    GpuScene g;
    g.cpu = &s;
    if (s.vertices.empty() || s.indices.empty()) throw vk::Error("scene " + s.name + " has no geometry");
    g.vertices = vk::uploadBuffer(ctx, s.vertices.data(), s.vertices.size() * sizeof(scene::Vertex),
                                  VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    g.indices = vk::uploadBuffer(ctx, s.indices.data(), s.indices.size() * sizeof(uint32_t),
                                 VK_BUFFER_USAGE_INDEX_BUFFER_BIT);

    for (size_t i = 0; i < s.textures.size(); ++i) {
        const auto& t = s.textures[i];
        g.textures.push_back(vk::uploadTexture(ctx, t.name.empty() ? "texture" + std::to_string(i) : t.name,
                                               t.rgba8.data(), uint32_t(t.width), uint32_t(t.height), t.srgb));
    }
    g.white_srgb = solidTexture(ctx, "white_srgb", 255, 255, 255, true);
    g.white_linear = solidTexture(ctx, "white_linear", 255, 255, 255, false);
    g.flat_normal = solidTexture(ctx, "flat_normal", 128, 128, 255, false);
    g.sampler = vk::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_REPEAT, VK_LOD_CLAMP_NONE);
    uploadMaterials(ctx, s, g);
    createSceneSets(ctx, s, g);
    sortDraws(s, g);
    return g;
}

void destroyGpuScene(vk::Context& ctx, GpuScene& g) {
    vkDeviceWaitIdle(ctx.device);
    vk::destroyBuffer(ctx, g.vertices);
    vk::destroyBuffer(ctx, g.indices);
    vk::destroyBuffer(ctx, g.materials);
    for (auto& t : g.textures) vk::destroyImage(ctx, t);
    vk::destroyImage(ctx, g.white_srgb);
    vk::destroyImage(ctx, g.white_linear);
    vk::destroyImage(ctx, g.flat_normal);
    if (g.sampler) vkDestroySampler(ctx.device, g.sampler, nullptr);
    if (g.pool) vkDestroyDescriptorPool(ctx.device, g.pool, nullptr);
    if (g.frame_layout) vkDestroyDescriptorSetLayout(ctx.device, g.frame_layout, nullptr);
    if (g.material_layout) vkDestroyDescriptorSetLayout(ctx.device, g.material_layout, nullptr);
    g = {};
}

}  // namespace cbr::gpu
