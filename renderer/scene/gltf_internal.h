// Shared by the glTF loader's files (not part of cbr_scene's interface): load context, error helpers.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "renderer/scene/gltf_validate.h"
#include "renderer/scene/scene.h"

namespace cbr::scene {

struct GltfContext {
    std::string file;
    tinygltf::Model& model;  // its decoded RGBA8 images are moved into the scene's textures
    Scene& scene;
    std::map<std::pair<int, bool>, int> textures;  // (image, sRGB) -> Scene texture
    std::map<int, int> moved_images;               // image whose pixels a Scene texture took -> that texture
    std::vector<int> materials;                    // glTF material -> Scene material, -1 until used
    int default_material = -1;
    std::vector<std::optional<std::vector<int>>> meshes;  // glTF mesh -> Scene meshes
    int skipped_primitives = 0;                           // points and lines
};

[[noreturn]] inline void gltfError(const GltfContext& ctx, const std::string& where, const std::string& what,
                                   const std::string& expected) {
    gltfFail(ctx.file, where, what, expected);
}

// "/array/index" as a JSON pointer.
inline std::string gltfAt(const char* array, size_t index) {
    std::string pointer("/");  // built by appending: GCC 12 warns falsely on "literal" + string&&
    pointer += array;
    pointer += '/';
    pointer += std::to_string(index);
    return pointer;
}

inline std::string gltfIndexRange(const char* array, size_t count) {
    return count ? "an index into /" + std::string(array) + " (0.." + std::to_string(count - 1) + ")"
                 : "no reference: /" + std::string(array) + " is empty";
}

// A checked accessor: every element lies inside its buffer view and buffer.
struct View {
    const uint8_t* data = nullptr;
    size_t stride = 0, count = 0;
    int components = 0, component_type = 0;
    bool normalized = false;
    std::string pointer, used_by;
};

// Checks type, component type (one of `component_types`) and bounds before anything is read.
View viewAccessor(const GltfContext& ctx, int index, const std::string& used_by, int type,
                  std::initializer_list<int> component_types);
// Elements as floats: FLOAT as is, normalized integers per glTF 2.0; a NaN or infinity
// throws naming the accessor, element and user.
std::vector<float> readFloats(const GltfContext& ctx, const View& view);
// Elements of an unsigned scalar accessor as uint32 (ranges are the caller's to check).
std::vector<uint32_t> readIndices(const View& view);

// The Scene meshes of glTF mesh `mesh_index`, one per triangle primitive, loaded on first use
// (gltf_primitives.cpp).
const std::vector<int>& gltfMeshes(GltfContext& ctx, size_t mesh_index);

// Animations and cameras (gltf_animation.cpp). `scene_node[i]` is the Scene::nodes index of
// glTF node i, -1 for nodes outside the scene. Channels on nodes outside the scene are
// dropped; "weights" channels are counted (morph targets are not animated).
void gltfAnimations(GltfContext& ctx, const std::vector<int>& scene_node);
// Targets of translation/rotation/scale channels of any animation, per glTF node.
std::vector<bool> gltfAnimatedNodes(const GltfContext& ctx);
void gltfCamera(GltfContext& ctx, const tinygltf::Node& node, size_t node_index, int scene_node);

// Images in two steps, so that decoding runs on every core (issue 16): tinygltf's image
// callback (TinyGLTF::SetImageLoader; user data: a GltfImages*) checks each image's header
// and keeps its encoded bytes; gltfDecodeImages decodes them all after the parse. PNG and
// JPEG only, the formats glTF 2.0 allows, and only when the bytes can hold the pixels the
// header claims, so a truncated 150-byte JPEG that says 16384x16384 is refused before the
// decoder allocates a gigabyte for it.
struct GltfImages {
    struct Encoded {
        int index = 0;                      // into model.images
        int req_width = 0, req_height = 0;  // a buffer view image's declared size, else 0
        std::vector<unsigned char> bytes;
    };
    std::string file;
    std::vector<Encoded> encoded;
};
bool gltfLoadImage(tinygltf::Image* image, int image_index, std::string* err, std::string* warn, int req_width,
                   int req_height, const unsigned char* bytes, int size, void* images);
// Decodes the recorded images into model.images (RGBA, 8 or 16 bits), one image per task on
// up to hardware_concurrency threads (CBR_DECODE_THREADS=N overrides, for measurements):
// 8-bit PNGs by decodePngRgba8 (png_decode.h) where it takes them, the rest by tinygltf's
// own decoder, whose pixels are the same (CBR_PNG_DECODER=stb sends every image there, for
// measurements). Returns tinygltf's error text for the lowest-numbered image that fails,
// empty when all decode.
std::string gltfDecodeImages(GltfImages& images, tinygltf::Model& model);

// Scene texture for a glTF texture index, decoded to RGBA8; sRGB for colour, linear for data.
int gltfTexture(GltfContext& ctx, int index, bool srgb, const std::string& used_by);
// Scene material for a glTF material index; -1 gives glTF's default material.
int gltfMaterial(GltfContext& ctx, int index, const std::string& used_by);

}  // namespace cbr::scene
