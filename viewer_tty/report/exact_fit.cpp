// SPDX-License-Identifier: MIT
// exact_fit.cpp — layer maps fitted through exact per-subpixel lookups (exact_fit.h).
#include "viewer_tty/report/exact_fit.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "base/parallel.h"
#include "infer/env_map.h"
#include "infer/problem.h"
#include "infer/solver.h"
#include "raster/cube_lookup.h"
#include "raster/render.h"
#include "trace/segment.h"

namespace pem::report {
namespace {

// Every subpixel of the group's pixels: covered (its camera ray meets the group, continued
// through occluders as the trace's segmentation does) and each term's exit ray, if it escaped.
struct Subpixels {
    int k2 = 1;
    std::vector<uint32_t> pixels;  // pixel indices with coverage > 0
    std::vector<uint8_t> covered;  // [pixel slot · k2 + s]
    std::vector<uint8_t> escaped[2];
    std::vector<raster::Ray> exits[2];
};

Subpixels TraceSubpixels(const trace::Tracer& tracer, const raster::Camera& camera, int k,
                         int group, const trace::FloatImage& coverage, int threads) {
    Subpixels sp;
    sp.k2 = k * k;
    for (int p = 0; p < camera.width * camera.height; ++p)
        if (coverage.data[4 * size_t(p) + 3] > 0.0f) sp.pixels.push_back(uint32_t(p));
    const size_t n = sp.pixels.size() * size_t(sp.k2);
    sp.covered.assign(n, 0);
    for (int t = 0; t < 2; ++t) sp.escaped[t].assign(n, 0), sp.exits[t].resize(n);
    const raster::PixelRays rays(camera);
    base::ForChunks(sp.pixels.size(), threads, [&](size_t first, size_t last) {
        trace::RayCounts counts;
        for (size_t q = first; q < last; ++q)
            for (int s = 0; s < sp.k2; ++s) {
                const int x = int(sp.pixels[q]) % camera.width,
                          y = int(sp.pixels[q]) / camera.width;
                const glm::vec2 at = trace::SamplePosition(x, y, k, s);
                const raster::Ray ray = rays(at.x, at.y);
                const trace::Hit hit = trace::IncomingHit(tracer, ray, group, counts);
                const size_t slot = q * size_t(sp.k2) + size_t(s);
                if (!hit.valid) continue;
                sp.covered[slot] = 1;
                const auto paths = tracer.GreedyPathsAt(ray, hit, group, counts);
                if (!paths) continue;
                for (int t = 0; t < 2; ++t) {
                    const trace::RayPath& p = t == 0 ? paths->reflection : paths->refraction;
                    if (!p.escaped) continue;
                    sp.escaped[t][slot] = 1;
                    sp.exits[t][slot] = {p.exitOrigin, p.exitDir};
                }
            }
    });
    return sp;
}

// The bilinear taps at the finest level of a face-size-n cube, clamped to the face.
void AddTaps(const glm::dvec3& dir, int n, double weight, std::map<uint32_t, double>* taps) {
    const raster::CubeCoord cc =
        raster::CubeLookup({float(dir.x), float(dir.y), float(dir.z)}, {0, 0, 0}, {0, 0, 0}, false);
    const double x = double(cc.s) * n - 0.5, y = double(cc.t) * n - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y), fx = x - x0, fy = y - y0;
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            const int i = std::clamp(int(x0) + dx, 0, n - 1),
                      j = std::clamp(int(y0) + dy, 0, n - 1);
            const double w = (dx ? fx : 1.0 - fx) * (dy ? fy : 1.0 - fy);
            if (w > 0.0) (*taps)[uint32_t((cc.face * n + j) * n + i)] += weight * w;
        }
}

