// Built-in scenes: `atrium`, laid out to stress checkerboard reconstruction, and plain `blocks`.
//
// The atrium's layout is a contract with camera_paths/ (its flythrough is hand-placed):
// Y up, floor at y = 0, walls at x = +-10 and z = +-6, 6 m tall, open to the sky; a clear
// aisle along X (|z| < 1, 0 <= y <= 3 holds no geometry); pillars at x = -8..8 step 4,
// z = +-2, so one stands near x = 0, z = 2 in front of the striped far wall.
// What each part stresses (see docs/method/checkerboard.md):
//   thin geometry (cables ~1 cm, railing balusters, coat hangers): detail under one
//     quarter-res pixel, where ASO smears and CSO should recover;
//   checker floor and striped walls: high-contrast edges and texture aliasing (crawl);
//   pillars, railing and fence in front of far walls: disocclusion when the camera moves;
//   chain-link fence and foliage (MASK): alpha-tested edges inside a surface;
//   glass panes (BLEND): the transparent pass over reconstructed content;
//   an orbiting box and a spinning turnstile: per-object motion vectors.
#include "renderer/scene/procedural.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/scene/geometry.h"

namespace cbr::scene {
namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kHalfX = 10.0f;
constexpr float kHalfZ = 6.0f;
constexpr float kHeight = 6.0f;
constexpr float kPillarXs[] = {-8.0f, -4.0f, 0.0f, 4.0f, 8.0f};
constexpr float kPillarZ = 2.0f;
constexpr float kPillarRadius = 0.3f;
constexpr float kBeamBottom = 5.2f;
constexpr float kRailingZ = -1.3f;
constexpr float kFenceZ = 3.2f;
constexpr float kRackZ = 1.35f;
constexpr float kRackRodY = 1.9f;
// About one full-res pixel (960x540, 60 degree field of view) at 5 m: 2*5*tan(30)/540.
constexpr float kCableRadius = 0.005f;
constexpr float kHangerRadius = 0.003f;

Material plain(std::string name, glm::vec3 color, float roughness) {
    Material m;
    m.name = std::move(name);
    m.base_color_factor = glm::vec4(color, 1.0f);
    // Dielectric throughout: without environment lighting a metal renders nearly black.
    m.metallic_factor = 0.0f;
    m.roughness_factor = roughness;
    return m;
}

Material textured(std::string name, int texture, glm::vec3 tint, float roughness) {
    Material m = plain(std::move(name), tint, roughness);
    m.base_color_texture = texture;
    return m;
}

Material glass(std::string name, glm::vec3 tint) {
    Material m = plain(std::move(name), tint, 0.05f);
    m.base_color_factor.a = 0.3f;
    m.alpha_mode = AlphaMode::Blend;
    m.double_sided = true;
    return m;
}

Material masked(std::string name, int texture, float roughness) {
    Material m = textured(std::move(name), texture, glm::vec3(1.0f), roughness);
    m.alpha_mode = AlphaMode::Mask;
    m.alpha_cutoff = 0.5f;
    m.double_sided = true;
    return m;
}

glm::mat4 placed(glm::vec3 position, float yaw = 0.0f) {
    return glm::rotate(glm::translate(glm::mat4(1.0f), position), yaw, glm::vec3(0, 1, 0));
}

// A coat hanger in its own plane (x across, y up), hook centre at the origin so the
// instance can be placed with the hook on a rod.
std::vector<glm::vec3> hangerPath() {
    constexpr float kHook = 0.025f;
    std::vector<glm::vec3> path;
    for (int i = 0; i <= 12; ++i) {  // open tip at -50 degrees, over the top, to 180
        const float a = glm::radians(-50.0f + 230.0f * float(i) / 12.0f);
        path.emplace_back(kHook * std::cos(a), kHook * std::sin(a), 0.0f);
    }
    const glm::vec3 corners[] = {
        {-kHook, -0.03f, 0.0f},   // neck
        {0.0f, -0.07f, 0.0f},     // twist
        {-0.2f, -0.25f, 0.0f},    // left shoulder end
        {0.2f, -0.25f, 0.0f},     // bottom bar
        {0.006f, -0.072f, 0.004f} // right shoulder back up to the twist
    };
    std::vector<glm::vec3> body{path.back()};
    body.insert(body.end(), std::begin(corners), std::end(corners));
    const std::vector<glm::vec3> rounded = roundCorners(body, 0.02f, 4);
    path.insert(path.end(), rounded.begin() + 1, rounded.end());
    return path;
}

void addFloorAndWalls(Scene& scene, int checker, int stripes) {
    const int floor_material = addMaterial(scene, textured("floor_checker", checker, glm::vec3(1.0f), 0.7f));
    MeshBuilder floor;
    // 1 texture tile per metre, 8 checks per tile: 12.5 cm checks alias at distance.
    addGrid(floor, {-kHalfX, 0, kHalfZ}, {2 * kHalfX, 0, 0}, {0, 0, -2 * kHalfZ}, 20, 12,
            {2 * kHalfX, 2 * kHalfZ});
    addInstance(scene, addMesh(scene, "floor", floor, floor_material), glm::mat4(1.0f));

    const int wall_material = addMaterial(scene, textured("wall_stripes", stripes, glm::vec3(1.0f), 0.8f));
    MeshBuilder walls;
    const float tiles_x = kHalfX, tiles_z = kHalfZ, tiles_y = kHeight / 2;  // 2 m tiles
    // Long walls: vertical stripes; end walls: texture u runs up, so stripes lie flat.
    addGrid(walls, {-kHalfX, 0, -kHalfZ}, {2 * kHalfX, 0, 0}, {0, kHeight, 0}, 4, 2, {tiles_x, tiles_y});
    addGrid(walls, {kHalfX, 0, kHalfZ}, {-2 * kHalfX, 0, 0}, {0, kHeight, 0}, 4, 2, {tiles_x, tiles_y});
    addGrid(walls, {-kHalfX, 0, -kHalfZ}, {0, kHeight, 0}, {0, 0, 2 * kHalfZ}, 2, 4, {tiles_y, tiles_z});
    addGrid(walls, {kHalfX, 0, kHalfZ}, {0, kHeight, 0}, {0, 0, -2 * kHalfZ}, 2, 4, {tiles_y, tiles_z});
    addInstance(scene, addMesh(scene, "walls", walls, wall_material), glm::mat4(1.0f));
}

void addStructure(Scene& scene) {
    const int stone = addMaterial(scene, plain("stone", {0.72f, 0.68f, 0.6f}, 0.8f));
    MeshBuilder pillar;
    addBox(pillar, {-0.4f, 0.0f, -0.4f}, {0.4f, 0.3f, 0.4f});
    addCylinder(pillar, {0, 0.3f, 0}, {0, kBeamBottom, 0}, kPillarRadius, 24, false);
    const int pillar_mesh = addMesh(scene, "pillar", pillar, stone);
    for (float z : {-kPillarZ, kPillarZ})
        for (float x : kPillarXs) addInstance(scene, pillar_mesh, placed({x, 0, z}));

    MeshBuilder beams;
    for (float x : kPillarXs) addBox(beams, {x - 0.15f, kBeamBottom, -2.3f}, {x + 0.15f, 5.5f, 2.3f});
    for (float z : {-kPillarZ, kPillarZ}) addBox(beams, {-8.3f, 5.5f, z - 0.2f}, {8.3f, 5.8f, z + 0.2f});
    addInstance(scene, addMesh(scene, "beams", beams, stone), glm::mat4(1.0f));

    // Turnstile pedestal; the turnstile itself moves (addMovers).
    MeshBuilder pedestal;
    addBox(pedestal, {-0.3f, 0.0f, -0.3f}, {0.3f, 0.9f, 0.3f});
    addInstance(scene, addMesh(scene, "pedestal", pedestal, stone), placed({-6.0f, 0, -3.6f}));
}

void addThinGeometry(Scene& scene) {
    const int paint = addMaterial(scene, plain("railing_paint", {0.75f, 0.1f, 0.07f}, 0.5f));
    MeshBuilder railing;
    for (float x = -9.0f; x <= 9.01f; x += 3.0f)
        addCylinder(railing, {x, 0, kRailingZ}, {x, 1.05f, kRailingZ}, 0.03f, 8, true);
    addCylinder(railing, {-9, 1.05f, kRailingZ}, {9, 1.05f, kRailingZ}, 0.025f, 8, true);
    addCylinder(railing, {-9, 0.55f, kRailingZ}, {9, 0.55f, kRailingZ}, 0.012f, 6, true);
    addCylinder(railing, {-9, 0.08f, kRailingZ}, {9, 0.08f, kRailingZ}, 0.012f, 6, true);
    for (int i = 0; i <= 150; ++i) {  // balusters every 12 cm
        const float x = -9.0f + 0.12f * float(i);
        addCylinder(railing, {x, 0.08f, kRailingZ}, {x, 1.05f, kRailingZ}, 0.008f, 6, false);
    }
    addInstance(scene, addMesh(scene, "railing", railing, paint), glm::mat4(1.0f));

    // Dark cables against the bright sky and the light stripes.
    const int cable = addMaterial(scene, plain("cable", {0.03f, 0.03f, 0.03f}, 0.6f));
    MeshBuilder cables;
    for (float z : {-0.6f, 0.6f})
        for (int i = 0; i + 1 < 5; ++i) {
            const auto wire = saggingWire({kPillarXs[i], kBeamBottom, z}, {kPillarXs[i + 1], kBeamBottom, z}, 0.5f, 16);
            addTube(cables, wire, kCableRadius, 6, false);
        }
    for (float x : {-4.0f, 4.0f}) addCylinder(cables, {x, kBeamBottom, 0}, {x, 3.5f, 0}, 0.004f, 6, false);
    // Straight diagonals give stair-stepped edges at every angle; each ends in a pillar.
    addCylinder(cables, {-9.9f, 5.8f, -5.9f}, {-4.0f, 4.0f, 1.8f}, kCableRadius, 6, false);
    addCylinder(cables, {9.9f, 5.5f, 5.9f}, {4.0f, 3.8f, -1.8f}, kCableRadius, 6, false);
    addInstance(scene, addMesh(scene, "cables", cables, cable), glm::mat4(1.0f));

    const int chrome = addMaterial(scene, plain("chrome", {0.9f, 0.9f, 0.88f}, 0.3f));
    MeshBuilder rack;
    for (float x : {-7.0f, -5.0f}) {
        addCylinder(rack, {x, 0.02f, kRackZ}, {x, 1.95f, kRackZ}, 0.015f, 8, true);
        addCylinder(rack, {x, 0.02f, 1.1f}, {x, 0.02f, 1.6f}, 0.015f, 8, true);
    }
    addCylinder(rack, {-7.05f, kRackRodY, kRackZ}, {-4.95f, kRackRodY, kRackZ}, 0.012f, 8, true);
    addInstance(scene, addMesh(scene, "rack", rack, chrome), glm::mat4(1.0f));

    MeshBuilder hanger;
    addTube(hanger, hangerPath(), kHangerRadius, 6, true);
    const int hanger_mesh = addMesh(scene, "coat_hanger", hanger, chrome);
    const float hanger_x[] = {-6.5f, -6.0f, -5.5f};
    const float hanger_yaw[] = {0.0f, 0.6f, 1.4f};
    for (int i = 0; i < 3; ++i) addInstance(scene, hanger_mesh, placed({hanger_x[i], kRackRodY, kRackZ}, hanger_yaw[i]));

    MeshBuilder fence_frame;
    for (float x = -9.0f; x <= 9.01f; x += 3.0f)
        addCylinder(fence_frame, {x, 0, kFenceZ}, {x, 2.5f, kFenceZ}, 0.03f, 8, true);
    addCylinder(fence_frame, {-9, 2.45f, kFenceZ}, {9, 2.45f, kFenceZ}, 0.02f, 8, true);
    addInstance(scene, addMesh(scene, "fence_frame", fence_frame, chrome), glm::mat4(1.0f));
}

void addMasked(Scene& scene, int chain_link, int leaves) {
    const int fence_material = addMaterial(scene, masked("chain_link", chain_link, 0.5f));
    MeshBuilder fence;
    // 0.6 m tiles of 4 x 4 diamonds: 15 cm cells, wires about 1 cm thick.
    addGrid(fence, {9, 0.05f, kFenceZ}, {-18, 0, 0}, {0, 2.4f, 0}, 6, 1, {30.0f, 4.0f});
    addInstance(scene, addMesh(scene, "fence", fence, fence_material), glm::mat4(1.0f));

    const int planter_material = addMaterial(scene, plain("terracotta", {0.6f, 0.3f, 0.18f}, 0.9f));
    MeshBuilder planter;
    addBox(planter, {-0.5f, 0.0f, -0.3f}, {0.5f, 0.5f, 0.3f});
    const int planter_mesh = addMesh(scene, "planter", planter, planter_material);

    const int foliage_material = addMaterial(scene, masked("foliage", leaves, 0.8f));
    MeshBuilder foliage;
    for (float degrees : {0.0f, 60.0f, 120.0f}) {  // crossed cards, v = 0 at the top
        const float a = glm::radians(degrees);
        const glm::vec3 across(std::cos(a), 0.0f, std::sin(a));
        addGrid(foliage, glm::vec3(0, 2.05f, 0) - 0.7f * across, 1.4f * across, {0, -1.6f, 0}, 1, 1, {1, 1});
    }
    const int foliage_mesh = addMesh(scene, "foliage", foliage, foliage_material);
    for (float x : {-2.0f, 2.0f, 6.0f}) {
        addInstance(scene, planter_mesh, placed({x, 0, -3.6f}));
        addInstance(scene, foliage_mesh, placed({x, 0, -3.6f}));
    }
}

void addGlass(Scene& scene) {
    struct Pane { const char* name; glm::vec3 tint; glm::vec2 size; };
    const Pane panes[] = {
        {"glass_blue", {0.55f, 0.75f, 1.0f}, {3.2f, 2.5f}},
        {"glass_amber", {1.0f, 0.7f, 0.3f}, {3.2f, 2.2f}},
        {"glass_green", {0.6f, 1.0f, 0.75f}, {0.7f, 2.1f}},
    };
    int meshes[3];
    for (int i = 0; i < 3; ++i) {
        MeshBuilder pane;
        addGrid(pane, {-panes[i].size.x / 2, 0, 0}, {panes[i].size.x, 0, 0}, {0, panes[i].size.y, 0}, 1, 1, {1, 1});
        meshes[i] = addMesh(scene, panes[i].name, pane, addMaterial(scene, glass(panes[i].name, panes[i].tint)));
    }
    // Blue panes in front of the foliage, amber in front of a pillar bay and the fence,
    // green fins across the aisle's edge (seen face-on when walking).
    addInstance(scene, meshes[0], placed({-2.0f, 0.1f, -2.8f}));
    addInstance(scene, meshes[0], placed({2.0f, 0.1f, -2.8f}));
    addInstance(scene, meshes[1], placed({6.0f, 0.2f, 1.2f}));
    addInstance(scene, meshes[2], placed({-2.0f, 0.1f, 1.45f}, kPi / 2));
    addInstance(scene, meshes[2], placed({2.0f, 0.1f, 1.45f}, kPi / 2));
}

void addMoversAndLights(Scene& scene, int checker) {
    Material lamp = plain("lamp", {1.0f, 0.95f, 0.85f}, 0.5f);
    lamp.emissive_factor = {1.0f, 0.85f, 0.6f};
    const int lamp_material = addMaterial(scene, lamp);
    MeshBuilder bulb;
    addSphere(bulb, glm::vec3(0), 0.15f, 12, 16);
    const int bulb_mesh = addMesh(scene, "lamp", bulb, lamp_material);
    for (float x : {-4.0f, 4.0f}) {
        addInstance(scene, bulb_mesh, placed({x, 3.35f, 0}));
        Light light;
        light.type = Light::Type::Point;
        light.position = {x, 3.0f, 0};  // just under the bulb, outside its geometry
        light.color = {1.0f, 0.85f, 0.6f};
        light.intensity = 15.0f;
        light.range = 12.0f;
        scene.lights.push_back(light);
    }
    Light sun;
    sun.direction = glm::normalize(glm::vec3(-0.35f, -1.0f, -0.25f));
    sun.color = {1.0f, 0.97f, 0.9f};
    sun.intensity = 2.5f;
    scene.lights.push_back(sun);

    // Checker-textured so that a wrong motion vector shows on the object itself.
    MeshBuilder box;
    addBox(box, glm::vec3(-0.18f), glm::vec3(0.18f), 2.8f);
    const int box_material = addMaterial(scene, textured("orbiter", checker, {1.0f, 0.45f, 0.15f}, 0.4f));
    Animation orbit;
    orbit.kind = Animation::Kind::Orbit;
    orbit.center = {-2.0f, 1.6f, 2.6f};  // vertical circle between the pillars and the fence
    orbit.axis = {0, 0, 1};
    orbit.radius = 0.8f;
    orbit.radians_per_second = 0.5f;
    addInstance(scene, addMesh(scene, "orbiter", box, box_material), placed(glm::vec3(0), kPi / 4), orbit);

    MeshBuilder turnstile;
    addBox(turnstile, {-0.5f, -0.15f, -0.03f}, {0.5f, 0.15f, 0.03f}, 2.8f);
    addBox(turnstile, {-0.03f, -0.15f, -0.5f}, {0.03f, 0.15f, 0.5f}, 2.8f);
    const int turnstile_material = addMaterial(scene, textured("turnstile", checker, {1.0f, 0.85f, 0.1f}, 0.4f));
    Animation spin;
    spin.kind = Animation::Kind::Spin;
    spin.center = {-6.0f, 1.05f, -3.6f};
    spin.axis = {0, 1, 0};
    spin.radians_per_second = 0.8f;
    addInstance(scene, addMesh(scene, "turnstile", turnstile, turnstile_material), placed(spin.center), spin);
}

}  // namespace

