// SPDX-License-Identifier: MIT
// render.cpp — RenderFrame and CompareImages (render.h).
#include "trace/render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "base/parallel.h"

namespace pem::trace {

namespace {

// One image row, traced in coherent steps: all camera rays (packets of 8), then lens and miss
// samples (the full tree is recorded as a Tracer::RadianceTape, its diffuse leaves deferred; the
// greedy model shades immediately), then the diffuse points one light at a time (shadow rays in
// packets of 8; camera-ray points and tree-leaf points in separate batches), then the samples'
// values, then the box filter in sample order. Per sample this is the same arithmetic as
// Tracer::HitRadiance / ShadeDiffuse (packets give the same hits as single rays), so the values
// do not depend on this order.
struct RowTracer {
    RowTracer(const Tracer& t, const raster::Camera& c, const raster::PixelRays& p, int kk, Model m)
        : tracer(t), camera(c), pixelRays(p), k(kk), model(m) {}

    const Tracer& tracer;
    const raster::Camera& camera;
    const raster::PixelRays& pixelRays;
    int k;
    Model model;
    std::vector<Ray> rays;
    std::vector<Hit> hits;
    std::vector<glm::vec2> offsets;  // SampleOffset per sample of a pixel
    std::vector<glm::vec3> radiance, irradiance, leafIrradiance, stack;
    std::vector<size_t> diffuse, taped, tapeStart;
    std::vector<glm::ivec2> row;
    std::vector<Tracer::DiffusePoint> points;
    Tracer::RadianceTape tape;

    // Every sample of the given pixels: camera rays, then their radiance (lens samples black in
    // the Surroundings model) into `radiance`, pixels × k² in sample order.
    void TraceSamples(std::span<const glm::ivec2> pixels, RayCounts& counts) {
        const int spp = k * k;
        const size_t n = pixels.size() * static_cast<size_t>(spp);
        rays.resize(n), hits.resize(n), radiance.assign(n, glm::vec3(0.0f));
        diffuse.clear(), points.clear(), taped.clear(), tapeStart.clear(), tape.Clear();
        offsets.resize(static_cast<size_t>(spp));
        for (int s = 0; s < spp; ++s) offsets[static_cast<size_t>(s)] = SampleOffset(k, s);
        for (size_t i = 0, p = 0; p < pixels.size(); ++p) {
            const float fx = static_cast<float>(pixels[p].x), fy = static_cast<float>(pixels[p].y);
            for (const glm::vec2& o : offsets) rays[i++] = pixelRays(fx + o.x, fy + o.y);
        }
        tracer.IntersectCamera(rays, hits, counts);
        const int depth = tracer.options().fullTreeDepth;
        for (size_t i = 0; i < n; ++i) {
            const int group = hits[i].valid ? tracer.GroupOf(hits[i].object) : -1;
            if (hits[i].valid && group < 0) {
                diffuse.push_back(i);
                points.push_back(tracer.DiffuseAt(rays[i], hits[i]));
            } else if (model == Model::Greedy && group >= 0) {
                radiance[i] = tracer.TraceGreedy(rays[i], hits[i], group, counts).Radiance();
            } else if (model == Model::Surroundings && group >= 0) {
                continue;  // black: drawn from the maps
            } else {
                taped.push_back(i);
                tapeStart.push_back(tape.ops.size());
                tracer.RecordHitRadiance(rays[i], hits[i], depth, 1.0, tape, counts);
            }
        }
        tapeStart.push_back(tape.ops.size());
        irradiance.assign(points.size(), glm::vec3(0.0f));
        leafIrradiance.assign(tape.points.size(), glm::vec3(0.0f));
        for (const Light& light : tracer.scene().lights) {
            tracer.AddLightIrradiance(light, points, irradiance, counts);
            tracer.AddLightIrradiance(light, tape.points, leafIrradiance, counts);
        }
        for (size_t j = 0; j < points.size(); ++j)
            radiance[diffuse[j]] = Tracer::Finish(points[j], irradiance[j]);
        const std::span<const Tracer::RadianceTape::Entry> ops(tape.ops);
        for (size_t j = 0; j < taped.size(); ++j)
            radiance[taped[j]] =
                Tracer::EvalTape(ops.subspan(tapeStart[j], tapeStart[j + 1] - tapeStart[j]),
                                 tape.points, leafIrradiance, stack);
    }

