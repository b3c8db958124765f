#include <libdeflate.h>
#include <zlib.h>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>
using clk = std::chrono::steady_clock;
static unsigned be(const unsigned char* p) { return (p[0] << 24) | (p[1] << 16) | (p[2] << 8) | p[3]; }
int main() {
    std::vector<std::vector<unsigned char>> idats;
    size_t total = 0;
    for (int i = 0; i < 50; ++i) {
        char n[64]; snprintf(n, 64, "/tmp/big/big_%02d.png", i);
        std::ifstream f(n, std::ios::binary);
        std::vector<unsigned char> b((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
        std::vector<unsigned char> z;
        for (size_t p = 8; p + 8 <= b.size();) { unsigned len = be(&b[p]); if (!memcmp(&b[p + 4], "IDAT", 4)) z.insert(z.end(), &b[p + 8], &b[p + 8 + len]); p += 12 + len; }
        total += z.size(); idats.push_back(std::move(z));
    }
    printf("IDAT total %.1f MiB\n", total / 1048576.0);
    std::vector<unsigned char> out(512 * (512 * 4 + 1));
    auto* d = libdeflate_alloc_decompressor();
    for (int r = 0; r < 3; ++r) {
        auto t0 = clk::now(); size_t s = 0;
        for (auto& z : idats) { size_t got; libdeflate_zlib_decompress(d, z.data(), z.size(), out.data(), out.size(), &got); s += got; }
        auto t1 = clk::now();
        for (auto& z : idats) { uLongf got = out.size(); uncompress(out.data(), &got, z.data(), z.size()); s += got; }
        auto t2 = clk::now();
        auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
        printf("libdeflate %.1f ms  zlib %.1f ms (%zu)\n", ms(t0, t1), ms(t1, t2), s);
    }
}
