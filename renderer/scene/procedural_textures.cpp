// Textures generated in code for the procedural scenes: high-contrast patterns and alpha masks.
#include "renderer/scene/procedural.h"

#include <algorithm>
#include <cmath>

namespace cbr::scene {
namespace {

constexpr uint8_t kDark = 18;    // sRGB; near black and near white for maximum edge contrast
constexpr uint8_t kLight = 235;

Texture blank(const char* name, int size) {
    Texture texture;
    texture.name = name;
    texture.width = size;
    texture.height = size;
    texture.srgb = true;
    texture.rgba8.assign(size_t(size) * size_t(size) * 4, 255);
    return texture;
}

void put(Texture& texture, int x, int y, uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
    uint8_t* p = &texture.rgba8[(size_t(y) * size_t(texture.width) + size_t(x)) * 4];
    p[0] = r;
    p[1] = g;
    p[2] = b;
    p[3] = a;
}

uint8_t toByte(float v) { return uint8_t(std::clamp(v, 0.0f, 255.0f) + 0.5f); }

}  // namespace

uint64_t Random::next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

float Random::uniform(float lo, float hi) {
    return lo + (hi - lo) * float(next() >> 40) * (1.0f / 16777216.0f);
}

Texture checkerTexture(int size, int checks) {
    Texture texture = blank("checker", size);
    const int cell = size / checks;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const uint8_t v = ((x / cell + y / cell) & 1) ? kDark : kLight;
            put(texture, x, y, v, v, v, 255);
        }
    return texture;
}

Texture stripeTexture(int size, int stripes) {
    Texture texture = blank("stripes", size);
    const int width = size / stripes;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const int in_stripe = x % width;
            bool dark = (x / width) & 1;
            // A two-texel line inside each light stripe adds detail finer than a
            // quarter-resolution pixel at mid distance.
            if (!dark && (in_stripe == width / 2 - 1 || in_stripe == width / 2)) dark = true;
            const uint8_t v = dark ? kDark : kLight;
            put(texture, x, y, v, v, v, 255);
        }
    return texture;
}

Texture chainLinkTexture(int size, int cells, float wire) {
    Texture texture = blank("chain_link", size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float u = (float(x) + 0.5f) / float(size) * float(cells);
            const float v = (float(y) + 0.5f) / float(size) * float(cells);
            const float a = u + v, b = u - v;
            const float d = std::min(std::abs(a - std::round(a)), std::abs(b - std::round(b)));
            const bool on_wire = d < wire;
            // Holes keep the wire's colour so filtering at the cut-out edge does not
            // darken it; only alpha cuts.
            const float shade = on_wire ? 205.0f - 70.0f * (d / wire) : 170.0f;
            put(texture, x, y, toByte(shade), toByte(shade + 4), toByte(shade + 8), on_wire ? 255 : 0);
        }
    return texture;
}

Texture leafTexture(int size, int leaves, uint64_t seed) {
    Texture texture = blank("leaves", size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) put(texture, x, y, 40, 90, 30, 0);

    Random random{seed};
    for (int i = 0; i < leaves; ++i) {
        const float half_length = random.uniform(0.05f, 0.09f);
        const float half_width = random.uniform(0.02f, 0.035f);
        const float cx = random.uniform(0.12f, 0.88f);
        const float cy = random.uniform(0.1f, 0.9f);
        const float angle = random.uniform(0.0f, 3.14159265f);
        const float r = random.uniform(35, 80), g = random.uniform(100, 170), b = random.uniform(25, 60);
        const float ca = std::cos(angle), sa = std::sin(angle);
        const int x0 = std::max(0, int((cx - half_length) * float(size)) - 1);
        const int x1 = std::min(size - 1, int((cx + half_length) * float(size)) + 1);
        const int y0 = std::max(0, int((cy - half_length) * float(size)) - 1);
        const int y1 = std::min(size - 1, int((cy + half_length) * float(size)) + 1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const float dx = (float(x) + 0.5f) / float(size) - cx;
                const float dy = (float(y) + 0.5f) / float(size) - cy;
                const float along = dx * ca + dy * sa, across = -dx * sa + dy * ca;
                const float e = (along / half_length) * (along / half_length) +
                                (across / half_width) * (across / half_width);
                if (e > 1.0f) continue;
                const float midrib = std::abs(across) < 0.004f ? 0.6f : 1.0f;
                const float tip = 0.8f + 0.2f * (along / half_length);
                put(texture, x, y, toByte(r * midrib * tip), toByte(g * midrib * tip),
                    toByte(b * midrib * tip), 255);
            }
    }
    return texture;
}

}  // namespace cbr::scene
