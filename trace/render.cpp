// SPDX-License-Identifier: MIT
// render.cpp — RenderFrame and CompareImages (render.h).
#include "trace/render.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "trace/parallel.h"

namespace pem::trace {

namespace {

// One image row, traced in coherent steps: all camera rays, then lens and miss samples, then the
// diffuse hits one light at a time (the same arithmetic as Tracer::ShadeDiffuse per sample, so
// the values do not depend on this order), then the box filter in sample order.
struct RowTracer {
    const Tracer& tracer;
    const raster::Camera& camera;
    int k;
    Model model;
    std::vector<Ray> rays;
    std::vector<Hit> hits;
    std::vector<glm::vec3> radiance, irradiance;
    std::vector<size_t> diffuse;
    std::vector<Tracer::DiffusePoint> points;

    void Trace(int y, FrameResult& out, RayCounts& counts) {
        const int spp = k * k;
        const size_t n = static_cast<size_t>(camera.width) * static_cast<size_t>(spp);
        rays.resize(n), hits.resize(n), radiance.assign(n, glm::vec3(0.0f));
        diffuse.clear(), points.clear();
        for (size_t i = 0; i < n; ++i) {
            const int x = static_cast<int>(i) / spp, s = static_cast<int>(i) % spp;
            const glm::vec2 p = SamplePosition(x, y, k, s);
            rays[i] = raster::PixelRay(camera, p.x, p.y);
            hits[i] = tracer.Intersect(rays[i], counts, true);
        }
        const int depth = tracer.options().fullTreeDepth;
        for (size_t i = 0; i < n; ++i) {
            const int group = hits[i].valid ? tracer.GroupOf(hits[i].object) : -1;
            if (hits[i].valid && group < 0) {
                diffuse.push_back(i);
                points.push_back(tracer.DiffuseAt(rays[i], hits[i]));
            } else if (model == Model::Greedy && group >= 0) {
                radiance[i] = tracer.TraceGreedy(rays[i], hits[i], group, counts).Radiance();
            } else {
                radiance[i] = tracer.HitRadiance(rays[i], hits[i], depth, 1.0, counts);
            }
        }
        irradiance.assign(points.size(), glm::vec3(0.0f));
        for (const Light& light : tracer.scene().lights)
            for (size_t j = 0; j < points.size(); ++j)
                irradiance[j] += tracer.LightIrradiance(light, points[j], counts);
        for (size_t j = 0; j < points.size(); ++j)
            radiance[diffuse[j]] = Tracer::Finish(points[j], irradiance[j]);
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
        }
    }
};

}  // namespace

FrameResult RenderFrame(const Tracer& tracer, const raster::Camera& camera, int k, Model model,
                        int threads, const std::function<void(int, int)>& progress) {
    FrameResult result{
        FloatImage(camera.width, camera.height, 3), FloatImage(camera.width, camera.height, 1), {}};
    std::vector<RayCounts> rowCounts(static_cast<size_t>(camera.height));
    ParallelRows(
        camera.height, threads,
        [&](int y) {
            RowTracer row{tracer, camera, k, model, {}, {}, {}, {}, {}, {}};
            row.Trace(y, result, rowCounts[static_cast<size_t>(y)]);
        },
        progress);
    for (const RayCounts& c : rowCounts) result.counts += c;
    return result;
}

ImageError CompareImages(const FloatImage& a, const FloatImage& b, const FloatImage& mask,
                         bool hdr) {
    ImageError e;
    double sum = 0.0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (!mask.data.empty() && !(mask.At(x, y)[0] > 0.0f)) continue;
            for (int c = 0; c < 3; ++c) {
                double va = a.At(x, y)[c], vb = b.At(x, y)[c];
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
