// SPDX-License-Identifier: MIT
// softpipe_render.cpp — softpipe's pipeline per pass (softpipe_render.h): vertices, setup, quads,
// shading, blending into the float colour tile, and the final packing.
#include "raster/softpipe_render.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "raster/blend.h"
#include "raster/clip.h"
#include "raster/float_mode.h"
#include "raster/numeric.h"
#include "raster/softpipe_setup.h"

namespace pem::raster {
namespace {

// The colour of a texture whose texels are all equal (every filter, wrap and LOD returns it:
// softpipe's lerps a + w * (b - a) of equal texels give a); nullopt otherwise.
std::optional<RgbaF> UniformColour(const Texture& t) {
    if (t.levels.empty() || t.levels[0].size() < 4) return std::nullopt;
    const uint8_t* first = t.levels[0].data();
    for (const std::vector<uint8_t>& level : t.levels)
        for (size_t i = 0; i < level.size(); i += 4)
            if (std::memcmp(&level[i], first, 4) != 0) return std::nullopt;
    return RgbaF{FloatFromUnorm8(first[0]), FloatFromUnorm8(first[1]), FloatFromUnorm8(first[2]),
                 FloatFromUnorm8(first[3])};
}

// Whether unit u's coordinates stay where a uniform texture gives its colour at every tap:
// finite and small enough that softpipe's integer texel addresses do not overflow (2D repeat
// wraps a texel index i by (i + 1024 size) % size, which leaves the texture below -1024 size,
// and a tap outside returns the border colour), so every weight is finite.
bool CoordinatesInRange(const Pass& pass, int u, const Texture& t) {
    const float limit = t.kind == TextureKind::Cube ? 0x1p64f
                        : (t.sampler.wrapS == Wrap::Repeat || t.sampler.wrapT == Wrap::Repeat)
                            ? 1000.0f
                            : 0x1p30f;
    const int dims = t.kind == TextureKind::Cube ? 3 : 2;
    for (const Vertex& v : pass.vertices)
        for (int k = 0; k < dims; ++k)
            if (!(std::fabs(v.coord[static_cast<size_t>(u)][k]) < limit)) return false;
    return true;
}

}  // namespace

std::optional<std::string> SoftpipeUnsupported(const Frame& frame) {
    if (frame.depth) return "depth buffers are not modelled yet";
    for (size_t i = 0; i < frame.textures.size(); ++i) {
        const Texture& t = frame.textures[i];
        if (!UniformColour(t) || t.sampler.maxAnisotropy > 1.0f)
            return "texture " + std::to_string(i) +
                   ": sampling is modelled only for textures whose texels are all equal, without "
                   "anisotropy (softpipe's sampler is not modelled yet)";
    }
    for (size_t p = 0; p < frame.passes.size(); ++p) {
        const Pass& pass = frame.passes[p];
        for (int u = 0; u < pass.numUnits; ++u)
            if (!CoordinatesInRange(pass, u, frame.textures[static_cast<size_t>(pass.texture[u])]))
                return "pass " + std::to_string(p) + ", unit " + std::to_string(u) +
                       ": texture coordinates not finite or beyond the modelled range";
    }
    return std::nullopt;
}

namespace {

// CLAMP(x, 0, 1) as the C macro evaluates it: a NaN stays NaN.
float Clamp01(float x) {
    return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x);
}

// The window triangles of triangle t of a pass (the draw module without LLVM).
void WindowTriangles(const Frame& frame, const Pass& pass, int t,
                     std::vector<WindowTriangle>* out) {
    const int numAttribs = PassColourAttrib(pass) + 4;
    ClipVertex v[3];
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
        v[k] = PassClipVertex(pass, PassIndex(pass, static_cast<size_t>(3 * t + k)));
        inside = inside && InsideViewVolume(v[k].pos, frame.depthClamp, ViewportForm::Plain);
    }
    out->clear();
    if (inside) {
        WindowTriangle w;
        for (int k = 0; k < 3; ++k)
            w[static_cast<size_t>(k)] =
                ToWindow(v[k], numAttribs, frame.width, frame.height, ViewportForm::Plain);
        out->push_back(w);
        return;
    }
    ClipTriangle(v[0], v[1], v[2], numAttribs, frame.depthClamp, frame.width, frame.height,
                 ViewportForm::Plain, out);
}

// The float colour buffer (rows bottom-up: raster y) and what a pass draws into it.
struct Target {
    int width, height;
    std::vector<float> colour;  // 4 per pixel
};

