// SPDX-License-Identifier: MIT
// render.cpp — the frame loop: vertex processing (once per referenced vertex), triangle setup in
// batches (contiguous chunks per thread), the quad loop over row bands (one band set per
// thread), the depth test, shading (texture units times colour), conversion and blending. Batches
// keep the setups small; a pass shared by several frames (RenderFrames) is set up once per batch
// and drawn into each. The same loop writes pixels and, in matrix mode, collects the rows of the
// rendering matrix as well.
#include "raster/render.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "base/parallel.h"
#include "base/worker_pool.h"
#include "raster/blend.h"
#include "raster/clip.h"
#include "raster/depth.h"
#include "raster/float_mode.h"
#include "raster/fragment.h"
#include "raster/numeric.h"
#include "raster/softpipe_render.h"
#include "raster/triangle_setup.h"

namespace pem::raster {
namespace {

// Per vertex of a pass: inside the view volume (then its window vertex is ready), outside, or
// not referenced.
enum class VertexState : uint8_t { Unused, Inside, Outside };

// The state (shared by the variants: the same positions) and each variant's window vertices,
// allocated without zeroing (only the Inside vertices are written and read; zeroing 64 bytes
// per vertex of every variant was 2 % of the benchmark frame).
struct PassVertices {
    std::vector<VertexState> state;
    std::vector<std::unique_ptr<WindowVertex[]>> window;  // [variant][vertex]
};

// The referenced vertices in [first, last): clip test and, inside, the viewport transform of
// every variant's pass.
void TransformVertices(const Frame& frame, const std::vector<const Pass*>& passes, size_t first,
                       size_t last, PassVertices* pv) {
    const int numAttribs = PassColourAttrib(*passes[0]) + 4;
    for (size_t v = first; v < last; ++v) {
        if (pv->state[v] == VertexState::Unused) continue;
        if (!InsideViewVolume(passes[0]->vertices[v].pos, frame.depthClamp, ViewportForm::Fused)) {
            pv->state[v] = VertexState::Outside;
            continue;
        }
        for (size_t k = 0; k < passes.size(); ++k)
            pv->window[k][v] = ToWindow(PassClipVertex(*passes[k], static_cast<uint32_t>(v)),
                                        numAttribs, frame.width, frame.height, ViewportForm::Fused);
    }
}

// Clipping and triangle setup of triangles [first, last) of one pass geometry, appended to
// each variant's `setups` (setups[k][i] of every k are the same triangle: which triangles are
// drawn, and their coverage, depend on the positions only). Triangles inside the view volume
// take the transformed vertices and are set up once, then given each variant's attribute planes.
void SetupTriangles(const Frame& frame, const std::vector<const Pass*>& passes,
                    const PassVertices& pv, int first, int last,
                    std::vector<std::vector<TriangleSetup>>* setups) {
    const Pass& pass = *passes[0];
    const int numAttribs = PassColourAttrib(pass) + 4;
    const PixelBox drawn = DrawnBox(frame);
    std::vector<WindowTriangle> clipped;
    TriangleSetup s;
    for (int t = first; t < last; ++t) {
        uint32_t idx[3];
        bool inside = true;
        for (int k = 0; k < 3; ++k) {
            idx[k] = PassIndex(pass, static_cast<size_t>(3 * t + k));
            inside = inside && pv.state[idx[k]] == VertexState::Inside;
        }
        // Inside the view volume: set up in place (copying the 264-byte setup cost 3 % of the
        // benchmark frame).
        if (inside) {
            const WindowVertex* w0 = pv.window[0].get();
            TriangleSetup& s0 = (*setups)[0].emplace_back();
            if (!SetupTriangle(w0[idx[0]], w0[idx[1]], w0[idx[2]], numAttribs, drawn, &s0)) {
                (*setups)[0].pop_back();
                continue;
            }
            for (size_t k = 1; k < passes.size(); ++k) {
                const WindowVertex* wk = pv.window[k].get();
                TriangleSetup& sk = (*setups)[k].emplace_back((*setups)[0].back());
                SetupAttributePlanes(wk[idx[0]], wk[idx[1]], wk[idx[2]], numAttribs, &sk);
            }
            continue;
        }
        for (size_t k = 0; k < passes.size(); ++k) {
            const Pass& pk = *passes[k];
            clipped.clear();
            ClipTriangle(PassClipVertex(pk, idx[0]), PassClipVertex(pk, idx[1]),
                         PassClipVertex(pk, idx[2]), numAttribs, frame.depthClamp, frame.width,
                         frame.height, ViewportForm::Fused, &clipped);
            for (const WindowTriangle& w : clipped)
                if (SetupTriangle(w[0], w[1], w[2], numAttribs, drawn, &s))
                    (*setups)[k].push_back(s);
        }
    }
}

// Runs fn(0) .. fn(workers - 1) at once (worker_pool.h), with denormals flushed when `ftz`
// (llvmpipe's draw and rasterizer threads both flush).
template <typename Fn>
void RunWorkers(int workers, bool ftz, const Fn& fn) {
    base::RunOnWorkers(workers, [&](int w) {
        if (ftz) {
            ScopedFlushToZero guard;
            fn(w);
        } else {
            fn(w);
        }
    });
}

// Triangles set up and drawn per batch, so the setups stay small and in cache.
constexpr int kBatchTriangles = 8192;

// One pass geometry drawn into one or more targets. Variants: groups of draws whose passes
// have the same vertices (SameVertices); every variant's pass has the same positions and indices
// (SamePositions) in frames of the same size. Each variant's first pass is set up (clipping,
// setup; coverage once for all variants) and its triangles drawn with each draw's own pass
// state and textures.
void DrawPass(const std::vector<std::vector<PassDraw>>& variants, std::vector<SetupChunk>* chunks,
              PassVertices* pv) {
    const FragmentTarget& tg0 = *variants[0][0].first;
    const Pass& pass = *variants[0][0].second;
    std::vector<const Pass*> passes;
    for (const std::vector<PassDraw>& v : variants) passes.push_back(v[0].second);
    const bool ftz = tg0.options.profile == Profile::Llvmpipe;  // Linear: plain IEEE arithmetic
    const Frame& frame = tg0.frame->frame();
    const DrawBandsFn drawBands = SelectDrawBands();
    const int workers = static_cast<int>(chunks->size());
    // Step 1: mark the referenced vertices.
    const size_t nv = pass.vertices.size();
    const int n = pass.NumTriangles();
    pv->state.assign(nv, pass.indices.empty() ? VertexState::Inside : VertexState::Unused);
    for (uint32_t i : pass.indices) pv->state[i] = VertexState::Inside;
    pv->window.resize(passes.size());
    for (std::unique_ptr<WindowVertex[]>& w : pv->window)
        w = std::make_unique_for_overwrite<WindowVertex[]>(nv);
    base::SpinBarrier sync(workers);
    // A worker whose step throws does no more work but keeps arriving at the barriers, so the
    // others are not left waiting; every worker skips the steps after a failure, and
    // RunOnWorkers rethrows the error once all have returned.
    std::atomic<bool> failed{false};
    RunWorkers(workers, ftz, [&](int w) {
        std::exception_ptr error;
        auto step = [&](const auto& work) {
            if (failed.load()) return;
            try {
                work();
            } catch (...) {
                error = std::current_exception();
                failed = true;
            }
        };
        // Step 2: vertex processing in contiguous ranges.
        step([&] {
            TransformVertices(frame, passes, nv * static_cast<size_t>(w) / workers,
                              nv * static_cast<size_t>(w + 1) / workers, pv);
        });
        sync.ArriveAndWait();
        // Step 3: per batch, setup in contiguous chunks of triangles, then fragments by row bands
        // over the chunks in primitive order.
        SetupChunk& mine = (*chunks)[static_cast<size_t>(w)];
        for (int b0 = 0; b0 < n; b0 += kBatchTriangles) {
            const int nb = std::min(kBatchTriangles, n - b0);
            step([&] {
                mine.resize(passes.size());
                for (std::vector<TriangleSetup>& v : mine) {
                    v.clear();  // about nb / workers setups (clipping may add some)
                    v.reserve(static_cast<size_t>(nb / workers + 1));
                }
                SetupTriangles(frame, passes, *pv, b0 + nb * w / workers,
                               b0 + nb * (w + 1) / workers, &mine);
            });
            sync.ArriveAndWait();
            step([&] {
                for (const SetupChunk& c : *chunks) drawBands(variants, c, w, workers);
            });
            sync.ArriveAndWait();
        }
        if (error) std::rethrow_exception(error);
    });
}

// Whether two passes of equally sized frames give the same triangles at the same places:
// bitwise equal positions, indices and attribute count, the same scissor box.
bool SamePositions(const Frame& fa, const Pass& a, const Frame& fb, const Pass& b) {
    if (fa.width != fb.width || fa.height != fb.height || fa.depthClamp != fb.depthClamp ||
        fa.scissor != fb.scissor || a.numUnits != b.numUnits || a.indices != b.indices ||
        a.vertices.size() != b.vertices.size())
        return false;
    bool same = true;  // no early exit: the loop vectorises
    for (size_t v = 0; v < a.vertices.size(); ++v)
        for (int c = 0; c < 4; ++c)
            same &= std::bit_cast<uint32_t>(a.vertices[v].pos[c]) ==
                    std::bit_cast<uint32_t>(b.vertices[v].pos[c]);
    return same;
}

// Whether two such passes give the same triangle setups: bitwise equal vertices (Vertex is 14
// floats, no padding).
bool SameVertices(const Pass& a, const Pass& b) {
    static_assert(sizeof(Vertex) == 14 * sizeof(float));
    return std::memcmp(a.vertices.data(), b.vertices.data(), a.vertices.size() * sizeof(Vertex)) ==
           0;
}

// Whether two frames keep equal depth buffers fragment by fragment: the same depth buffer, and
// pass by pass the same positions (SamePositions: size, box, clamp), depth test and blending on
// or off, so DrawFrames draws their passes in the same DrawPass calls (fused alike).
bool SameDepthHistory(const Frame& a, const Frame& b) {
    if (!a.depth || a.depth != b.depth || a.passes.size() != b.passes.size()) return false;
    for (size_t p = 0; p < a.passes.size(); ++p)
        if (a.passes[p].depthTest != b.passes[p].depthTest ||
            a.passes[p].blend.enabled != b.passes[p].blend.enabled ||
            !SamePositions(a, a.passes[p], b, b.passes[p]))
            return false;
    return true;
}

// Whether pass p + 1 of a target's frame may be drawn together with pass p, each fragment's
// pass p + 1 right after its pass p (triangle by triangle) instead of after the whole pass p:
// pass p writes depth with LESS and replaces the colour, pass p + 1 tests EQUAL without writing,
// at the same positions. Per pixel, the fragments pass p keeps are those that set a new least
// depth; each replaces whatever came before, so only what follows the first fragment at the
// final depth survives: in both orders that is its pass p colour, then the pass p + 1 draws of
// the fragments at that depth, in primitive order. The bytes are those of drawing the passes
// one after the other. Not in matrix mode (its rows are kept in the two-pass order).
bool FusesWithNext(const FragmentTarget& tg, size_t p) {
    const Frame& frame = tg.frame->frame();
    if (tg.rows || !frame.depth || p + 1 >= frame.passes.size()) return false;
    const Pass& a = frame.passes[p];
    const Pass& b = frame.passes[p + 1];
    return a.depthTest && a.depthTest->func == DepthFunc::Less && a.depthTest->write &&
           !a.blend.enabled && b.depthTest && b.depthTest->func == DepthFunc::Equal &&
           !b.depthTest->write && SamePositions(frame, a, frame, b);
}

// Adds a draw to the variant of passes with its vertices (SameVertices), or to a new one.
void AddDraw(const PassDraw& draw, std::vector<std::vector<PassDraw>>* variants) {
    auto same = std::find_if(variants->begin(), variants->end(), [&](const auto& v) {
        return SameVertices(*v[0].second, *draw.second);
    });
    if (same == variants->end()) {
        variants->emplace_back();
        same = variants->end() - 1;
    }
    same->push_back(draw);
}

// Draws every frame's passes, each framebuffer's in order; pass p of several frames at the same
// positions is set up once (its attribute planes once per distinct set of vertices). A pass
// that fuses with the next (FusesWithNext) takes the next one along as further variants, drawn
// after its own in every lane group.
void DrawFrames(const std::vector<FragmentTarget>& targets) {
    const int workers = std::max(1, targets[0].options.threads);
    PassVertices pv;
    std::vector<SetupChunk> chunks(static_cast<size_t>(workers));
    size_t nPasses = 0;
    for (const FragmentTarget& tg : targets)
        nPasses = std::max(nPasses, tg.frame->frame().passes.size());
    std::vector<size_t> next(targets.size(), 0);  // per target: its first pass not yet drawn
    for (size_t p = 0; p < nPasses; ++p) {
        for (size_t f = 0; f < targets.size(); ++f) {
            const Frame& frame = targets[f].frame->frame();
            if (next[f] > p || p >= frame.passes.size()) continue;
            // Step 1: the targets whose pass p lies where this one's does, by vertices.
            std::vector<std::vector<PassDraw>> variants{{{&targets[f], &frame.passes[p]}}};
            next[f] = p + 1;
            for (size_t g = f + 1; g < targets.size(); ++g) {
                const Frame& other = targets[g].frame->frame();
                if (next[g] > p || p >= other.passes.size() ||
                    !SamePositions(frame, frame.passes[p], other, other.passes[p]))
                    continue;
                AddDraw({&targets[g], &other.passes[p]}, &variants);
                next[g] = p + 1;
            }
            // Step 2: their passes p + 1 drawn along where they fuse.
            std::vector<std::vector<PassDraw>> fused;
            for (const std::vector<PassDraw>& v : variants)
                for (const PassDraw& d : v) {
                    if (!FusesWithNext(*d.first, p)) continue;
                    const size_t t = static_cast<size_t>(d.first - targets.data());
                    AddDraw({d.first, &d.first->frame->frame().passes[p + 1]}, &fused);
                    next[t] = p + 2;
                }
            variants.insert(variants.end(), fused.begin(), fused.end());
            DrawPass(variants, &chunks, &pv);
        }
    }
}

void DrawFrame(const FragmentTarget& tg) {
    DrawFrames({tg});
}

// Pixels in a box.
size_t Pixels(const PixelBox& box) {
    return static_cast<size_t>(box.width) * static_cast<size_t>(box.height);
}

// The frame's depth buffer (its drawn box) cleared into *buffer (nullptr, buffer left empty,
// without one).
std::vector<uint32_t>* ClearedDepth(const Frame& frame, std::vector<uint32_t>* buffer) {
    if (!frame.depth) return nullptr;
    buffer->assign(Pixels(DrawnBox(frame)),
                   DepthClearValue(frame.depth->format, frame.depth->clear));
    return buffer;
}

// A target drawing `frame` into *r: its pictures (and depth buffer) over the drawn box cleared.
FragmentTarget ClearedTarget(const PreparedFrame& prepared, const RenderOptions& options,
                             RenderResult* r, bool ownDepth = true) {
    const Frame& frame = prepared.frame();
    const PixelBox box = DrawnBox(frame);
    const size_t n = Pixels(box);
    const auto& k = frame.clear;
    const bool floats = FloatTarget(frame, options);
    // The 8-bit picture: one pass, a byte fill when the four bytes agree, else 32-bit stores.
    if (!floats || options.picture8) {
        if (k[0] == k[1] && k[1] == k[2] && k[2] == k[3]) {
            r->image8 = {box.width, box.height, std::vector<uint8_t>(4 * n, k[0])};
        } else {
            r->image8 = {box.width, box.height, std::vector<uint8_t>(4 * n)};
            uint32_t pattern;
            std::memcpy(&pattern, k.data(), 4);
            uint8_t* px = r->image8.rgba.data();
            for (size_t i = 0; i < n; ++i) std::memcpy(px + 4 * i, &pattern, 4);
        }
    }
    // The float buffer: glClearColor(c / 255.0f).
    if (floats) {
        r->imageF = {box.width, box.height, std::vector<float>(4 * n)};  // zeros
        const float c[4] = {k[0] / 255.0f, k[1] / 255.0f, k[2] / 255.0f, k[3] / 255.0f};
        float* px = r->imageF.rgba.data();
        if (k[0] | k[1] | k[2] | k[3])
            for (size_t i = 0; i < n; ++i) std::memcpy(px + 4 * i, c, sizeof c);
    }
    return {&prepared,
            options,
            &r->image8,
            &r->imageF,
            nullptr,
            nullptr,
            ownDepth ? ClearedDepth(frame, &r->depth) : nullptr,
            box};
}

// The 8-bit picture of a float colour buffer, once drawn.
void FinishResult(const Frame& frame, const RenderOptions& options, RenderResult* r) {
    if (!FloatTarget(frame, options) || !options.picture8) return;
    for (size_t i = 0; i < r->imageF.rgba.size(); ++i)
        r->image8.rgba[i] =
            UnormFromFloat(r->imageF.rgba[i], options.rounding == UnormRounding::HalfEven);
}

// The pixels of MatrixRows band b: GL rows [y0, y1) are the buffer's rows [height - y1,
// height - y0).
std::pair<size_t, size_t> BandPixels(int width, int height, int b) {
    const int y0 = b * MatrixRows::kBandRows;
    const int y1 = std::min(y0 + MatrixRows::kBandRows, height);
    return {static_cast<size_t>(height - y1) * static_cast<size_t>(width),
            static_cast<size_t>(height - y0) * static_cast<size_t>(width)};
}

// CSR from the logged taps of the kept pixels (the i-th kept pixel is pixelOf(i), kept pixels
// increasing; keptFrom(p) the first kept index whose pixel is >= p): per band, its log grouped by
// pixel (MatrixRows::GroupBand), each kept pixel's taps sorted by texel, then per channel c the
// row of columns 4 * texel + c, duplicate texels summed in sorted order. Bands are independent,
// so they run in parallel (group, sort and count, then fill); each band's log freed once copied.
template <class PixelOf, class KeptFrom>
void RowsToCsr(MatrixRows* rows, int width, int height, size_t kept, const PixelOf& pixelOf,
               const KeptFrom& keptFrom, RenderingMatrix* m, int threads) {
    const auto byTexel = [](const MatrixTap& a, const MatrixTap& b) { return a.texel < b.texel; };
    const int bands = static_cast<int>(rows->Bands());
    const auto bandPixels = [&](int b) { return BandPixels(width, height, b); };
    // Step 1: each band's taps grouped by pixel, each kept pixel's sorted, its texels counted.
    std::vector<uint32_t> distinct(kept, 0);
    std::vector<std::vector<uint32_t>> first(static_cast<size_t>(bands));
    base::ParallelFor(bands, threads, [&](int b) {
        const auto [p0, p1] = bandPixels(b);
        std::vector<MatrixTap> scratch;
        std::vector<uint32_t>& f = first[static_cast<size_t>(b)];
        rows->GroupBand(static_cast<size_t>(b), p0, p1, &f, &scratch);
        std::vector<MatrixTap>& log = rows->Log(static_cast<size_t>(b));
        for (size_t i = keptFrom(p0); i < keptFrom(p1); ++i) {
            const size_t p = pixelOf(i) - p0;
            const auto row = log.begin() + f[p], end = log.begin() + f[p + 1];
            std::sort(row, end, byTexel);
            for (auto k = row; k != end; ++k)
                distinct[i] += k == row || k->texel != (k - 1)->texel ? 1u : 0u;
        }
    });
    // Step 2: row pointers, four rows of distinct[i] entries per pixel.
    m->rowPtr.assign(4 * kept + 1, 0);
    for (size_t i = 0; i < kept; ++i)
        for (size_t c = 0; c < 4; ++c)
            m->rowPtr[4 * i + c + 1] = m->rowPtr[4 * i + c] + distinct[i];
    m->col.resize(static_cast<size_t>(m->rowPtr.back()));
    m->val.resize(m->col.size());
    // Step 3: the entries.
    base::ParallelFor(bands, threads, [&](int b) {
        const auto [p0, p1] = bandPixels(b);
        const std::vector<uint32_t>& f = first[static_cast<size_t>(b)];
        std::vector<MatrixTap>& log = rows->Log(static_cast<size_t>(b));
        for (size_t i = keptFrom(p0); i < keptFrom(p1); ++i) {
            const size_t p = pixelOf(i) - p0;
            const MatrixTap* row = log.data() + f[p];
            const size_t count = f[p + 1] - f[p];
            auto at = static_cast<size_t>(m->rowPtr[4 * i]);
            for (size_t c = 0; c < 4; ++c)
                for (size_t k = 0; k < count; ++k) {
                    const double v = row[k].weight * static_cast<double>(row[k].modulation[c]);
                    if (k > 0 && row[k].texel == row[k - 1].texel) {
                        m->val[at - 1] += v;
                        continue;
                    }
                    m->col[at] = 4 * row[k].texel + static_cast<uint32_t>(c);
                    m->val[at++] = v;
                }
        }
        std::vector<MatrixTap>().swap(log);
    });
}

// The per-pixel arrays of the kept pixels, moved to the front in place (pixelOf(i) >= i).
template <class PixelOf>
void KeepPixels(size_t kept, const PixelOf& pixelOf, RenderingMatrix* m) {
    for (size_t i = 0; i < kept; ++i) {
        const size_t p = pixelOf(i);
        for (size_t c = 0; c < 4; ++c) m->offset[4 * i + c] = m->offset[4 * p + c];
        m->fragments[i] = m->fragments[p];
    }
    m->offset.resize(4 * kept);
    m->fragments.resize(kept);
}

// The float of each byte (c / 255, or llvmpipe's c * fl(1/255)), through a table of the 256.
std::vector<float> ToFloat(const std::vector<uint8_t>& bytes, bool exact) {
    std::array<float, 256> table;
    for (int c = 0; c < 256; ++c) {
        const auto b = static_cast<uint8_t>(c);
        table[static_cast<size_t>(c)] = exact ? static_cast<float>(b) / 255.0f : FloatFromUnorm8(b);
    }
    std::vector<float> f(bytes.size());
    for (size_t i = 0; i < bytes.size(); ++i) f[i] = table[bytes[i]];
    return f;
}

// The softpipe model covers RGBA8 textures and colour buffers only.
void RequireRgba8(const Frame& frame, const char* profile) {
    bool rgba8 = frame.colorFormat == ColorFormat::Rgba8;
    for (const Texture& t : frame.textures) rgba8 &= t.format == TexelFormat::Rgba8;
    if (!rgba8)
        throw std::invalid_argument(
            std::string("the ") + profile +
            " profile draws RGBA8 textures into an RGBA8 colour buffer only");
}

// A scissor box must lie inside the framebuffer and hold a pixel.
void RequireValidScissor(const Frame& frame) {
    if (!frame.scissor) return;
    const PixelBox& b = *frame.scissor;
    if (b.width < 1 || b.height < 1 || b.x < 0 || b.y < 0 || b.width > frame.width - b.x ||
        b.height > frame.height - b.y)
        throw std::invalid_argument(
            "scissor box " + std::to_string(b.width) + "x" + std::to_string(b.height) + " at (" +
            std::to_string(b.x) + ", " + std::to_string(b.y) + ") is not inside the " +
            std::to_string(frame.width) + "x" + std::to_string(frame.height) + " framebuffer");
}

// The whole-frame result `r` (rows top-down) cut to the frame's drawn box.
void CropToDrawnBox(const Frame& frame, RenderResult* r) {
    if (!frame.scissor) return;
    const PixelBox& b = *frame.scissor;
    const auto top = static_cast<size_t>(frame.height - b.y - b.height);
    const auto crop = [&](const auto& in, size_t perPixel) {
        std::remove_cvref_t<decltype(in)> out(perPixel * Pixels(b));
        for (size_t row = 0; row < static_cast<size_t>(b.height); ++row)
            std::copy_n(
                in.begin() + static_cast<std::ptrdiff_t>(
                                 perPixel * ((top + row) * static_cast<size_t>(frame.width) +
                                             static_cast<size_t>(b.x))),
                perPixel * static_cast<size_t>(b.width),
                out.begin() +
                    static_cast<std::ptrdiff_t>(perPixel * row * static_cast<size_t>(b.width)));
        return out;
    };
    if (!r->image8.rgba.empty()) r->image8 = {b.width, b.height, crop(r->image8.rgba, 4)};
    if (!r->imageF.rgba.empty()) r->imageF = {b.width, b.height, crop(r->imageF.rgba, 4)};
    if (!r->depth.empty()) r->depth = crop(r->depth, 1);
}

// Matrix mode's checks: linear blends, no scissor box, kept pixels increasing in the frame.
void CheckMatrixFrame(const Frame& frame, const std::vector<uint32_t>* pixels, const char* what) {
    if (frame.scissor)
        throw std::invalid_argument(std::string(what) + ": a scissored frame (list the pixels)");
    for (size_t i = 0; i < frame.passes.size(); ++i) {
        const Pass& p = frame.passes[i];
        if (p.blend.enabled && !(p.blend == BlendState::Additive()))
            throw std::invalid_argument("pass " + std::to_string(i) +
                                        ": blend is not linear in the texels (use none or add)");
    }
    const size_t n = static_cast<size_t>(frame.width) * frame.height;
    if (!pixels) return;
    for (size_t i = 0; i < pixels->size(); ++i)
        if ((*pixels)[i] >= n || (i > 0 && (*pixels)[i] <= (*pixels)[i - 1]))
            throw std::invalid_argument(std::string(what) +
                                        ": kept pixels not increasing in the frame");
}

// The draw of matrix mode: every pixel's offsets and fragment counts into *m (sized here), its
// taps into *rows, the rendered picture into *r (softpipe: drawn after).
void DrawMatrixRows(const PreparedFrame& prepared, const RenderOptions& options, RenderingMatrix* m,
                    MatrixRows* rows, RenderResult* r) {
    const Frame& frame = prepared.frame();
    const size_t n = static_cast<size_t>(frame.width) * frame.height;
    m->offset.assign(4 * n, 0.0);
    m->fragments.assign(n, 0);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 4; ++c)
            m->offset[4 * i + c] =
                FloatTarget(frame, options)
                    ? static_cast<double>(static_cast<float>(frame.clear[c]) / 255.0f)
                    : frame.clear[c] / 255.0;
    if (options.profile == Profile::Softpipe) {
        RequireRgba8(frame, "softpipe");
        SoftpipeMatrixRows(prepared, m, rows);
        *r = Render(prepared, options);
    } else {
        FragmentTarget tg = ClearedTarget(prepared, options, r);
        tg.matrix = m;
        tg.rows = rows;
        DrawFrame(tg);
        FinishResult(frame, options, r);
    }
}

// The first kept index whose pixel is >= p (kept pixels increasing; null: every pixel).
size_t KeptFrom(const std::vector<uint32_t>* pixels, size_t p) {
    return pixels ? static_cast<size_t>(std::lower_bound(pixels->begin(), pixels->end(), p) -
                                        pixels->begin())
                  : p;
}

}  // namespace