// Rows 4·(term·W·H + pixel) + c of one layer: the mean over the pixel's covered subpixels of
// the map at each exit ray's meeting with the shell.
raster::RenderingMatrix ExactRows(const Subpixels& sp, const raster::Camera& cam, int terms,
                                  const trace::Shell& shell, const glm::vec3& emOrigin, int res,
                                  uint32_t texels) {
    raster::RenderingMatrix a;
    const size_t wh = size_t(cam.width) * size_t(cam.height);
    a.rows = int64_t(4 * wh * size_t(terms));
    a.cols = int64_t(4) * texels;
    std::vector<std::map<uint32_t, double>> rowTaps(wh * size_t(terms));
    for (int t = 0; t < terms; ++t)
        for (size_t q = 0; q < sp.pixels.size(); ++q) {
            int covered = 0;
            for (int s = 0; s < sp.k2; ++s) covered += sp.covered[q * size_t(sp.k2) + size_t(s)];
            auto& taps = rowTaps[size_t(t) * wh + sp.pixels[q]];
            for (int s = 0; s < sp.k2; ++s) {
                const size_t slot = q * size_t(sp.k2) + size_t(s);
                if (!sp.escaped[t][slot]) continue;
                const auto hit = trace::Intersect(shell, sp.exits[t][slot]);
                if (hit) AddTaps(hit->point - glm::dvec3(emOrigin), res, 1.0 / covered, &taps);
            }
        }
    a.rowPtr.push_back(0);
    for (const auto& taps : rowTaps)
        for (int c = 0; c < 4; ++c) {
            for (const auto& [texel, w] : taps)
                a.col.push_back(4 * texel + uint32_t(c)), a.val.push_back(w);
            a.rowPtr.push_back(int64_t(a.col.size()));
        }
    a.offset.assign(size_t(a.rows), 0.0);
    a.rendered.assign(size_t(a.rows), 0.0);
    return a;
}

raster::Frame UnknownCube(int width, int height, int res) {
    raster::Frame f;
    f.width = width, f.height = height;
    raster::Texture tex;
    tex.width = tex.height = res;
    for (int l = 0; (res >> l) >= 1; ++l)
        tex.levels.emplace_back(size_t(6 * (res >> l) * (res >> l) * 4), 0);
    f.textures.push_back(std::move(tex));
    return f;
}

using Layers = std::vector<std::vector<raster::ImageF>>;

// Iterations of every fit, each from the prior value. Measured on scene (a): 1000 move every
// stage by at most 0.1 dB but the cup's nonnegative fit (+1.0 dB); 100 iterations started from
// the fit before, clamped, end 0.3–2.9 dB lower than these.
constexpr int kIterations = 300;
// The unbounded fits (float maps' stages, the first fit of 8-bit maps'): on scene (a) with float
// maps 150 iterations give every stage of the budget to 0.01 dB as 300 do, in 0.7 of the time.
constexpr int kUnboundedIterations = 150;

// One layer's system at one resolution, RGB in the units radiance / scale. Its unknowns are the
// tapped texels alone (activeRings 0): with neither smoothness nor pyramid rows nothing couples
// a texel to its neighbours, an untapped texel stays at the prior, and the rows' values (all
// Show reads) are the same as with rings of untapped neighbours (2 rings held 2.2x the unknowns
// at 2x the maps' resolution and took 1.7x the time).
infer::LinearSystem BuildLayerSystem(const raster::RenderingMatrix& a, int res, int width,
                                     int height, const infer::Target& radiance, double scale) {
    infer::Target target = radiance;
    for (size_t row = 0; row < target.b.size(); ++row)
        if (row % 4 < 3) target.b[row] /= scale;
    infer::RegularizerWeights w;
    w.smooth = w.pyramid = 0.0;
    w.prior = 1e-9;
    return infer::BuildSystem(a, UnknownCube(width, height, res), 0, target, w, {0});
}

// The least-squares map (nearly unregularized, within `bounds`).
infer::Vector Fit(const infer::LinearSystem& sys, infer::Bounds bounds, int threads) {
    infer::SolveOptions so;
    so.bounds = bounds;
    so.maxIterations = bounds.Active() ? kIterations : kUnboundedIterations;
    so.atol = 1e-7;
    so.logEvery = 0;
    so.threads = threads;
    return infer::SolveIterative(sys, infer::InitialGuess(sys), so).x;
}

