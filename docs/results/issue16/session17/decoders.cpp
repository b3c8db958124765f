#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
#include <png.h>
#include <spng.h>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>
using clk = std::chrono::steady_clock;
int main() {
    std::vector<std::vector<unsigned char>> files;
    for (int i = 0; i < 50; ++i) {
        char n[64]; snprintf(n, 64, "/tmp/big/big_%02d.png", i);
        std::ifstream f(n, std::ios::binary);
        files.emplace_back(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
    }
    size_t sum = 0;
    for (int round = 0; round < 3; ++round) {
        auto t0 = clk::now();
        for (auto& f : files) { int w, h, c; unsigned char* p = stbi_load_from_memory(f.data(), int(f.size()), &w, &h, &c, 4); sum += p[5]; stbi_image_free(p); }
        auto t1 = clk::now();
        for (auto& f : files) {
            png_image img{}; img.version = PNG_IMAGE_VERSION;
            png_image_begin_read_from_memory(&img, f.data(), f.size()); img.format = PNG_FORMAT_RGBA;
            std::vector<unsigned char> out(PNG_IMAGE_SIZE(img));
            png_image_finish_read(&img, nullptr, out.data(), 0, nullptr); sum += out[5];
        }
        auto t2 = clk::now();
        for (auto& f : files) {
            spng_ctx* ctx = spng_ctx_new(0);
            spng_set_png_buffer(ctx, f.data(), f.size());
            size_t sz; spng_decoded_image_size(ctx, SPNG_FMT_RGBA8, &sz);
            std::vector<unsigned char> out(sz);
            spng_decode_image(ctx, out.data(), sz, SPNG_FMT_RGBA8, 0); sum += out[5];
            spng_ctx_free(ctx);
        }
        auto t3 = clk::now();
        auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
        printf("stb %.1f ms  libpng %.1f ms  spng %.1f ms\n", ms(t0, t1), ms(t1, t2), ms(t2, t3));
    }
    return int(sum & 1);
}