std::shared_ptr<const PreparedTexture> PrepareTexture(const Texture& t) {
    auto p = std::make_shared<PreparedTexture>();
    p->source = &t;
    p->lod = DerivePipeLodState(t.sampler, t.NumLevels());
    for (const auto& level : t.levels) {
        if (t.format == TexelFormat::Rgba32F) {  // the floats as they are, on every path
            p->levelsF.push_back(FloatsFromBytes(level));
            p->levelsExact.push_back(p->levelsF.back());
            continue;
        }
        p->levelsF.push_back(ToFloat(level, false));
        p->levelsExact.push_back(ToFloat(level, true));
    }
    return p;
}

PreparedFrame::PreparedFrame(const Frame& frame) : frame_(&frame), indexer_(frame.textures) {
    for (const Texture& t : frame.textures) textures_.push_back(PrepareTexture(t));
}

PreparedFrame::PreparedFrame(const Frame& frame,
                             std::vector<std::shared_ptr<const PreparedTexture>> prepared)
    : frame_(&frame), textures_(std::move(prepared)), indexer_(frame.textures) {
    if (textures_.size() != frame.textures.size())
        throw std::invalid_argument("PreparedFrame: one prepared texture per frame texture");
}

RenderResult Render(const PreparedFrame& prepared, const RenderOptions& options) {
    return std::move(RenderFrames({&prepared}, options)[0]);
}