    // One image row into `out`.
    void Trace(int y, FrameResult& out, RayCounts& counts) {
        const int spp = k * k;
        row.resize(static_cast<size_t>(camera.width));
        for (int x = 0; x < camera.width; ++x) row[static_cast<size_t>(x)] = glm::ivec2(x, y);
        TraceSamples(row, counts);
        const float invSamples = 1.0f / static_cast<float>(spp);
        for (int x = 0; x < camera.width; ++x) {
            glm::vec3 sum(0.0f);
            float lens = 0.0f;
            for (int s = 0; s < spp; ++s) {
                const size_t i =
                    static_cast<size_t>(x) * static_cast<size_t>(spp) + static_cast<size_t>(s);
                sum += radiance[i];
                lens += hits[i].valid && tracer.GroupOf(hits[i].object) >= 0 ? 1.0f : 0.0f;
            }
            out.image.Add(x, y, sum * invSamples);
            out.lensCoverage.At(x, y)[0] = lens * invSamples;
            if (model == Model::Surroundings) {
                const Hit& first = hits[static_cast<size_t>(x) * static_cast<size_t>(spp)];
                out.lensGroup[static_cast<size_t>(y) * static_cast<size_t>(camera.width) +
                              static_cast<size_t>(x)] =
                    first.valid ? tracer.GroupOf(first.object) : -1;
            }
        }
    }
};

}  // namespace

FrameResult RenderFrame(const Tracer& tracer, const raster::Camera& camera, int k, Model model,
                        int threads, const std::function<void(int, int)>& progress) {
    FrameResult result{FloatImage(camera.width, camera.height, 3),
                       FloatImage(camera.width, camera.height, 1),
                       {},
                       {}};
    if (model == Model::Surroundings)
        result.lensGroup.assign(
            static_cast<size_t>(camera.width) * static_cast<size_t>(camera.height), -1);
    std::vector<RayCounts> rowCounts(static_cast<size_t>(camera.height));
    const raster::PixelRays pixelRays(camera);
    // Idle row tracers: each row takes one and gives it back, so the buffers are reused across
    // rows (no per-row allocation and page faults); every buffer is reset per row.
    std::mutex poolMutex;
    std::vector<std::unique_ptr<RowTracer>> pool;
    base::ParallelFor(
        camera.height, threads,
        [&](int y) {
            std::unique_ptr<RowTracer> row;
            {
                std::lock_guard<std::mutex> lock(poolMutex);
                if (!pool.empty()) row = std::move(pool.back()), pool.pop_back();
            }
            if (!row) row = std::make_unique<RowTracer>(tracer, camera, pixelRays, k, model);
            row->Trace(y, result, rowCounts[static_cast<size_t>(y)]);
            std::lock_guard<std::mutex> lock(poolMutex);
            pool.push_back(std::move(row));
        },
        progress);
    for (const RayCounts& c : rowCounts) result.counts += c;
    return result;
}

PixelSamples RenderPixels(const Tracer& tracer, const raster::Camera& camera, int k,
                          const std::vector<glm::ivec2>& pixels, int threads) {
    const size_t spp = static_cast<size_t>(k) * static_cast<size_t>(k);
    PixelSamples out;
    out.surroundings.assign(pixels.size(), glm::vec3(0.0f));
    out.groups.assign(pixels.size() * spp, -1);
    // Runs of kRun pixels, each traced by one RowTracer of its thread into its own slots.
    constexpr size_t kRun = 64;
    const size_t runs = (pixels.size() + kRun - 1) / kRun;
    std::vector<RayCounts> runCounts(runs);
    const raster::PixelRays pixelRays(camera);
    base::ParallelFor(static_cast<int>(runs), threads, [&](int r) {
        RowTracer t(tracer, camera, pixelRays, k, Model::Surroundings);
        const size_t first = static_cast<size_t>(r) * kRun;
        const size_t count = std::min(kRun, pixels.size() - first);
        t.TraceSamples(std::span<const glm::ivec2>(pixels).subspan(first, count),
                       runCounts[static_cast<size_t>(r)]);
        const float invSamples = 1.0f / static_cast<float>(spp);
        for (size_t p = 0; p < count; ++p) {
            glm::vec3 sum(0.0f);
            for (size_t s = 0; s < spp; ++s) {
                const size_t i = p * spp + s;
                sum += t.radiance[i];
                out.groups[(first + p) * spp + s] =
                    t.hits[i].valid ? tracer.GroupOf(t.hits[i].object) : -1;
            }
            out.surroundings[first + p] = sum * invSamples;
        }
    });
    for (const RayCounts& c : runCounts) out.counts += c;
    return out;
}

ImageError CompareImages(const FloatImage& a, const FloatImage& b, const FloatImage& mask,
                         bool hdr) {
    ImageError e;
    double sum = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (!mask.data.empty() && !(mask.At(x, y)[0] > 0.0f)) continue;
            for (int c = 0; c < 3; ++c) {
                double va = static_cast<double>(a.At(x, y)[c]),
                       vb = static_cast<double>(b.At(x, y)[c]);
                if (!hdr) va = std::clamp(va, 0.0, 1.0), vb = std::clamp(vb, 0.0, 1.0);
                sum += (va - vb) * (va - vb);
            }
            ++e.pixels;
        }
    if (e.pixels == 0) return e;
    const double mse = sum / (3.0 * static_cast<double>(e.pixels));
    e.rmse = std::sqrt(mse);
    e.psnr = mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : std::numeric_limits<double>::infinity();
    return e;
}

}  // namespace pem::trace
