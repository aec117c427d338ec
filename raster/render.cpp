// SPDX-License-Identifier: MIT
// render.cpp — the frame loop: vertex processing, triangle setup, the quad loop over row bands
// (one band set per thread), shading (texture units times colour), conversion and blending.
// The same loop either writes pixels or collects the rows of the rendering matrix.
#include "raster/render.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "raster/blend.h"
#include "raster/clip.h"
#include "raster/float_mode.h"
#include "raster/numeric.h"
#include "raster/sampler.h"
#include "raster/triangle_setup.h"

namespace pem::raster {
namespace {

constexpr int kBandQuadRows = 4;  // rows of 2x2 quads per band (8 pixel rows)

int ColourOffset(const Pass& pass) { return 3 * pass.numUnits; }

// Vertex fetch, clipping, viewport transform and triangle setup of one pass.
std::vector<TriangleSetup> SetupPass(const Frame& frame, const Pass& pass) {
    const int numAttribs = ColourOffset(pass) + 4;
    auto fetch = [&](uint32_t index) {
        const Vertex& v = pass.vertices[index];
        ClipVertex cv{v.pos, {}};
        for (int u = 0; u < pass.numUnits; ++u)
            for (int k = 0; k < 3; ++k) cv.attr[static_cast<size_t>(3 * u + k)] = v.coord[u][k];
        for (int k = 0; k < 4; ++k) cv.attr[static_cast<size_t>(ColourOffset(pass) + k)] = v.color[k];
        return cv;
    };
    std::vector<TriangleSetup> setups;
    std::vector<WindowTriangle> clipped;
    for (int t = 0; t < pass.NumTriangles(); ++t) {
        uint32_t idx[3];
        for (int k = 0; k < 3; ++k)
            idx[k] = pass.indices.empty() ? static_cast<uint32_t>(3 * t + k)
                                          : pass.indices[static_cast<size_t>(3 * t + k)];
        clipped.clear();
        ClipTriangle(fetch(idx[0]), fetch(idx[1]), fetch(idx[2]), numAttribs, frame.depthClamp,
                     frame.width, frame.height, &clipped);
        for (const WindowTriangle& w : clipped) {
            TriangleSetup s;
            if (SetupTriangle(w[0], w[1], w[2], numAttribs, frame.width, frame.height, &s))
                setups.push_back(s);
        }
    }
    return setups;
}

// Per-lane attribute values of a 4x2 lane group (sampler.h's lane order): the interpolated
// 1/w, one true division, and each attribute times it.
struct LaneAttribs {
    std::array<std::array<float, kMaxAttribs>, kLanes> a;
};

constexpr int kLaneDx[kLanes] = {0, 1, 0, 1, 2, 3, 2, 3};
constexpr int kLaneDy[kLanes] = {0, 0, 1, 1, 0, 0, 1, 1};

LaneAttribs InterpolateLanes(const TriangleSetup& t, int gx, int gy) {
    LaneAttribs q;
    for (int l = 0; l < kLanes; ++l) {
        const float x = static_cast<float>(gx + kLaneDx[l]);
        const float y = static_cast<float>(gy + kLaneDy[l]);
        const float oow = 1.0f / EvalPlane(t.oow, x, y);
        for (int k = 0; k < t.numAttribs; ++k) q.a[l][k] = EvalPlane(t.attr[k], x, y) * oow;
    }
    return q;
}

// Everything a band worker needs about the frame being drawn.
struct Target {
    const PreparedFrame* frame;
    RenderOptions options;
    Image8* image8;
    ImageF* imageF;             // linear profile
    RenderingMatrix* matrix;    // matrix mode: rows collected per pixel
    std::vector<std::vector<std::pair<uint32_t, double>>>* rows;
};

uint8_t ToUnorm(float v, UnormRounding r) {
    return r == UnormRounding::HalfEven ? UnormFromFloatRne(v) : UnormFromFloatHalfUp(v);
}

// Shades the covered lanes of one 4x2 group of one triangle and writes them.
void ShadeGroup(const Target& tg, const Pass& pass, const TriangleSetup& t, int gx, int gy,
                unsigned mask) {
    const Frame& frame = tg.frame->frame();
    const LaneAttribs qa = InterpolateLanes(t, gx, gy);
    const bool wantTaps = tg.rows != nullptr;

    // Texture units.
    std::array<std::array<RgbaF, kLanes>, kMaxUnits> tex{};
    std::array<PixelTaps, kLanes> taps;
    for (int u = 0; u < pass.numUnits; ++u) {
        LaneCoords lc;
        for (int l = 0; l < kLanes; ++l)
            for (int k = 0; k < 3; ++k) lc.c[l][k] = qa.a[l][static_cast<size_t>(3 * u + k)];
        SampleLanes(*tg.frame, pass.texture[u], tg.options, lc, &tex[u],
                    wantTaps && u == 0 ? &taps : nullptr);
    }

    const int co = ColourOffset(pass);
    const bool linear = tg.options.profile == Profile::Linear;
    for (int l = 0; l < kLanes; ++l) {
        if (!(mask & (1u << l))) continue;
        const int x = gx + kLaneDx[l], y = gy + kLaneDy[l];
        const size_t pixel = static_cast<size_t>(frame.height - 1 - y) * frame.width + x;

        // Fragment colour: texture(u0) * texture(u1) * colour, left to right.
        RgbaF src, mod;
        for (int c = 0; c < 4; ++c) {
            const float col = qa.a[l][static_cast<size_t>(co + c)];
            float m = col;  // what multiplies unit 0's sample
            float v = col;
            if (pass.numUnits == 1) v = tex[0][l][c] * col;
            if (pass.numUnits == 2) {
                v = (tex[0][l][c] * tex[1][l][c]) * col;
                m = tex[1][l][c] * col;
            }
            src[c] = v;
            mod[c] = m;
        }

        if (wantTaps) {
            // Matrix rows: blend none replaces, add accumulates (checked by the caller).
            for (int c = 0; c < 4; ++c) {
                auto& row = (*tg.rows)[4 * pixel + static_cast<size_t>(c)];
                double& off = tg.matrix->offset[4 * pixel + static_cast<size_t>(c)];
                if (!pass.blend.enabled) { row.clear(); off = 0.0; }
                if (pass.numUnits == 0) { off += static_cast<double>(src[c]); continue; }
                for (int k = 0; k < taps[l].count; ++k)
                    row.push_back({4 * taps[l].tap[k].texel + static_cast<uint32_t>(c),
                                   static_cast<double>(taps[l].tap[k].weight) * static_cast<double>(mod[c])});
            }
            continue;
        }
        if (linear) {
            float* d = &tg.imageF->rgba[4 * pixel];
            const RgbaF out = BlendF(pass.blend, src, {d[0], d[1], d[2], d[3]});
            for (int c = 0; c < 4; ++c) d[c] = out[c];
        } else {
            uint8_t* d = &tg.image8->rgba[4 * pixel];
            const UnormRounding r = tg.options.rounding;
            const Rgba8 s8{ToUnorm(src[0], r), ToUnorm(src[1], r), ToUnorm(src[2], r),
                           ToUnorm(src[3], r)};
            const Rgba8 out = Blend8(pass.blend, s8, {d[0], d[1], d[2], d[3]});
            for (int c = 0; c < 4; ++c) d[c] = out[c];
        }
    }
}

// Draws the 4x2 lane groups of one triangle that lie in the bands owned by `worker`. A group
// is shaded when at least one of its pixels is covered (llvmpipe skips empty 8-lane vectors).
void DrawTriangle(const Target& tg, const Pass& pass, const TriangleSetup& t, int worker,
                  int workers) {
    const int gy0 = t.y0 & ~1, gx0 = t.x0 & ~3;
    for (int gy = gy0; gy <= t.y1; gy += 2) {
        if ((gy / 2 / kBandQuadRows) % workers != worker) continue;
        for (int gx = gx0; gx <= t.x1; gx += 4) {
            unsigned mask = 0;
            for (int l = 0; l < kLanes; ++l) {
                const int x = gx + kLaneDx[l], y = gy + kLaneDy[l];
                if (x >= t.x0 && x <= t.x1 && y >= t.y0 && y <= t.y1 && Inside(t, x, y))
                    mask |= 1u << l;
            }
            if (mask) ShadeGroup(tg, pass, t, gx, gy, mask);
        }
    }
}

void DrawFrame(const Target& tg) {
    // llvmpipe runs both the draw/setup stage and its rasterizer threads with denormals flushed
    // (MXCSR DAZ|FTZ); the Linear profile uses plain IEEE arithmetic.
    const bool ftz = tg.options.profile == Profile::Llvmpipe;
    const Frame& frame = tg.frame->frame();
    const int workers = std::max(1, tg.options.threads);
    for (const Pass& pass : frame.passes) {
        std::vector<TriangleSetup> setups;
        if (ftz) {
            ScopedFlushToZero guard;
            setups = SetupPass(frame, pass);
        } else {
            setups = SetupPass(frame, pass);
        }
        auto work = [&](int w) {
            if (ftz) {
                ScopedFlushToZero guard;
                for (const TriangleSetup& t : setups) DrawTriangle(tg, pass, t, w, workers);
            } else {
                for (const TriangleSetup& t : setups) DrawTriangle(tg, pass, t, w, workers);
            }
        };
        if (workers == 1) {
            work(0);
        } else {
            std::vector<std::thread> pool;
            for (int w = 1; w < workers; ++w) pool.emplace_back(work, w);
            work(0);
            for (std::thread& th : pool) th.join();
        }
    }
}

std::vector<float> ToFloat(const std::vector<uint8_t>& bytes, bool exact) {
    std::vector<float> f(bytes.size());
    for (size_t i = 0; i < bytes.size(); ++i)
        f[i] = exact ? static_cast<float>(bytes[i]) / 255.0f : FloatFromUnorm8(bytes[i]);
    return f;
}

}  // namespace

PreparedFrame::PreparedFrame(const Frame& frame) : frame_(&frame), indexer_(frame.textures) {
    for (const Texture& t : frame.textures) {
        PreparedTexture p;
        p.source = &t;
        for (const auto& level : t.levels) {
            p.levelsF.push_back(ToFloat(level, false));
            p.levelsExact.push_back(ToFloat(level, true));
        }
        textures_.push_back(std::move(p));
    }
}

RenderResult Render(const PreparedFrame& prepared, const RenderOptions& options) {
    const Frame& frame = prepared.frame();
    const size_t n = static_cast<size_t>(frame.width) * frame.height;
    RenderResult r;
    r.image8 = {frame.width, frame.height, std::vector<uint8_t>(4 * n)};
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 4; ++c) r.image8.rgba[4 * i + c] = frame.clear[c];
    if (options.profile == Profile::Linear) {
        r.imageF = {frame.width, frame.height, std::vector<float>(4 * n)};
        for (size_t i = 0; i < 4 * n; ++i) r.imageF.rgba[i] = static_cast<float>(r.image8.rgba[i]) / 255.0f;
    }
    DrawFrame({&prepared, options, &r.image8, &r.imageF, nullptr, nullptr});
    if (options.profile == Profile::Linear)
        for (size_t i = 0; i < 4 * n; ++i) r.image8.rgba[i] = ToUnorm(r.imageF.rgba[i], options.rounding);
    return r;
}