// One quad: interpolation at its four pixels, the fragment colour, blending of covered pixels.
void ShadeQuad(const SpTriangle& t, const Pass& pass, const std::vector<RgbaF>& texColour, int x,
               int y, unsigned mask, Target* target) {
    const float fx = static_cast<float>(x), fy = static_cast<float>(y);
    auto corner = [&](const Plane& p) { return p.a0 + p.dadx * fx + p.dady * fy; };
    auto atPixel = [](const Plane& p, float a, int j) {
        return j == 0 ? a : j == 1 ? a + p.dadx : j == 2 ? a + p.dady : a + p.dadx + p.dady;
    };
    const float w0 = corner(t.oow);
    const int co = PassColourAttrib(pass);
    float colourCorner[4];
    for (int c = 0; c < 4; ++c) colourCorner[c] = corner(t.attr[static_cast<size_t>(co + c)]);
    for (int j = 0; j < 4; ++j) {
        if (!(mask & (1u << j))) continue;
        const float w = atPixel(t.oow, w0, j);
        // Step 1: the fragment colour, texture(u0) * texture(u1) * colour, left to right.
        RgbaF src;
        for (int c = 0; c < 4; ++c) {
            const float v = atPixel(t.attr[static_cast<size_t>(co + c)], colourCorner[c], j) / w;
            float f = pass.numUnits > 0 ? texColour[static_cast<size_t>(pass.texture[0])][c] : v;
            if (pass.numUnits > 1) f = f * texColour[static_cast<size_t>(pass.texture[1])][c];
            if (pass.numUnits > 0) f = f * v;
            src[static_cast<size_t>(c)] = f;
        }
        // Step 2: unblended, the colour is stored as it is (GL core: no fragment colour clamp);
        // blended, it is clamped, blended against the float tile and clamped again.
        const size_t px = 4 * (static_cast<size_t>(y + (j >> 1)) * target->width +
                               static_cast<size_t>(x + (j & 1)));
        float* dst = &target->colour[px];
        RgbaF out = src;
        if (pass.blend.enabled) {
            for (float& v : src) v = Clamp01(v);
            out = BlendF(pass.blend, src, {dst[0], dst[1], dst[2], dst[3]});
            for (float& v : out) v = Clamp01(v);
        }
        std::copy(out.begin(), out.end(), dst);
    }
}

void DrawPass(const Frame& frame, const Pass& pass, const std::vector<RgbaF>& texColour,
              Target* target) {
    const int numAttribs = PassColourAttrib(pass) + 4;
    std::vector<WindowTriangle> windows;
    SpTriangle setup;
    for (int t = 0; t < pass.NumTriangles(); ++t) {
        WindowTriangles(frame, pass, t, &windows);
        for (const WindowTriangle& w : windows) {
            if (!SetupSoftpipeTriangle(w[0], w[1], w[2], numAttribs, &setup)) continue;
            ScanSoftpipeTriangle(setup, frame.width, frame.height,
                                 [&](int x, int y, unsigned mask) {
                                     ShadeQuad(setup, pass, texColour, x, y, mask, target);
                                 });
        }
    }
}

}  // namespace

uint8_t SoftpipeUbyte(float x) {
    if (!(x > 0.0f)) return 0;
    if (x >= 1.0f) return 255;
    const float biased = x * (255.0f / 256.0f) + 32768.0f;
    return static_cast<uint8_t>(FloatBits(biased) & 255u);
}

RenderResult RenderSoftpipe(const PreparedFrame& prepared) {
    const Frame& frame = prepared.frame();
    if (const std::optional<std::string> why = SoftpipeUnsupported(frame))
        throw std::invalid_argument("softpipe profile: " + *why);
    std::vector<RgbaF> texColour;
    for (const Texture& t : frame.textures) texColour.push_back(*UniformColour(t));
    ScopedFlushToZero ftz;  // draw_vbo: the whole draw, setup to blending
    // Step 1: the tile cache cleared to glClearColor(c / 255.0f).
    const size_t n = static_cast<size_t>(frame.width) * static_cast<size_t>(frame.height);
    Target target{frame.width, frame.height, std::vector<float>(4 * n)};
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < 4; ++c)
            target.colour[4 * i + c] = static_cast<float>(frame.clear[c]) / 255.0f;
    // Step 2: the passes in order.
    for (const Pass& pass : frame.passes) DrawPass(frame, pass, texColour, &target);
    // Step 3: packed to RGBA8, rows flipped to top-down.
    RenderResult r;
    r.image8 = {frame.width, frame.height, std::vector<uint8_t>(4 * n)};
    const auto w = static_cast<size_t>(frame.width);
    for (size_t row = 0; row < static_cast<size_t>(frame.height); ++row) {
        const size_t src = 4 * row * w, dst = 4 * (static_cast<size_t>(frame.height) - 1 - row) * w;
        for (size_t i = 0; i < 4 * w; ++i)
            r.image8.rgba[dst + i] = SoftpipeUbyte(target.colour[src + i]);
    }
    return r;
}

}  // namespace pem::raster