std::vector<RenderResult> RenderFrames(const std::vector<const PreparedFrame*>& frames,
                                       const RenderOptions& options) {
    std::vector<RenderResult> results(frames.size());
    for (const PreparedFrame* f : frames) RequireValidScissor(f->frame());
    if (options.profile == Profile::Softpipe) {  // scissor: the whole frame drawn, then cut
        for (size_t f = 0; f < frames.size(); ++f) {
            RequireRgba8(frames[f]->frame(), "softpipe");
            results[f] = RenderSoftpipe(*frames[f]);
            CropToDrawnBox(frames[f]->frame(), &results[f]);
        }
        return results;
    }
    // Frames with the same depth history share the first one's depth buffer (its tests), and
    // get a copy of it at the end.
    std::vector<size_t> twin(frames.size());
    for (size_t f = 0; f < frames.size(); ++f) {
        twin[f] = f;
        for (size_t g = 0; g < f && twin[f] == f; ++g)
            if (twin[g] == g && SameDepthHistory(frames[g]->frame(), frames[f]->frame()))
                twin[f] = g;
    }
    std::vector<FragmentTarget> targets;
    targets.reserve(frames.size());
    for (size_t f = 0; f < frames.size(); ++f) {
        targets.push_back(ClearedTarget(*frames[f], options, &results[f], twin[f] == f));
        if (twin[f] != f) targets[f].depthTwin = &targets[twin[f]];
    }
    if (!targets.empty()) DrawFrames(targets);
    for (size_t f = 0; f < frames.size(); ++f) {
        if (twin[f] != f) results[f].depth = results[twin[f]].depth;
        FinishResult(frames[f]->frame(), options, &results[f]);
    }
    return results;
}