RenderingMatrix BuildRenderingMatrix(const PreparedFrame& prepared, const RenderOptions& options) {
    const Frame& frame = prepared.frame();
    for (size_t i = 0; i < frame.passes.size(); ++i) {
        const Pass& p = frame.passes[i];
        const bool ok = !p.blend.enabled || (p.numUnits == 0 && BlendIsDstAffine(p.blend)) ||
                        p.blend == BlendState::Additive();
        if (!ok || (p.numUnits == 0 && p.blend.enabled && !(p.blend == BlendState::Additive())))
            throw std::invalid_argument("pass " + std::to_string(i) +
                                        ": blend is not linear in the texels (use none or add)");
    }
    const size_t n = static_cast<size_t>(frame.width) * frame.height;
    RenderingMatrix m;
    m.rows = static_cast<int64_t>(4 * n);
    m.cols = 4 * static_cast<int64_t>(prepared.indexer().TotalTexels());
    m.offset.assign(4 * n, 0.0);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 4; ++c) m.offset[4 * i + c] = frame.clear[c] / 255.0;
    std::vector<std::vector<std::pair<uint32_t, double>>> rows(4 * n);
    DrawFrame({&prepared, options, nullptr, nullptr, &m, &rows});

    // Merge duplicate columns per row (sorted), then CSR.
    m.rowPtr.push_back(0);
    for (auto& row : rows) {
        std::sort(row.begin(), row.end(),
                  [](const auto& a, const auto& b) { return a.first < b.first; });
        for (size_t k = 0; k < row.size(); ++k) {
            if (!m.col.empty() && static_cast<int64_t>(m.col.size()) > m.rowPtr.back() &&
                m.col.back() == row[k].first) {
                m.val.back() += row[k].second;
                continue;
            }
            m.col.push_back(row[k].first);
            m.val.push_back(row[k].second);
        }
        m.rowPtr.push_back(static_cast<int64_t>(m.col.size()));
    }
    const RenderResult r = Render(prepared, options);
    m.rendered.resize(4 * n);
    for (size_t i = 0; i < 4 * n; ++i)
        m.rendered[i] = options.profile == Profile::Linear ? static_cast<double>(r.imageF.rgba[i])
                                                           : r.image8.rgba[i] / 255.0;
    return m;
}

}  // namespace pem::raster
