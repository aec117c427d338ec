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
#include "raster/fragment.h"
#include "raster/numeric.h"
#include "raster/triangle_setup.h"

namespace pem::raster {
namespace {

int ColourOffset(const Pass& pass) {
    return 3 * pass.numUnits;
}

// Vertex fetch, clipping, viewport transform and triangle setup of one pass.
std::vector<TriangleSetup> SetupPass(const Frame& frame, const Pass& pass, int first, int last) {
    const int numAttribs = ColourOffset(pass) + 4;
    auto fetch = [&](uint32_t index) {
        const Vertex& v = pass.vertices[index];
        ClipVertex cv{v.pos, {}};
        for (int u = 0; u < pass.numUnits; ++u)
            for (int k = 0; k < 3; ++k) cv.attr[static_cast<size_t>(3 * u + k)] = v.coord[u][k];
        for (int k = 0; k < 4; ++k)
            cv.attr[static_cast<size_t>(ColourOffset(pass) + k)] = v.color[k];
        return cv;
    };
    std::vector<TriangleSetup> setups;
    std::vector<WindowTriangle> clipped;
    for (int t = first; t < last; ++t) {
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

// Runs fn(0) .. fn(workers - 1), each on its own thread (fn(0) on the caller's), with
// denormals flushed when `ftz` (llvmpipe's draw and rasterizer threads both flush).
template <typename Fn>
void RunWorkers(int workers, bool ftz, const Fn& fn) {
    auto run = [&](int w) {
        if (ftz) {
            ScopedFlushToZero guard;
            fn(w);
        } else {
            fn(w);
        }
    };
    std::vector<std::thread> pool;
    for (int w = 1; w < workers; ++w) pool.emplace_back(run, w);
    run(0);
    for (std::thread& th : pool) th.join();
}

void DrawFrame(const FragmentTarget& tg) {
    const bool ftz = tg.options.profile == Profile::Llvmpipe;  // Linear: plain IEEE arithmetic
    const Frame& frame = tg.frame->frame();
    const DrawBandsFn drawBands = SelectDrawBands();
    const int workers = std::max(1, tg.options.threads);
    for (const Pass& pass : frame.passes) {
        // Setup in contiguous chunks of triangles, joined in primitive order.
        const int n = pass.NumTriangles();
        std::vector<std::vector<TriangleSetup>> chunks(static_cast<size_t>(workers));
        RunWorkers(workers, ftz, [&](int w) {
            chunks[static_cast<size_t>(w)] =
                SetupPass(frame, pass, static_cast<int>(int64_t{n} * w / workers),
                          static_cast<int>(int64_t{n} * (w + 1) / workers));
        });
        std::vector<TriangleSetup> setups = std::move(chunks[0]);
        for (size_t w = 1; w < chunks.size(); ++w)
            setups.insert(setups.end(), chunks[w].begin(), chunks[w].end());
        // Fragments by row bands.
        RunWorkers(workers, ftz, [&](int w) { drawBands(tg, pass, setups, w, workers); });
    }
}

std::vector<float> ToFloat(const std::vector<uint8_t>& bytes, bool exact) {
    std::vector<float> f(bytes.size());
    for (size_t i = 0; i < bytes.size(); ++i)
        f[i] = exact ? static_cast<float>(bytes[i]) / 255.0f : FloatFromUnorm8(bytes[i]);
    return f;
}

}  // namespace

std::shared_ptr<const PreparedTexture> PrepareTexture(const Texture& t) {
    auto p = std::make_shared<PreparedTexture>();
    p->source = &t;
    p->lod = DerivePipeLodState(t.sampler, t.NumLevels());
    for (const auto& level : t.levels) {
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
    const Frame& frame = prepared.frame();
    const size_t n = static_cast<size_t>(frame.width) * frame.height;
    RenderResult r;
    r.image8 = {frame.width, frame.height, std::vector<uint8_t>(4 * n)};
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 4; ++c) r.image8.rgba[4 * i + c] = frame.clear[c];
    if (options.profile == Profile::Linear) {
        r.imageF = {frame.width, frame.height, std::vector<float>(4 * n)};
        for (size_t i = 0; i < 4 * n; ++i)
            r.imageF.rgba[i] = static_cast<float>(r.image8.rgba[i]) / 255.0f;
    }
    DrawFrame({&prepared, options, &r.image8, &r.imageF, nullptr, nullptr});
    if (options.profile == Profile::Linear)
        for (size_t i = 0; i < 4 * n; ++i)
            r.image8.rgba[i] =
                UnormFromFloat(r.imageF.rgba[i], options.rounding == UnormRounding::HalfEven);
    return r;
}

RenderingMatrix BuildRenderingMatrix(const PreparedFrame& prepared, const RenderOptions& options) {
    const Frame& frame = prepared.frame();
    for (size_t i = 0; i < frame.passes.size(); ++i) {
        const Pass& p = frame.passes[i];
        if (p.blend.enabled && !(p.blend == BlendState::Additive()))
            throw std::invalid_argument("pass " + std::to_string(i) +
                                        ": blend is not linear in the texels (use none or add)");
    }
    const size_t n = static_cast<size_t>(frame.width) * frame.height;
    RenderingMatrix m;
    m.rows = static_cast<int64_t>(4 * n);
    m.cols = 4 * static_cast<int64_t>(prepared.indexer().TotalTexels());
    m.offset.assign(4 * n, 0.0);
    m.fragments.assign(n, 0);
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