RenderingMatrix BuildRenderingMatrix(const PreparedFrame& prepared, const RenderOptions& options,
                                     const std::vector<uint32_t>* pixels) {
    const Frame& frame = prepared.frame();
    CheckMatrixFrame(frame, pixels, "BuildRenderingMatrix");
    const size_t n = static_cast<size_t>(frame.width) * frame.height;
    const size_t kept = pixels ? pixels->size() : n;
    const auto pixelOf = [&](size_t i) { return pixels ? size_t{(*pixels)[i]} : i; };
    RenderingMatrix m;
    m.rows = static_cast<int64_t>(4 * kept);
    m.cols = 4 * static_cast<int64_t>(prepared.indexer().TotalTexels());
    MatrixRows rows(n, frame.height);
    RenderResult r;
    DrawMatrixRows(prepared, options, &m, &rows, &r);
    // The kept pixels' rows, offsets, fragment counts and rendered values.
    const auto keptFrom = [&](size_t p) { return KeptFrom(pixels, p); };
    RowsToCsr(&rows, frame.width, frame.height, kept, pixelOf, keptFrom, &m, options.threads);
    KeepPixels(kept, pixelOf, &m);
    m.rendered.resize(4 * kept);
    for (size_t i = 0; i < kept; ++i)
        for (size_t c = 0; c < 4; ++c) {
            const size_t at = 4 * pixelOf(i) + c;
            m.rendered[4 * i + c] = FloatTarget(frame, options)
                                        ? static_cast<double>(r.imageF.rgba[at])
                                        : r.image8.rgba[at] / 255.0;
        }
    return m;
}