// What a solution shows, A x, as the layer's images per term (in radiance).
void Show(const raster::RenderingMatrix& a, const infer::LinearSystem& sys,
          const infer::Vector& solution, double scale, int terms, int width, int height,
          Layers* out) {
    const infer::Vector x = infer::FillUnobserved(sys, solution);
    const size_t wh = size_t(width) * size_t(height);
    for (int t = 0; t < terms; ++t) {
        raster::ImageF img{width, height, std::vector<float>(4 * wh, 0.0f)};
        for (size_t i = 0; i < 4 * wh; ++i) {
            const size_t row = 4 * size_t(t) * wh + i;
            double v = 0.0;
            for (int64_t e = a.rowPtr[row]; e < a.rowPtr[row + 1]; ++e)
                v += a.val[size_t(e)] * x[a.col[size_t(e)]];
            img.rgba[i] = float(v * (i % 4 < 3 ? scale : 1.0));
        }
        (*out)[size_t(t)].push_back(std::move(img));
    }
}

}  // namespace

ExactStages ExactLookupStages(const trace::Tracer& tracer, const raster::Camera& cam, int k,
                              const runtime::LensGroupEm& g,
                              const std::vector<std::vector<trace::FloatImage>>& targets,
                              const trace::FloatImage& coverage, int res, double maxRadiance,
                              bool bounded, int threads) {
    // Step 1: the subpixels' exit rays, traced once for every fit.
    const Subpixels sp = TraceSubpixels(tracer, cam, k, g.index, coverage, threads);
    const size_t wh = size_t(cam.width) * size_t(cam.height);
    ExactStages out;
    for (Layers* l : {&out.unbounded, &out.nonnegative, &out.inRange, &out.ownResolution})
        l->resize(size_t(g.Terms()));
    for (size_t l = 0; l < g.layers.size(); ++l) {
        if (g.layers[l].Empty()) continue;
        // Step 2: the targets in radiance, weighted by the coverage.
        infer::Target target;
        target.b.assign(4 * wh * size_t(g.Terms()), 0.0);
        target.confidence.assign(target.b.size(), 0.0);
        for (int t = 0; t < g.Terms(); ++t)
            for (uint32_t p : sp.pixels)
                for (size_t c = 0; c < 4; ++c) {
                    const size_t row = 4 * (size_t(t) * wh + p) + c;
                    target.b[row] = double(targets[size_t(t)][l].data[4 * p + c]);
                    target.confidence[row] = double(coverage.data[4 * size_t(p) + 3]);
                }
        // Step 3: at twice the resolution: unbounded, nonnegative, in the maps' range.
        const int w = cam.width, h = cam.height, terms = g.Terms();
        const auto rows = [&](int n) {
            const uint32_t texels =
                raster::TexelIndexer(UnknownCube(w, h, n).textures).TotalTexels();
            return ExactRows(sp, cam, terms, g.layers[l].shell, g.emOrigin, n, texels);
        };
        const raster::RenderingMatrix fine = rows(2 * res);
        const infer::LinearSystem sys = BuildLayerSystem(fine, 2 * res, w, h, target, 1.0);
        Show(fine, sys, Fit(sys, infer::Bounds::None(), threads), 1.0, terms, w, h, &out.unbounded);
        const raster::RenderingMatrix coarse = rows(res);
        if (!bounded) {  // float maps: unbounded at their own resolution too
            const infer::LinearSystem own = BuildLayerSystem(coarse, res, w, h, target, 1.0);
            Show(coarse, own, Fit(own, infer::Bounds::None(), threads), 1.0, terms, w, h,
                 &out.ownResolution);
            continue;
        }
        Show(fine, sys, Fit(sys, infer::Bounds::Hdr(), threads), 1.0, terms, w, h,
             &out.nonnegative);
        const infer::LinearSystem scaled =
            BuildLayerSystem(fine, 2 * res, w, h, target, maxRadiance);
        Show(fine, scaled, Fit(scaled, infer::Bounds::Unit(), threads), maxRadiance, terms, w, h,
             &out.inRange);
        // Step 4: in the maps' range at their own resolution.
        const infer::LinearSystem own = BuildLayerSystem(coarse, res, w, h, target, maxRadiance);
        Show(coarse, own, Fit(own, infer::Bounds::Unit(), threads), maxRadiance, terms, w, h,
             &out.ownResolution);
    }
    return out;
}

}  // namespace pem::report
