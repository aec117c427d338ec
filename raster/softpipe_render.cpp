// SPDX-License-Identifier: MIT
// softpipe_render.cpp — softpipe's pipeline per pass (softpipe_render.h): vertices, setup, quads,
// shading, blending into the float colour tile, and the final packing.
#include "raster/softpipe_render.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include "raster/blend.h"
#include "raster/clip.h"
#include "raster/depth.h"
#include "raster/float_mode.h"
#include "raster/matrix_rows.h"
#include "raster/numeric.h"
#include "raster/softpipe_sampler.h"
#include "raster/softpipe_setup.h"

namespace pem::raster {
namespace {

// CLAMP(x, 0, 1) as Mesa's macro evaluates it: x > 0 ? (x > 1 ? 1 : x) : 0 (a NaN gives 0).
float Clamp01(float x) {
    return x > 0.0f ? (x > 1.0f ? 1.0f : x) : 0.0f;
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

// The float colour buffer and the depth buffer (rows bottom-up: raster y) a pass draws into.
struct Target {
    int width, height;
    std::vector<float> colour;    // 4 per pixel
    int depthStride = 0;          // even width: a quad's pixels always have a word
    std::vector<uint32_t> depth;  // the depth tile's words (Z16, Z24X8 or Z32F bits); empty: none
    // Matrix mode (BuildRenderingMatrix): the rows of A as the frame is drawn.
    RenderingMatrix* matrix = nullptr;
    MatrixRows* rows = nullptr;
    SoftpipeBudget budget;
};

// C's (unsigned) and (ushort) casts of a float as gcc compiles them for x86-64: cvttss2si to
// 64 bits (unsigned) or 32 bits (ushort), then the low bits; NaN and out of range give
// 0x8000...0, whose low bits are 0.
uint32_t CastUnsigned(float v) {
    if (!(std::fabs(v) < 0x1p63f)) return 0;
    return static_cast<uint32_t>(static_cast<uint64_t>(static_cast<int64_t>(v)));
}
uint16_t CastUshort(float v) {
    return static_cast<uint16_t>(static_cast<uint32_t>(TruncI32(v)));
}

// The quad's four depths from the z plane (interpolate_quad_depth).
std::array<float, 4> QuadDepth(const Plane& z, int x, int y) {
    const float z0 = z.a0 + z.dadx * static_cast<float>(x) + z.dady * static_cast<float>(y);
    return {z0, z0 + z.dadx, z0 + z.dady, z0 + z.dadx + z.dady};
}

// Where a pass's depth stage stands within the current 16-pixel chunk of quads: softpipe's Z16
// write path steps every quad's depth from the chunk's first quad.
struct DepthBatch {
    int y = -1, chunk = -1;  // the chunk's row pair and x / 16
    int x0 = 0;              // its first quad's x
    std::array<uint16_t, 4> first{};
    uint16_t step = 0;
};

// The Z16 write path (sp_quad_depth_test_tmp.h): the chunk's first quad's depths scaled by
// 65535 and cast to ushort, later quads stepped by (ushort)(dzdx * 65535) per pixel in 16-bit
// arithmetic; a passing pixel writes its depth.
unsigned DepthZ16Write(const SpTriangle& t, DepthFunc func, int x, int y, unsigned mask,
                       DepthBatch* batch, Target* target) {
    if (y != batch->y || (x >> 4) != batch->chunk) {
        const std::array<float, 4> z = QuadDepth(t.z, x, y);
        *batch = {y, x >> 4, x, {}, CastUshort(t.z.dadx * 65535.0f)};
        for (size_t j = 0; j < 4; ++j) batch->first[j] = CastUshort(z[j] * 65535.0f);
    }
    unsigned out = 0;
    for (int j = 0; j < 4; ++j) {
        if (!(mask & (1u << j))) continue;
        const auto v = static_cast<uint16_t>(batch->first[static_cast<size_t>(j)] +
                                             (x - batch->x0) * batch->step);
        uint32_t& stored = target->depth[static_cast<size_t>(y + (j >> 1)) *
                                             static_cast<size_t>(target->depthStride) +
                                         static_cast<size_t>(x + (j & 1))];
        if (CompareDepth(func, static_cast<int>(v), static_cast<int>(stored))) {
            stored = v;
            out |= 1u << j;
        }
    }
    return out;
}

// depth_test_quads_fallback: the quad's depths (clamped to [0, 1] under GL_DEPTH_CLAMP),
// converted as (unsigned)(z * 65535.0f) / (unsigned)(z * 16777215.0f) / the float's bits,
// compared with the stored value (Z24X8: its low 24 bits; Z32F: as floats), written where the
// fragment passes and the mask allows.
unsigned DepthFallback(const SpTriangle& t, DepthFormat format, const DepthTest& test, bool clamp,
                       int x, int y, unsigned mask, Target* target) {
    std::array<float, 4> z = QuadDepth(t.z, x, y);
    if (clamp)
        for (float& v : z) v = Clamp01(v);
    unsigned out = 0;
    for (int j = 0; j < 4; ++j) {
        if (!(mask & (1u << j))) continue;
        const float d = z[static_cast<size_t>(j)];
        uint32_t& word = target->depth[static_cast<size_t>(y + (j >> 1)) *
                                           static_cast<size_t>(target->depthStride) +
                                       static_cast<size_t>(x + (j & 1))];
        bool pass;
        uint32_t q;
        if (format == DepthFormat::Z32F) {
            q = FloatBits(d);
            pass = CompareDepth(test.func, d, BitsFloat(word));
        } else {
            q = CastUnsigned(format == DepthFormat::Z16 ? d * 65535.0f : d * 16777215.0f);
            const uint32_t stored = format == DepthFormat::Z16 ? word : word & 0xFFFFFFu;
            pass = CompareDepth(test.func, q, stored);
        }
        if (!pass) continue;
        out |= 1u << j;
        if (test.write) word = format == DepthFormat::Z16 ? (q & 0xFFFFu) : q;
    }
    return out;
}

// Matrix mode: pixel (x, y)'s rows (matrix_rows.h), unit 0's texels times what multiplies them.
void AddRows(const PreparedFrame& prepared, const Pass& pass, int x, int y,
             const std::vector<SoftpipeTap>& taps, const RgbaF& colour, const RgbaF& mod,
             Target* target) {
    const Frame& frame = prepared.frame();
    const size_t pixel =
        static_cast<size_t>(frame.height - 1 - y) * static_cast<size_t>(frame.width) +
        static_cast<size_t>(x);
    AddFragmentRows(
        target->matrix, target->rows, pixel, y, pass, colour, [&](MatrixRows::Appender& row) {
            for (const SoftpipeTap& t : taps)
                row.Add(prepared.indexer().Index(pass.texture[0], t.level, t.face, t.x, t.y),
                        t.weight, mod);
        });
}

// One quad: interpolation at its four pixels, the texture units (one LOD per quad), the
// fragment colour, blending of the covered pixels.
void ShadeQuad(const SpTriangle& t, const PreparedFrame& prepared, const Pass& pass, int x, int y,
               unsigned mask, Target* target) {
    const float fx = static_cast<float>(x), fy = static_cast<float>(y);
    // Step 1: the attributes at the four pixels (eval_perspective_coef).
    auto atPixels = [&](const Plane& p) {
        const float a = p.a0 + p.dadx * fx + p.dady * fy;
        return std::array<float, 4>{a, a + p.dadx, a + p.dady, a + p.dadx + p.dady};
    };
    const std::array<float, 4> w = atPixels(t.oow);
    std::array<std::array<float, 4>, kMaxAttribs> attr;
    for (int k = 0; k < t.numAttribs; ++k) {
        const std::array<float, 4> a = atPixels(t.attr[static_cast<size_t>(k)]);
        for (size_t j = 0; j < 4; ++j) attr[static_cast<size_t>(k)][j] = a[j] / w[j];
    }
    // Step 2: the texture units, texture(u0) * texture(u1) * colour, left to right (matrix
    // mode: unit 0's texels too).
    std::array<RgbaF, 4> colour, sample, mod;  // mod: what multiplies unit 0 (matrix mode)
    std::array<std::vector<SoftpipeTap>, 4> taps;
    const auto co = static_cast<size_t>(PassColourAttrib(pass));
    for (size_t j = 0; j < 4; ++j)
        for (size_t c = 0; c < 4; ++c) colour[j][c] = attr[co + c][j];
    for (int u = 0; u < pass.numUnits; ++u) {
        const auto k = static_cast<size_t>(3 * u);
        SampleSoftpipeQuad(prepared.texture(pass.texture[static_cast<size_t>(u)]),
                           {attr[k], attr[k + 1], attr[k + 2]}, &sample, &target->budget,
                           target->rows && u == 0 ? &taps : nullptr);
        for (size_t j = 0; j < 4; ++j)
            for (size_t c = 0; c < 4; ++c) {
                colour[j][c] = u == 0 ? sample[j][c] : colour[j][c] * sample[j][c];
                mod[j][c] = (u == 1 ? sample[j][c] : 1.0f) * attr[co + c][j];
            }
    }
    if (pass.numUnits > 0)
        for (size_t j = 0; j < 4; ++j)
            for (size_t c = 0; c < 4; ++c) colour[j][c] = colour[j][c] * attr[co + c][j];
    if (target->rows) {
        for (int j = 0; j < 4; ++j)
            if (mask & (1u << j))
                AddRows(prepared, pass, x + (j & 1), y + (j >> 1), taps[static_cast<size_t>(j)],
                        colour[static_cast<size_t>(j)], mod[static_cast<size_t>(j)], target);
        return;
    }
    // Step 3: unblended, the colour is stored as it is (GL core: no fragment colour clamp);
    // blended, it is clamped, blended against the float tile and clamped again.
    for (int j = 0; j < 4; ++j) {
        if (!(mask & (1u << j))) continue;
        const size_t px = 4 * (static_cast<size_t>(y + (j >> 1)) * target->width +
                               static_cast<size_t>(x + (j & 1)));
        float* dst = &target->colour[px];
        RgbaF out = colour[static_cast<size_t>(j)];
        if (pass.blend.enabled) {
            for (float& v : out) v = Clamp01(v);
            out = BlendF(pass.blend, out, {dst[0], dst[1], dst[2], dst[3]});
            for (float& v : out) v = Clamp01(v);
        }
        std::copy(out.begin(), out.end(), dst);
    }
}

void DrawPass(const PreparedFrame& prepared, const Pass& pass, Target* target) {
    const Frame& frame = prepared.frame();
    const int numAttribs = PassColourAttrib(pass) + 4;
    std::vector<WindowTriangle> windows;
    SpTriangle setup;
    // The depth stage (choose_depth_test): none, the Z16 write path or the general one.
    std::function<unsigned(const SpTriangle&, int, int, unsigned, DepthBatch*)> depth;
    if (frame.depth && pass.depthTest) {
        const DepthFormat format = frame.depth->format;
        const DepthTest test = *pass.depthTest;
        const bool clamp = frame.depthClamp;
        if (format == DepthFormat::Z16 && test.write && !clamp && test.func != DepthFunc::Never)
            depth = [=](const SpTriangle& t, int x, int y, unsigned m, DepthBatch* b) {
                return DepthZ16Write(t, test.func, x, y, m, b, target);
            };
        else
            depth = [=](const SpTriangle& t, int x, int y, unsigned m, DepthBatch*) {
                return DepthFallback(t, format, test, clamp, x, y, m, target);
            };
    }
    for (int t = 0; t < pass.NumTriangles(); ++t) {
        WindowTriangles(frame, pass, t, &windows);
        for (const WindowTriangle& w : windows) {
            if (!SetupSoftpipeTriangle(w[0], w[1], w[2], numAttribs, &setup)) continue;
            DepthBatch batch;
            ScanSoftpipeTriangle(setup, frame.width, frame.height,
                                 [&](int x, int y, unsigned mask) {
                                     if (depth) mask = depth(setup, x, y, mask, &batch);
                                     if (mask) ShadeQuad(setup, prepared, pass, x, y, mask, target);
                                 });
        }
    }
}

// The cleared buffers (the tile caches cleared to glClearColor(c / 255.0f) and util_pack_z's
// depth), then the passes in order, with denormals flushed (draw_vbo).
Target DrawFrame(const PreparedFrame& prepared, RenderingMatrix* matrix, MatrixRows* rows) {
    const Frame& frame = prepared.frame();
    ScopedFlushToZero ftz;
    const size_t n = static_cast<size_t>(frame.width) * static_cast<size_t>(frame.height);
    Target target{frame.width, frame.height, std::vector<float>(4 * n), 0, {}, matrix, rows, {}};
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < 4; ++c)
            target.colour[4 * i + c] = static_cast<float>(frame.clear[c]) / 255.0f;
    if (frame.depth) {
        target.depthStride = (frame.width + 1) & ~1;
        target.depth.assign(
            static_cast<size_t>(target.depthStride) * static_cast<size_t>((frame.height + 1) & ~1),
            DepthClearValue(frame.depth->format, frame.depth->clear));
    }
    for (const Pass& pass : frame.passes) DrawPass(prepared, pass, &target);
    return target;
}

}  // namespace

uint8_t SoftpipeUbyte(float x) {
    if (!(x > 0.0f)) return 0;
    if (x >= 1.0f) return 255;
    const float biased = x * (255.0f / 256.0f) + 32768.0f;
    return static_cast<uint8_t>(FloatBits(biased) & 255u);
}

void SoftpipeMatrixRows(const PreparedFrame& frame, RenderingMatrix* matrix, MatrixRows* rows) {
    DrawFrame(frame, matrix, rows);
}

RenderResult RenderSoftpipe(const PreparedFrame& prepared) {
    const Frame& frame = prepared.frame();
    const Target target = DrawFrame(prepared, nullptr, nullptr);
    const size_t n = static_cast<size_t>(frame.width) * static_cast<size_t>(frame.height);
    // Step 3: packed to RGBA8, rows flipped to top-down.
    RenderResult r;
    r.image8 = {frame.width, frame.height, std::vector<uint8_t>(4 * n)};
    const auto w = static_cast<size_t>(frame.width);
    for (size_t row = 0; row < static_cast<size_t>(frame.height); ++row) {
        const size_t src = 4 * row * w, dst = 4 * (static_cast<size_t>(frame.height) - 1 - row) * w;
        for (size_t i = 0; i < 4 * w; ++i)
            r.image8.rgba[dst + i] = SoftpipeUbyte(target.colour[src + i]);
    }
    if (frame.depth) {  // rows top-down; Z24X8 reads back its low 24 bits
        const uint32_t keep = frame.depth->format == DepthFormat::Z24 ? 0xFFFFFFu : 0xFFFFFFFFu;
        r.depth.resize(n);
        for (size_t row = 0; row < static_cast<size_t>(frame.height); ++row)
            for (size_t x = 0; x < w; ++x)
                r.depth[(static_cast<size_t>(frame.height) - 1 - row) * w + x] =
                    target.depth[row * static_cast<size_t>(target.depthStride) + x] & keep;
    }
    return r;
}

}  // namespace pem::raster
