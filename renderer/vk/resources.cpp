// Buffer and image creation, staging uploads, mip generation.
#include "renderer/vk/resources.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "renderer/vk/check.h"
#include "renderer/vk/context.h"

namespace cbr::vk {
namespace {

uint32_t findMemoryType(const Context& ctx, uint32_t type_bits, VkMemoryPropertyFlags want) {
    for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) && (ctx.memory.memoryTypes[i].propertyFlags & want) == want) return i;
    throw Error("no memory type with properties " + std::to_string(want));
}

VkDeviceMemory allocate(Context& ctx, const VkMemoryRequirements& req, VkMemoryPropertyFlags want) {
    VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    info.allocationSize = req.size;
    info.memoryTypeIndex = findMemoryType(ctx, req.memoryTypeBits, want);
    VkDeviceMemory memory;
    VK_CHECK(vkAllocateMemory(ctx.device, &info, nullptr, &memory));
    const VkMemoryPropertyFlags flags = ctx.memory.memoryTypes[info.memoryTypeIndex].propertyFlags;
    // lavapipe's memory is device-local and host-visible at once: counted as the device's.
    ctx.memory_use.allocated(memory, req.size, (flags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT) != 0);
    return memory;
}

void release(Context& ctx, VkDeviceMemory memory) {
    ctx.memory_use.freed(memory);
    vkFreeMemory(ctx.device, memory, nullptr);
}

}  // namespace

// Optimal-tiling storage images of this format are supported.
bool storageFormat(Context& ctx, VkFormat format) {
    VkFormatProperties props;
    vkGetPhysicalDeviceFormatProperties(ctx.physical, format, &props);
    return (props.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, uint32_t base_mip, uint32_t mips, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                  VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access, uint32_t layers) {
    VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
    b.srcStageMask = src_stage;
    b.srcAccessMask = src_access;
    b.dstStageMask = dst_stage;
    b.dstAccessMask = dst_access;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, base_mip, mips, 0, layers};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.imageMemoryBarrierCount = 1;
    dep.pImageMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
    VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, src_stage, src_access, dst_stage, dst_access};
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

void bufferBarrier(VkCommandBuffer cmd, VkBuffer buffer, VkPipelineStageFlags2 src_stage, VkAccessFlags2 src_access,
                   VkPipelineStageFlags2 dst_stage, VkAccessFlags2 dst_access) {
    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2, nullptr, src_stage, src_access, dst_stage, dst_access};
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.size = VK_WHOLE_SIZE;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.bufferMemoryBarrierCount = 1;
    dep.pBufferMemoryBarriers = &b;
    vkCmdPipelineBarrier2(cmd, &dep);
}

bool isDepthFormat(VkFormat f) {
    return f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D24_UNORM_S8_UINT ||
           f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

namespace {

Buffer createBufferIn(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, VkMemoryPropertyFlags want,
                      VkMemoryPropertyFlags fallback) {
    Buffer b;
    b.size = size;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = std::max<VkDeviceSize>(size, 4);
    info.usage = usage;
    VK_CHECK(vkCreateBuffer(ctx.device, &info, nullptr, &b.buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(ctx.device, b.buffer, &req);
    bool has_wanted = false;
    for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i)
        has_wanted |= (req.memoryTypeBits & (1u << i)) && (ctx.memory.memoryTypes[i].propertyFlags & want) == want;
    b.memory = allocate(ctx, req, has_wanted ? want : fallback);
    VK_CHECK(vkBindBufferMemory(ctx.device, b.buffer, b.memory, 0));
    if (want & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) VK_CHECK(vkMapMemory(ctx.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
    return b;
}

}  // namespace

Buffer createBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage, bool host_visible) {
    const VkMemoryPropertyFlags want = host_visible
                                           ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                           : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    return createBufferIn(ctx, size, usage, want, want);
}

// Host-cached where the device has it: the host reads it back, and reading uncached
// (write-combined) memory runs at a fraction of memcpy's speed on discrete GPUs.
Buffer createReadbackBuffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage) {
    const VkMemoryPropertyFlags coherent = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    return createBufferIn(ctx, size, usage, coherent | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, coherent);
}

void destroyBuffer(Context& ctx, Buffer& b) {
    if (b.buffer) vkDestroyBuffer(ctx.device, b.buffer, nullptr);
    if (b.memory) release(ctx, b.memory);
    b = {};
}

Buffer uploadBuffer(Context& ctx, const void* data, VkDeviceSize size, VkBufferUsageFlags usage) {
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, data, size_t(size));
    Buffer b = createBuffer(ctx, size, usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT, false);
    ctx.immediate([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, size};
        vkCmdCopyBuffer(cmd, staging.buffer, b.buffer, 1, &region);
    });
    destroyBuffer(ctx, staging);
    return b;
}

