// The `tonemap` pass: HDR linear colour -> 8-bit sRGB display image (what metrics score).
#pragma once

#include "renderer/graph/graph.h"
#include "renderer/vk/pipelines.h"

namespace cbr::passes {

using Tonemap = vk::ImageKernel;

Tonemap createTonemap(vk::Context& ctx, vk::Image& hdr, vk::Image& display);
void destroyTonemap(vk::Context& ctx, Tonemap& t);
// pass_through: the HDR values already are display values (debug pixel-id mode).
void addTonemapPass(graph::Graph& graph, const Tonemap& t, vk::Image& hdr, vk::Image& display, float exposure,
                    bool pass_through = false);

}  // namespace cbr::passes
