// Forward scene pipelines and the `opaque` and `transparent` passes (dynamic rendering).
#include "renderer/passes/scene_pass.h"

#include <algorithm>

#include "renderer/passes/target_clear.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipelines.h"
#include "shaders/analysis.frag.h"
#include "shaders/gbuffer.frag.h"
#include "shaders/gbuffer_motion.frag.h"
#include "shaders/gbuffer_sample.frag.h"
#include "shaders/gbuffer_sample_motion.frag.h"
#include "shaders/scene.frag.h"
#include "shaders/scene_motion.frag.h"
#include "shaders/scene_sample.frag.h"
#include "shaders/scene_sample_motion.frag.h"
#include "shaders/scene.vert.h"

namespace cbr::passes {
namespace {

enum class AlphaMode : int { Opaque = 0, Mask = 1, Blend = 2 };

// The fragment shader of desc's pass: analysis, G-buffer or forward; per-sample interpolation
// (MSAA checkerboard) x motion output: four SPIR-V modules each, because an output with no
// attachment and a `sample` input are not specialisable.
VkShaderModule sceneFragmentModule(vk::Context& ctx, const ScenePipelineDesc& desc, bool writes_motion) {
    auto module = [&](const uint32_t* code, size_t size) { return vk::createShaderModule(ctx, code, size); };
    return desc.analysis ? module(kSpirv_analysis_frag, sizeof(kSpirv_analysis_frag))
           : desc.gbuffer
               ? (desc.sample_shading
                      ? (writes_motion ? module(kSpirv_gbuffer_sample_motion_frag, sizeof(kSpirv_gbuffer_sample_motion_frag))
                                     : module(kSpirv_gbuffer_sample_frag, sizeof(kSpirv_gbuffer_sample_frag)))
                      : (writes_motion ? module(kSpirv_gbuffer_motion_frag, sizeof(kSpirv_gbuffer_motion_frag))
                                     : module(kSpirv_gbuffer_frag, sizeof(kSpirv_gbuffer_frag))))
           : desc.sample_shading
               ? (writes_motion ? module(kSpirv_scene_sample_motion_frag, sizeof(kSpirv_scene_sample_motion_frag))
                              : module(kSpirv_scene_sample_frag, sizeof(kSpirv_scene_sample_frag)))
               : (writes_motion ? module(kSpirv_scene_motion_frag, sizeof(kSpirv_scene_motion_frag))
                              : module(kSpirv_scene_frag, sizeof(kSpirv_scene_frag)));
}

// The fixed-function state of a scene pipeline that holds no pointers: triangle lists, one
// dynamic viewport and scissor, back faces culled unless double-sided, reversed-Z depth (BLEND
// draws test but do not write it).
struct SceneFixedState {
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
};

SceneFixedState sceneFixedState(AlphaMode mode, bool double_sided) {
    SceneFixedState f;
    f.assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    f.viewport.viewportCount = 1;
    f.viewport.scissorCount = 1;
    f.raster.polygonMode = VK_POLYGON_MODE_FILL;
    f.raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    f.raster.cullMode = double_sided ? VK_CULL_MODE_NONE : VK_CULL_MODE_BACK_BIT;
    f.raster.lineWidth = 1.0f;
    f.depth.depthTestEnable = VK_TRUE;
    f.depth.depthWriteEnable = mode == AlphaMode::Blend ? VK_FALSE : VK_TRUE;
    f.depth.depthCompareOp = VK_COMPARE_OP_GREATER_OR_EQUAL;  // reversed Z: near = 1, far = 0
    return f;
}

// desc's sample count and sample-rate shading; with programmable sample locations, chained
// to `locations` (which must outlive the pipeline's creation).
VkPipelineMultisampleStateCreateInfo sceneMultisample(const ScenePipelineDesc& desc,
                                                      VkPipelineSampleLocationsStateCreateInfoEXT& locations) {
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = desc.samples;
    // Sample-rate shading: each of the two samples is a separately shaded full-res pixel.
    ms.sampleShadingEnable = desc.sample_shading ? VK_TRUE : VK_FALSE;
    ms.minSampleShading = desc.sample_shading ? 1.0f : 0.0f;
    if (desc.sample_locations) {
        locations.sampleLocationsEnable = VK_TRUE;
        locations.sampleLocationsInfo.sType = VK_STRUCTURE_TYPE_SAMPLE_LOCATIONS_INFO_EXT;
        ms.pNext = &locations;
    }
    return ms;
}

// The attachments' formats and blending: colour (or the G-buffer's three), then motion, masked
// off unless the shader writes it.
struct SceneAttachments {
    std::vector<VkFormat> formats;
    std::vector<VkPipelineColorBlendAttachmentState> blends;
};

SceneAttachments sceneAttachments(const ScenePipelineDesc& desc, AlphaMode mode, bool writes_motion) {
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
    VkPipelineColorBlendAttachmentState motion_blend{};
    motion_blend.colorWriteMask = writes_motion ? VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT : 0;
    SceneAttachments a;
    if (desc.gbuffer) {
        a.formats.assign(std::begin(kGBufferFormats), std::end(kGBufferFormats));
        a.blends.assign(3, blend);
    } else {
        a.formats.push_back(desc.analysis ? kAnalysisFormat : desc.color_format);
        a.blends.push_back(blend);
    }
    if (desc.motion) {
        a.formats.push_back(kMotionFormat);
        a.blends.push_back(motion_blend);
    }
    return a;
}

// writes_motion: the fragment shader has the motion output (else a motion attachment, if
// the desc has one, is masked off).
VkPipeline createScenePipeline(vk::Context& ctx, VkPipelineLayout layout, const ScenePipelineDesc& desc,
                               AlphaMode mode, bool double_sided, bool writes_motion) {
    VkShaderModule vert = vk::createShaderModule(ctx, kSpirv_scene_vert, sizeof(kSpirv_scene_vert));
    writes_motion = writes_motion && desc.motion && mode != AlphaMode::Blend;
    VkShaderModule frag = sceneFragmentModule(ctx, desc, writes_motion);
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
    const SceneFixedState fixed = sceneFixedState(mode, double_sided);
    VkPipelineSampleLocationsStateCreateInfoEXT locations{
        VK_STRUCTURE_TYPE_PIPELINE_SAMPLE_LOCATIONS_STATE_CREATE_INFO_EXT};
    const VkPipelineMultisampleStateCreateInfo ms = sceneMultisample(desc, locations);
    const SceneAttachments attachments = sceneAttachments(desc, mode, writes_motion);
    VkPipelineColorBlendStateCreateInfo blend_state{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blend_state.attachmentCount = uint32_t(attachments.blends.size());
    blend_state.pAttachments = attachments.blends.data();
    std::vector<VkDynamicState> dynamic = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    if (desc.sample_locations) dynamic.push_back(VK_DYNAMIC_STATE_SAMPLE_LOCATIONS_EXT);
    VkPipelineDynamicStateCreateInfo dynamic_state{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dynamic_state.dynamicStateCount = uint32_t(dynamic.size());
    dynamic_state.pDynamicStates = dynamic.data();
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.viewMask = desc.view_mask;
    rendering.colorAttachmentCount = uint32_t(attachments.formats.size());
    rendering.pColorAttachmentFormats = attachments.formats.data();
    rendering.depthAttachmentFormat = desc.depth_format;

    VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
    info.stageCount = 2;
    info.pStages = stages;
    info.pVertexInputState = &vertex_input;
    info.pInputAssemblyState = &fixed.assembly;
    info.pViewportState = &fixed.viewport;
    info.pRasterizationState = &fixed.raster;
    info.pMultisampleState = &ms;
    info.pDepthStencilState = &fixed.depth;
    info.pColorBlendState = &blend_state;
    info.pDynamicState = &dynamic_state;
    info.layout = layout;
    VkPipeline pipeline;
    VK_CHECK(vkCreateGraphicsPipelines(ctx.device, ctx.pipeline_cache, 1, &info, nullptr, &pipeline));
    vkDestroyShaderModule(ctx.device, vert, nullptr);
    vkDestroyShaderModule(ctx.device, frag, nullptr);
    return pipeline;
}

void setViewport(VkCommandBuffer cmd, const SceneFrame& f) {
    glm::vec2 size = f.viewport_size.x > 0 ? f.viewport_size : glm::vec2(f.viewport.width, f.viewport.height);
    VkViewport vp{0, 0, size.x, size.y, 0, 1};
    VkRect2D scissor{{0, 0}, f.viewport};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    if (f.sample_locations) {
        VkSampleLocationEXT locations[2] = {{f.sample_positions[0].x, f.sample_positions[0].y},
                                            {f.sample_positions[1].x, f.sample_positions[1].y}};
        VkSampleLocationsInfoEXT info{VK_STRUCTURE_TYPE_SAMPLE_LOCATIONS_INFO_EXT};
        info.sampleLocationsPerPixel = VK_SAMPLE_COUNT_2_BIT;
        info.sampleLocationGridSize = {1, 1};
        info.sampleLocationsCount = 2;
        info.pSampleLocations = locations;
        f.set_sample_locations(cmd, &info);
    }
}

enum class Draws { All, Static, Moving };

void drawItems(VkCommandBuffer cmd, const SceneFrame& f, const std::vector<gpu::DrawItem>& items,
               const VkPipeline (&pipelines)[2], Draws which = Draws::All) {
    const gpu::GpuScene& s = *f.scene;
    int bound_material = -1;
    VkPipeline bound_pipeline = VK_NULL_HANDLE;
    for (const auto& d : items) {
        if (which != Draws::All && d.moving != (which == Draws::Moving)) continue;
        if (d.material != bound_material) {
            VkPipeline pipeline = pipelines[s.cpu->materials[size_t(d.material)].double_sided ? 1 : 0];
            if (pipeline != bound_pipeline) {
                vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
                bound_pipeline = pipeline;
            }
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipelines->layout, 1, 1,
                                    &s.material_sets[size_t(d.material)], 0, nullptr);
            bound_material = d.material;
        }
        const auto& mesh = s.cpu->meshes[size_t(d.mesh)];
        // firstInstance selects the instance's matrices in the frame set's instance buffer.
        vkCmdDrawIndexed(cmd, mesh.index_count, 1, mesh.first_index, mesh.vertex_offset, uint32_t(d.instance));
    }
}

// layer < 0: the whole image (or all views); else that layer's 2D view. clear: colour
// and depth cleared; else both loaded, depth read-only, unless clear_colour_only (the CFB:
// transparent colour from zero over the opaque depth).
// The colour attachments of a scene pass in attachment order, each with the value it is
// cleared to: colour (the background, or zero for the CFB), the G-buffer's extras, motion.
std::vector<std::pair<const vk::Image*, glm::vec4>> colourClears(const SceneFrame& f, const SceneTargets& t,
                                                                 bool checkerboard_forward_buffer) {
    std::vector<std::pair<const vk::Image*, glm::vec4>> out;
    out.push_back({t.color, checkerboard_forward_buffer ? glm::vec4(0.0f) : glm::vec4(glm::vec3(f.clear_color), 0.0f)});
    for (const vk::Image* extra : t.extra)
        if (extra) out.push_back({extra, glm::vec4(0.0f)});
    // Sky: no motion; or, when only moving instances write it, "derive from depth".
    bool moving_only = f.pipelines && f.pipelines->moving_only_motion;
    if (t.motion) out.push_back({t.motion, moving_only ? glm::vec4(kMotionFromDepth, 0.0f, 0.0f, 0.0f) : glm::vec4(0.0f)});
    return out;
}

bool clearedByCompute(const SceneFrame& f, const vk::Image& image) { return f.clear && image.compute_clearable; }

// Before a pass that clears its colour targets: the compute clear of those that take it
// (target_clear.h); beginScene then loads them.
void clearByCompute(VkCommandBuffer cmd, const SceneFrame& f, const SceneTargets& t, bool checkerboard_forward_buffer) {
    for (const auto& [img, value] : colourClears(f, t, checkerboard_forward_buffer))
        if (clearedByCompute(f, *img)) f.clear->record(cmd, *img, value);
}

void beginScene(VkCommandBuffer cmd, const SceneFrame& f, const SceneTargets& t, bool clear, int layer,
                bool clear_colour_only = false) {
    auto view = [layer](const vk::Image* img) { return layer < 0 ? img->view : img->layer_views[size_t(layer)]; };
    std::vector<VkRenderingAttachmentInfo> color_att;
    for (const auto& [img, clear_value] : colourClears(f, t, clear_colour_only)) {
        VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        a.imageView = view(img);
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        // A target the pass cleared by compute (clearByCompute) is loaded.
        bool cleared_here = (clear || clear_colour_only) && !clearedByCompute(f, *img);
        a.loadOp = cleared_here ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
        a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        a.clearValue.color = {{clear_value.r, clear_value.g, clear_value.b, clear_value.a}};
        color_att.push_back(a);
    }
    VkRenderingAttachmentInfo depth_att{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth_att.imageView = view(t.depth);
    depth_att.imageLayout = clear ? VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
    depth_att.loadOp = clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    depth_att.storeOp = clear ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_NONE;
    depth_att.clearValue.depthStencil = {0.0f, 0};  // reversed Z: far plane at 0
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, f.viewport};
    info.layerCount = 1;
    info.viewMask = layer < 0 ? t.view_mask : 0;
    info.colorAttachmentCount = uint32_t(color_att.size());
    info.pColorAttachments = color_att.data();
    info.pDepthAttachment = &depth_att;
    vkCmdBeginRendering(cmd, &info);
    setViewport(cmd, f);
    const gpu::GpuScene& s = *f.scene;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, f.pipelines->layout, 0, 1, &f.frame_set, 0,
                            nullptr);
    VkDeviceSize offset = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &s.vertices.buffer, &offset);
    vkCmdBindIndexBuffer(cmd, s.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    constexpr uint32_t kNoOffset = 2;  // scene.vert
    uint32_t push_layer = t.unjittered ? kNoOffset : layer < 0 ? 0u : uint32_t(layer);
    vkCmdPushConstants(cmd, f.pipelines->layout, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(uint32_t), &push_layer);
}

// Runs `body` once per rendering instance: once, or once per layer for sequential layers.
template <class F>
void forEachLayer(const SceneTargets& t, F&& body) {
    if (!t.sequential_layers) {
        body(-1);
        return;
    }
    for (int layer = 0; layer < int(t.color->layers); ++layer) body(layer);
}

}  // namespace

ScenePipelines createScenePipelines(vk::Context& ctx, const gpu::GpuScene& scene, const ScenePipelineDesc& desc) {
    ScenePipelines p;
    VkDescriptorSetLayout sets[2] = {scene.frame_layout, scene.material_layout};
    VkPushConstantRange push{VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(uint32_t)};
    VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    info.setLayoutCount = 2;
    info.pSetLayouts = sets;
    info.pushConstantRangeCount = 1;
    info.pPushConstantRanges = &push;
    VK_CHECK(vkCreatePipelineLayout(ctx.device, &info, nullptr, &p.layout));
    // A feature costs only when the scene has it: no MASK or BLEND material (or no
    // double-sided one), no pipeline.
    p.moving_only_motion = desc.motion && !desc.motion_every_draw;
    auto wanted = [&](const std::vector<gpu::DrawItem>& items, bool double_sided, Draws which) {
        return std::any_of(items.begin(), items.end(), [&](const gpu::DrawItem& d) {
            return scene.cpu->materials[size_t(d.material)].double_sided == double_sided &&
                   (which == Draws::All || d.moving == (which == Draws::Moving));
        });
    };
    // Without a split every draw uses the first set, writing motion when the target has it.
    Draws first = p.moving_only_motion ? Draws::Static : Draws::All;
    bool first_writes = desc.motion && !p.moving_only_motion;
    for (int two = 0; two < 2; ++two) {
        if (wanted(scene.opaque, two, first))
            p.opaque[two] = createScenePipeline(ctx, p.layout, desc, AlphaMode::Opaque, two, first_writes);
        if (wanted(scene.masked, two, first))
            p.masked[two] = createScenePipeline(ctx, p.layout, desc, AlphaMode::Mask, two, first_writes);
        if (wanted(scene.blend, two, Draws::All) && !desc.analysis && !desc.gbuffer)
            p.blend[two] = createScenePipeline(ctx, p.layout, desc, AlphaMode::Blend, two, false);
        if (!p.moving_only_motion) continue;
        if (wanted(scene.opaque, two, Draws::Moving))
            p.opaque_moving[two] = createScenePipeline(ctx, p.layout, desc, AlphaMode::Opaque, two, true);
        if (wanted(scene.masked, two, Draws::Moving))
            p.masked_moving[two] = createScenePipeline(ctx, p.layout, desc, AlphaMode::Mask, two, true);
    }
    return p;
}

void destroyScenePipelines(vk::Context& ctx, ScenePipelines& p) {
    for (int two = 0; two < 2; ++two)
        for (VkPipeline pipeline : {p.opaque[two], p.masked[two], p.blend[two], p.opaque_moving[two], p.masked_moving[two]})
            if (pipeline) vkDestroyPipeline(ctx.device, pipeline, nullptr);
    if (p.layout) vkDestroyPipelineLayout(ctx.device, p.layout, nullptr);
    p = {};
}

namespace {

// Opaque and alpha-tested draws into cleared targets: the `opaque`, `gbuffer` and
// `analysis` passes differ only in name, pipelines (in `frame`) and targets.
void addClearedGeometryPass(graph::Graph& graph, const char* name, bool timed, const SceneTargets& targets,
                            std::shared_ptr<const SceneFrame> frame) {
    graph::Pass pass;
    pass.name = name;
    pass.timed = timed;
    pass.uses = {{targets.color, graph::Use::ColorWrite}, {targets.depth, graph::Use::DepthWrite}};
    for (vk::Image* extra : targets.extra)
        if (extra) pass.uses.push_back({extra, graph::Use::ColorWrite});
    if (targets.motion) pass.uses.push_back({targets.motion, graph::Use::ColorWrite});
    pass.record = [frame, targets](VkCommandBuffer cmd) {
        clearByCompute(cmd, *frame, targets, false);
        forEachLayer(targets, [&](int layer) {
            beginScene(cmd, *frame, targets, true, layer);
            const gpu::GpuScene& s = *frame->scene;
            const ScenePipelines& p = *frame->pipelines;
            if (!p.moving_only_motion) {
                drawItems(cmd, *frame, s.opaque, p.opaque);
                drawItems(cmd, *frame, s.masked, p.masked);
            } else {
                // Every static draw first, so a static surface in front of a moving one
                // has already failed the moving one's depth test and keeps the sentinel.
                drawItems(cmd, *frame, s.opaque, p.opaque, Draws::Static);
                drawItems(cmd, *frame, s.masked, p.masked, Draws::Static);
                drawItems(cmd, *frame, s.opaque, p.opaque_moving, Draws::Moving);
                drawItems(cmd, *frame, s.masked, p.masked_moving, Draws::Moving);
            }
            vkCmdEndRendering(cmd);
        });
    };
    graph.addPass(std::move(pass));
}

}  // namespace

void addOpaquePass(graph::Graph& graph, const SceneTargets& targets, std::shared_ptr<const SceneFrame> frame) {
    addClearedGeometryPass(graph, "opaque", true, targets, std::move(frame));
}

void addGBufferPass(graph::Graph& graph, const SceneTargets& targets, std::shared_ptr<const SceneFrame> frame) {
    addClearedGeometryPass(graph, "gbuffer", true, targets, std::move(frame));
}

void addAnalysisPass(graph::Graph& graph, const SceneTargets& targets, std::shared_ptr<const SceneFrame> frame) {
    addClearedGeometryPass(graph, "analysis", false, targets, std::move(frame));
}

void addTransparentPass(graph::Graph& graph, const SceneTargets& targets, std::shared_ptr<const SceneFrame> frame,
                        bool checkerboard_forward_buffer) {
    graph::Pass pass;
    pass.name = checkerboard_forward_buffer ? "cfb" : "transparent";
    pass.uses = {{targets.color, checkerboard_forward_buffer ? graph::Use::ColorWrite : graph::Use::ColorReadWrite},
                 {targets.depth, graph::Use::DepthTest}};
    if (targets.motion) pass.uses.push_back({targets.motion, graph::Use::ColorReadWrite});
    pass.record = [frame, targets, checkerboard_forward_buffer](VkCommandBuffer cmd) {
        // Back to front by the distance of each instance's bounds centre: correct for
        // separate panes, which is what blended scenes here contain.
        const auto& s = *frame->scene;
        std::vector<std::pair<float, gpu::DrawItem>> sorted;
        for (const auto& d : s.blend) {
            const auto& mesh = s.cpu->meshes[size_t(d.mesh)];
            // Camera-relative models: the centre is the vector from the camera.
            glm::vec3 to = glm::vec3(frame->models[size_t(d.instance)] *
                                     glm::vec4((mesh.bounds_min + mesh.bounds_max) * 0.5f, 1.0f));
            sorted.push_back({glm::dot(to, to), d});
        }
        std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        std::vector<gpu::DrawItem> items;
        for (const auto& [dist, d] : sorted) items.push_back(d);
        if (checkerboard_forward_buffer) clearByCompute(cmd, *frame, targets, true);
        forEachLayer(targets, [&](int layer) {
            beginScene(cmd, *frame, targets, false, layer, checkerboard_forward_buffer);
            drawItems(cmd, *frame, items, frame->pipelines->blend);
            vkCmdEndRendering(cmd);
        });
    };
    graph.addPass(std::move(pass));
}

}  // namespace cbr::passes