namespace {

// What a poisoned image starts as (Context::poison_images): NaN where the format holds
// floats, all bits set for integers, magenta for normalised formats (NaN has no UNORM value).
VkClearColorValue poisonValue(VkFormat format) {
    VkClearColorValue v{};
    switch (format) {
        case VK_FORMAT_R16G16B16A16_SFLOAT:
        case VK_FORMAT_R32G32B32A32_SFLOAT:
        case VK_FORMAT_R16G16_SFLOAT:
        case VK_FORMAT_R32G32_SFLOAT:
        case VK_FORMAT_R16_SFLOAT:
        case VK_FORMAT_R32_SFLOAT:
        case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
            for (float& c : v.float32) c = std::numeric_limits<float>::quiet_NaN();
            return v;
        case VK_FORMAT_R8_UINT:
        case VK_FORMAT_R32_UINT:
        case VK_FORMAT_R16_UINT:
            for (uint32_t& c : v.uint32) c = ~0u;
            return v;
        default:
            v.float32[0] = v.float32[2] = v.float32[3] = 1.0f;
            return v;
    }
}

void poison(Context& ctx, Image& img) {
    const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, img.mip_levels, 0, img.layers};
    const VkClearColorValue value = poisonValue(img.format);
    ctx.immediate([&](VkCommandBuffer cmd) {
        imageBarrier(cmd, img.image, 0, img.mip_levels, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                     VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_CLEAR_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, img.layers);
        vkCmdClearColorImage(cmd, img.image, VK_IMAGE_LAYOUT_GENERAL, &value, 1, &all);
    });
    // The graph's next barrier starts from here (a write it makes visible, in GENERAL).
    img.layout = VK_IMAGE_LAYOUT_GENERAL;
    img.stage = VK_PIPELINE_STAGE_2_CLEAR_BIT;
    img.access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
}

}  // namespace

Image createImage(Context& ctx, const ImageDesc& desc) {
    Image img;
    img.name = desc.name;
    img.format = desc.format;
    img.extent = desc.extent;
    img.mip_levels = desc.mip_levels;
    img.layers = desc.layers;
    img.samples = desc.samples;
    img.aspect = isDepthFormat(desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = desc.format;
    info.extent = {desc.extent.width, desc.extent.height, 1};
    info.mipLevels = desc.mip_levels;
    info.arrayLayers = desc.layers;
    info.samples = desc.samples;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    const bool poisoned = ctx.poison_images && !isDepthFormat(desc.format) &&
                          (desc.usage & (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT)) != 0;
    info.usage = desc.usage | (poisoned ? VK_IMAGE_USAGE_TRANSFER_DST_BIT : 0);
    if (ctx.compute_clears && (desc.usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) && storageFormat(ctx, desc.format) &&
        (ctx.properties.limits.storageImageSampleCounts & desc.samples)) {
        info.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
        img.compute_clearable = true;
    }
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkResult r = vkCreateImage(ctx.device, &info, nullptr, &img.image);
    if (r == VK_ERROR_FORMAT_NOT_SUPPORTED || r == VK_ERROR_FEATURE_NOT_PRESENT)
        throw Unsupported("image " + desc.name + ": format/usage not supported by the device");
    VK_CHECK(r);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(ctx.device, img.image, &req);
    img.memory = allocate(ctx, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    VK_CHECK(vkBindImageMemory(ctx.device, img.image, img.memory, 0));
    VkImageViewCreateInfo vinfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vinfo.image = img.image;
    vinfo.viewType = desc.layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
    vinfo.format = desc.format;
    vinfo.subresourceRange = {img.aspect, 0, desc.mip_levels, 0, desc.layers};
    VK_CHECK(vkCreateImageView(ctx.device, &vinfo, nullptr, &img.view));
    if (desc.layers > 1 && desc.mip_levels == 1) {
        vinfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
        for (uint32_t layer = 0; layer < desc.layers; ++layer) {
            vinfo.subresourceRange = {img.aspect, 0, 1, layer, 1};
            VkImageView v;
            VK_CHECK(vkCreateImageView(ctx.device, &vinfo, nullptr, &v));
            img.layer_views.push_back(v);
        }
    }
    if (poisoned) poison(ctx, img);
    return img;
}

void destroyImage(Context& ctx, Image& img) {
    if (img.view) vkDestroyImageView(ctx.device, img.view, nullptr);
    for (VkImageView v : img.layer_views) vkDestroyImageView(ctx.device, v, nullptr);
    if (img.image) vkDestroyImage(ctx.device, img.image, nullptr);
    if (img.memory) release(ctx, img.memory);
    img = {};
}

Image uploadTexture(Context& ctx, const std::string& name, const uint8_t* rgba8, uint32_t width, uint32_t height,
                    bool srgb) {
    uint32_t mips = 1 + uint32_t(std::floor(std::log2(double(std::max(width, height)))));
    ImageDesc desc;
    desc.name = name;
    desc.format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM;
    desc.extent = {width, height};
    desc.mip_levels = mips;
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    Image img = createImage(ctx, desc);
    VkDeviceSize size = VkDeviceSize(width) * height * 4;
    Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, rgba8, size_t(size));
    ctx.immediate([&](VkCommandBuffer cmd) {
        imageBarrier(cmd, img.image, 0, mips, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy copy{};
        copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.imageExtent = {width, height, 1};
        vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        // Each level is a linear blit of the one above (box-like 2:1 filter, sRGB-correct
        // because the blit filters in linear space for sRGB formats).
        int32_t w = int32_t(width), h = int32_t(height);
        for (uint32_t level = 1; level < mips; ++level) {
            imageBarrier(cmd, img.image, level - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                         VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                         VK_ACCESS_2_TRANSFER_READ_BIT);
            int32_t nw = std::max(1, w / 2), nh = std::max(1, h / 2);
            VkImageBlit blit{};
            blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, 1};
            blit.srcOffsets[1] = {w, h, 1};
            blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, 1};
            blit.dstOffsets[1] = {nw, nh, 1};
            vkCmdBlitImage(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img.image,
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
            w = nw;
            h = nh;
        }
        if (mips > 1)
            imageBarrier(cmd, img.image, 0, mips - 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                         VK_ACCESS_2_TRANSFER_READ_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                         VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
        imageBarrier(cmd, img.image, mips - 1, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    });
    destroyBuffer(ctx, staging);
    img.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    img.stage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    img.access = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    return img;
}

}  // namespace cbr::vk