Scene buildAtrium() {
    Scene scene;
    scene.name = "atrium";
    scene.source = "procedural:atrium";
    scene.background = {0.45f, 0.55f, 0.7f};  // open sky: dark cables stand out against it
    const int checker = addTexture(scene, checkerTexture(256, 8));
    const int stripes = addTexture(scene, stripeTexture(256, 8));
    const int chain_link = addTexture(scene, chainLinkTexture(256, 4, 0.05f));
    const int leaves = addTexture(scene, leafTexture(256, 48, 0x5eedu));
    addFloorAndWalls(scene, checker, stripes);
    addStructure(scene);
    addThinGeometry(scene);
    addMasked(scene, chain_link, leaves);
    addGlass(scene);
    addMoversAndLights(scene, checker);
    return scene;
}

Scene buildBlocks() {
    Scene scene;
    scene.name = "blocks";
    scene.source = "procedural:blocks";
    const int ground = addMaterial(scene, plain("ground", {0.5f, 0.5f, 0.5f}, 0.9f));
    MeshBuilder plane;
    addGrid(plane, {-8, 0, 8}, {16, 0, 0}, {0, 0, -16}, 8, 8, {1, 1});
    addInstance(scene, addMesh(scene, "ground", plane, ground), glm::mat4(1.0f));

    struct Block { const char* name; glm::vec3 color; glm::vec3 min, max; };
    const Block blocks[] = {
        {"red_box", {0.8f, 0.15f, 0.1f}, {-2.5f, 0.0f, -1.5f}, {-1.3f, 1.2f, -0.3f}},
        {"blue_box", {0.1f, 0.25f, 0.8f}, {1.5f, 0.0f, -2.5f}, {2.5f, 2.0f, -1.5f}},
        {"green_box", {0.15f, 0.7f, 0.2f}, {0.5f, 0.0f, 1.0f}, {1.3f, 0.8f, 1.8f}},
    };
    for (const Block& b : blocks) {
        MeshBuilder box;
        addBox(box, b.min, b.max);
        addInstance(scene, addMesh(scene, b.name, box, addMaterial(scene, plain(b.name, b.color, 0.6f))),
                    glm::mat4(1.0f));
    }
    struct Ball { const char* name; glm::vec3 color; glm::vec3 center; float radius; };
    const Ball balls[] = {
        {"white_sphere", {0.9f, 0.9f, 0.9f}, {-0.5f, 0.7f, -0.2f}, 0.7f},
        {"yellow_sphere", {0.9f, 0.75f, 0.1f}, {2.8f, 0.5f, 1.2f}, 0.5f},
    };
    for (const Ball& b : balls) {
        MeshBuilder sphere;
        addSphere(sphere, b.center, b.radius, 16, 32);
        addInstance(scene, addMesh(scene, b.name, sphere, addMaterial(scene, plain(b.name, b.color, 0.4f))),
                    glm::mat4(1.0f));
    }
    Light sun;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    return scene;
}

}  // namespace cbr::scene
