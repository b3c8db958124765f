// Forward scene pipelines and the `opaque` and `transparent` passes (dynamic rendering).
#include "renderer/passes/scene_pass.h"

#include <algorithm>

#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"
#include "shaders/scene.frag.h"
#include "shaders/scene.vert.h"

namespace cbr::passes {
namespace {

struct DrawPush {
    glm::mat4 model;
    glm::mat4 prev_model;
};
static_assert(sizeof(DrawPush) == 128, "push constants must fit the guaranteed 128 bytes");

enum class AlphaMode : int { Opaque = 0, Mask = 1, Blend = 2 };

VkPipeline createScenePipeline(vk::Context& ctx, VkPipelineLayout layout, const ScenePipelineDesc& desc,
                               AlphaMode mode) {
    VkShaderModule vert = vk::createShaderModule(ctx, kSpirv_scene_vert, sizeof(kSpirv_scene_vert));
    VkShaderModule frag = vk::createShaderModule(ctx, kSpirv_scene_frag, sizeof(kSpirv_scene_frag));
    int32_t alpha_mode = int32_t(mode);
    VkSpecializationMapEntry entry{/* ALPHA_MODE= */ 0, 0, sizeof(int32_t)};
    VkSpecializationInfo spec{1, &entry, sizeof(int32_t), &alpha_mode};
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;
    stages[1].pName = "main";
    stages[1].pSpecializationInfo = &spec;

    VkVertexInputBindingDescription binding{0, sizeof(scene::Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    VkVertexInputAttributeDescription attributes[3] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(scene::Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(scene::Vertex, normal)},
        {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(scene::Vertex, uv)}};
    VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertex_input.vertexBindingDescriptionCount = 1;
    vertex_input.pVertexBindingDescriptions = &binding;
    vertex_input.vertexAttributeDescriptionCount = 3;
    vertex_input.pVertexAttributeDescriptions = attributes;
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewport.viewportCount = 1;
    viewport.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = desc.samples;
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depth.depthTestEnable = VK_TRUE;
    depth.depthWriteEnable = mode == AlphaMode::Blend ? VK_FALSE : VK_TRUE;
    depth.depthCompareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reversed Z: near = 1, far = 0
    VkPipelineColorBlendAttachmentState blend{};
    blend.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                           VK_COLOR_COMPONENT_A_BIT;
    if (mode == AlphaMode::Blend) {
        blend.blendEnable = VK_TRUE;
        blend.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
        blend.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend.colorBlendOp = VK_BLEND_OP_ADD;
        // Destination alpha accumulates coverage (what the CFB of the deferred path stores).
        blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
        blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        blend.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    VkPipelineColorBlendStateCreateInfo blend_state{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend_state.attachmentCount = 1;
    blend_state.pAttachments = &blend;
    VkDynamicState dynamic[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR, VK_DYNAMIC_STATE_CULL_MODE};
    VkPipelineDynamicStateCreateInfo dynamic_state{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic_state.dynamicStateCount = 3;
    dynamic_state.pDynamicStates = dynamic;
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachmentFormats = &desc.color_format;
    rendering.depthAttachmentFormat = desc.depth_format;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &assembly;
    info.pViewportState = &viewport;
    info.pRasterizationState = &raster;
    info.pMultisampleState = &ms;
    info.pDepthStencilState = &depth;
    info.pColorBlendState = &blend_state;
    info.pDynamicState = &dynamic_state;
    info.layout = layout;
    VkPipeline pipeline;
    VK_CHECK(vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    vkDestroyShaderModule(ctx.device, vert, nullptr);
    vkDestroyShaderModule(ctx.device, frag, nullptr);
    return pipeline;
}

void setViewport(VkCommandBuffer cmd, VkExtent2D extent) {
    VkViewport vp{0, 0, float(extent.width), float(extent.height), 0, 1};
    VkRect2D scissor{{0, 0}, extent};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void drawItems(VkCommandBuffer cmd, const SceneFrame& f, const std::vector<gpu::DrawItem>& items, VkPipeline pipeline) {
    const gpu::GpuScene& s = *f.scene;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    int bound_material = -1;
    for (const auto& d : items) {
        if (d.material != bound_material) {
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipelines->layout, 1, 1,
                                    &s.material_sets[size_t(d.material)], 0, nullptr);
            bool two_sided = s.cpu->materials[size_t(d.material)].double_sided;
            vkCmdSetCullMode(cmd, two_sided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT);
            bound_material = d.material;
        }
        DrawPush push{f.models[size_t(d.instance)], f.prev_models[size_t(d.instance)]};
        vkCmdPushConstants(cmd, f.pipelines->layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
        const auto& mesh = s.cpu->meshes[size_t(d.mesh)];
        vkCmdDrawIndexed(cmd, mesh.index_count, 1, mesh.first_index, mesh.vertex_offset, 0);
    }
}

void beginScene(VkCommandBuffer cmd, const SceneFrame& f, vk::Image& color, vk::Image& depth, bool clear) {
    VkRenderingAttachmentInfo color_att{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color_att.imageView = color.view;
    color_att.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color_att.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    color_att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color_att.clearValue.color = {{f.clear_color.r, f.clear_color.g, f.clear_color.b, 0.0f}};
    VkRenderingAttachmentInfo depth_att{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth_att.imageView = depth.view;
    depth_att.imageLayout = clear ? VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
    depth_att.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    depth_att.storeOp = clear ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_NONE;
    depth_att.clearValue.depthStencil = {0.0f, 0};  // reversed Z: far plane at 0
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, f.viewport};
    info.layerCount = 1;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color_att;
    info.pDepthAttachment = &depth_att;
    vkCmdBeginRendering(cmd, &info);
    setViewport(cmd, f.viewport);
    const gpu::GpuScene& s = *f.scene;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipelines->layout, 0, 1, &f.frame_set, 0,
                            nullptr);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &s.vertices.buffer, &offset);
    vkCmdBindIndexBuffer(cmd, s.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
}

}  // namespace

ScenePipelines createScenePipelines(vk::Context& ctx, const gpu::GpuScene& scene, const ScenePipelineDesc& desc) {
    ScenePipelines p;
    VkDescriptorSetLayout sets[2] = {scene.frame_layout, scene.material_layout};
    VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(DrawPush)};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = 2;
    info.pSetLayouts = sets;
    info.pushConstantRangeCount = 1;
    info.pPushConstantRanges = &push;
    VK_CHECK(vkCreatePipelineLayout(ctx.device, &info, nullptr, &p.layout));
    p.opaque = createScenePipeline(ctx, p.layout, desc, AlphaMode::Opaque);
    // A feature costs only when the scene has it: no MASK or BLEND material, no pipeline.
    if (!scene.masked.empty()) p.masked = createScenePipeline(ctx, p.layout, desc, AlphaMode::Mask);
    if (!scene.blend.empty()) p.blend = createScenePipeline(ctx, p.layout, desc, AlphaMode::Blend);
    return p;
}

void destroyScenePipelines(vk::Context& ctx, ScenePipelines& p) {
    for (VkPipeline pipeline : {p.opaque, p.masked, p.blend})
        if (pipeline) vkDestroyPipeline(ctx.device, pipeline, nullptr);
    if (p.layout) vkDestroyPipelineLayout(ctx.device, p.layout, nullptr);
    p = {};
}

void addOpaquePass(graph::Graph& graph, vk::Image& color, vk::Image& depth, std::shared_ptr<const SceneFrame> frame) {
    graph::Pass pass;
    pass.name = "opaque";
    pass.uses = {{&color, graph::Use::ColorWrite}, {&depth, graph::Use::DepthWrite}};
    pass.record = [frame, &color, &depth](VkCommandBuffer cmd) {
        beginScene(cmd, *frame, color, depth, true);
        if (!frame->scene->opaque.empty()) drawItems(cmd, *frame, frame->scene->opaque, frame->pipelines->opaque);
        if (!frame->scene->masked.empty()) drawItems(cmd, *frame, frame->scene->masked, frame->pipelines->masked);
        vkCmdEndRendering(cmd);
    };
    graph.addPass(std::move(pass));
}

void addTransparentPass(graph::Graph& graph, vk::Image& color, vk::Image& depth,
                        std::shared_ptr<const SceneFrame> frame) {
    graph::Pass pass;
    pass.name = "transparent";
    pass.uses = {{&color, graph::Use::ColorReadWrite}, {&depth, graph::Use::DepthTest}};
    pass.record = [frame, &color, &depth](VkCommandBuffer cmd) {
        // Back to front by the distance of each instance's bounds centre: correct for
        // separate panes, which is what blended scenes here contain.
        const auto& s = *frame->scene;
        std::vector<std::pair<float, gpu::DrawItem>> sorted;
        for (const auto& d : s.blend) {
            const auto& mesh = s.cpu->meshes[size_t(d.mesh)];
            glm::vec3 centre = glm::vec3(frame->models[size_t(d.instance)] *
                                         glm::vec4((mesh.bounds_min + mesh.bounds_max) * 0.5f, 1.0f));
            glm::vec3 to = centre - frame->camera_position;
            sorted.push_back({glm::dot(to, to), d});
        }
        std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        std::vector<gpu::DrawItem> items;
        for (const auto& [dist, d] : sorted) items.push_back(d);
        beginScene(cmd, *frame, color, depth, false);
        drawItems(cmd, *frame, items, frame->pipelines->blend);
        vkCmdEndRendering(cmd);
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
