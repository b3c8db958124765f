// LDR-FLIP's colour pipeline for the device scorer (score_flip_*.comp): P. Andersson, J. Nilsson,
// T. Akenine-Moller, M. Oskarsson, K. Astrom, M. D. Fairchild, "FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020. Constants from ScoreParams, filled by the same expressions as
// metrics/flip.cpp; the arithmetic follows that file's order, in single precision as there.
// `precise` everywhere a value of the reference and one of the test are made: a compiler free to
// fuse multiplies and adds does so differently in the two copies of unrolled code (NVIDIA did),
// and identical images then score 1e-6 instead of 0.

// Band plane p (SCORE_FLIP_YCC_PLANES, then the horizontal planes), band row r, column x.
int bandIndex(int p, int r, int x) { return p * push.plane + r * P.width + x; }

vec3 rgbToXyzScaled(vec3 c) {
    precise vec3 xyz = vec3((P.rgb_to_xyz[0] * c.r + P.rgb_to_xyz[1] * c.g + P.rgb_to_xyz[2] * c.b) * P.inv_white[0],
                (P.rgb_to_xyz[3] * c.r + P.rgb_to_xyz[4] * c.g + P.rgb_to_xyz[5] * c.b) * P.inv_white[1],
                (P.rgb_to_xyz[6] * c.r + P.rgb_to_xyz[7] * c.g + P.rgb_to_xyz[8] * c.b) * P.inv_white[2]);
    return xyz;
}

// 8-bit sRGB codes -> YCxCz: Y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn).
vec3 codesToYCxCz(uint v) {
    const uvec3 c = unpackCodes(v);
    const vec3 xyz = rgbToXyzScaled(vec3(P.srgb_to_linear[c.r], P.srgb_to_linear[c.g], P.srgb_to_linear[c.b]));
    precise vec3 ycc = vec3(116.0 * xyz.y - 16.0, 500.0 * (xyz.x - xyz.y), 200.0 * (xyz.y - xyz.z));
    return ycc;
}

// t^(1/3): the CPU's first guess from the float's bits and two Halley steps, bit for bit the same.
float cubeRoot(float t) {
    const int bits = floatBitsToInt(t);
    precise float y = intBitsToFloat(int(float(bits) * (1.0 / 3.0)) + 0x2A555555);
    for (int i = 0; i < 2; ++i) {
        precise float y3 = y * y * y;
        y = y * (y3 + 2.0 * t) / (2.0 * y3 + t);
    }
    return y;
}

float labF(float t) {
    precise float line = P.lab_slope * t + P.lab_offset;
    return t > P.lab_delta_cube ? cubeRoot(t) : line;
}

// Filtered YCxCz -> linear RGB clamped to [0,1] -> L*a*b* with the Hunt adjustment.
vec3 huntLab(vec3 f) {
    precise float yn = (f.x + 16.0) / 116.0;
    precise float X = (yn + f.y / 500.0) * P.white[0];
    precise float Y = yn * P.white[1];
    precise float Z = (yn - f.z / 200.0) * P.white[2];
    precise vec3 rgb = clamp(vec3(P.xyz_to_rgb[0] * X + P.xyz_to_rgb[1] * Y + P.xyz_to_rgb[2] * Z,
                                P.xyz_to_rgb[3] * X + P.xyz_to_rgb[4] * Y + P.xyz_to_rgb[5] * Z,
                                P.xyz_to_rgb[6] * X + P.xyz_to_rgb[7] * Y + P.xyz_to_rgb[8] * Z),
                           0.0, 1.0);
    const vec3 xyz = rgbToXyzScaled(rgb);
    const float fx = labF(xyz.x), fy = labF(xyz.y), fz = labF(xyz.z);
    precise float L = 116.0 * fy - 16.0;
    precise vec3 lab = vec3(L, 0.01 * L * (500.0 * (fx - fy)), 0.01 * L * (200.0 * (fy - fz)));
    return lab;
}

// HyAB (Abasi et al. 2020): city-block in lightness, Euclidean in chroma.
float hyab(vec3 a, vec3 b) {
    precise float d = abs(a.x - b.x) + sqrt((a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
    return d;
}

const float kQc = 0.7;
const float kPt = 0.95;

// error = colour^(1 - feature): the re-mapped colour error to the power the feature difference
// leaves (section 4 of the paper; finalRow in metrics/flip.cpp). v*: filtered Y, Cx, Cz, and
// the edge/point responses along x and y (dx, ddx, dy, ddy) of reference and test.
float flipError(vec3 ref, vec3 test, vec4 ref_features, vec4 test_features) {
    float colour = hyab(huntLab(ref), huntLab(test));
    colour = colour > 0.0 ? pow(colour, kQc) : 0.0;
    const float below = kPt / P.pccmax, above = (1.0 - kPt) / (P.cmax - P.pccmax);
    colour = colour < P.pccmax ? colour * below : kPt + (colour - P.pccmax) * above;
    const vec4 r = ref_features, t = test_features;
    precise float e1 = sqrt(r.x * r.x + r.z * r.z), e2 = sqrt(t.x * t.x + t.z * t.z);
    precise float p1 = sqrt(r.y * r.y + r.w * r.w), p2 = sqrt(t.y * t.y + t.w * t.w);
    precise float exponent = 1.0 - sqrt(P.feature_scale * max(abs(e1 - e2), abs(p1 - p2)));
    return colour > 0.0 ? pow(colour, exponent) : (exponent == 0.0 ? 1.0 : 0.0);
}