std::vector<uint32_t> FinestTexels(const PreparedFrame& prepared, const RenderOptions& options,
                                   const std::vector<uint32_t>* pixels) {
    const Frame& frame = prepared.frame();
    CheckMatrixFrame(frame, pixels, "FinestTexels");
    const size_t n = static_cast<size_t>(frame.width) * frame.height;
    const size_t kept = pixels ? pixels->size() : n;
    RenderingMatrix m;
    MatrixRows rows(n, frame.height);
    RenderResult r;
    DrawMatrixRows(prepared, options, &m, &rows, &r);
    // Per band: its taps grouped by pixel, the least texel of each kept pixel's.
    std::vector<uint32_t> finest(kept, kNoTexel);
    base::ParallelFor(static_cast<int>(rows.Bands()), options.threads, [&](int b) {
        const auto [p0, p1] = BandPixels(frame.width, frame.height, b);
        std::vector<uint32_t> first;
        std::vector<MatrixTap> scratch;
        rows.GroupBand(static_cast<size_t>(b), p0, p1, &first, &scratch);
        const std::vector<MatrixTap>& log = rows.Log(static_cast<size_t>(b));
        for (size_t i = KeptFrom(pixels, p0); i < KeptFrom(pixels, p1); ++i) {
            const size_t p = (pixels ? size_t{(*pixels)[i]} : i) - p0;
            for (uint32_t k = first[p]; k < first[p + 1]; ++k)
                finest[i] = std::min(finest[i], log[k].texel);
        }
        std::vector<MatrixTap>().swap(rows.Log(static_cast<size_t>(b)));
    });
    return finest;
}

}  // namespace pem::raster
