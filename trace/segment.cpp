// SPDX-License-Identifier: MIT
// segment.cpp — per-group segmented images and hit records (segment.h).
#include "trace/segment.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "base/parallel.h"
#include "trace/confidence.h"

namespace pem::trace {

namespace {

// Slab test of a ray against a (slightly padded) box, any t >= 0.
bool RayMeetsBox(const Ray& ray, const Bounds& box) {
    const glm::vec3 pad = 1e-4f * (box.hi - box.lo) + glm::vec3(1e-5f);
    float t0 = 0.0f, t1 = EmbreeScene::kInfinity;
    for (int a = 0; a < 3; ++a) {
        const float lo = box.lo[a] - pad[a], hi = box.hi[a] + pad[a];
        if (ray.dir[a] == 0.0f) {
            if (ray.origin[a] < lo || ray.origin[a] > hi) return false;
            continue;
        }
        float ta = (lo - ray.origin[a]) / ray.dir[a], tb = (hi - ray.origin[a]) / ray.dir[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta), t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

// The first reflected ray of a mirror hit (off the surface along the facing geometric normal).
struct FirstBounce {
    Ray ray;
    glm::vec3 fresnel{0.0f};
};

FirstBounce BounceOf(const Tracer& tracer, const Ray& ray, const Hit& hit) {
    const SurfaceHit sh = tracer.MakeSurfaceHit(ray, hit);
    const Interaction in = Scatter(glm::normalize(glm::dvec3(ray.dir)), sh);
    const glm::vec3 facing = sh.entering ? sh.geometricNormal : -sh.geometricNormal;
    const float scale =
        std::max({1.0f, std::abs(sh.position.x), std::abs(sh.position.y), std::abs(sh.position.z)});
    return {{sh.position + facing * (1e-4f * scale), glm::vec3(in.reflectDir)},
            glm::vec3(in.reflectance)};
}

// Accumulators of one image row (merged in row order by SegmentGroup).
struct RowRecords {
    std::vector<HitRecord> records;
    std::vector<glm::vec3> points, origins, localOrigins, localPoints;
    double distantSum = 0.0;
    size_t distantCount = 0;
    RayCounts counts;
};

struct Segmenter {
    const Tracer& tracer;
    const raster::Camera& camera;
    int k, group;
    uint32_t viewpoint;
    glm::vec3 origin;
    GroupSegmentation& out;

    void Record(const Ray& exit, uint64_t rayId, RowRecords& row) const {
        for (const Hit& h : EnvironmentHits(tracer, exit, group, row.counts)) {
            const glm::vec3 p = exit.origin + h.t * exit.dir;
            row.records.push_back({glm::length(glm::dvec3(p) - glm::dvec3(origin)),
                                   static_cast<uint32_t>(h.object), viewpoint, rayId});
            row.points.push_back(p);
            row.origins.push_back(exit.origin);
        }
    }

    // PEM split along the first reflected ray (mirror-only groups) of the sample in `cell`.
    void MirrorSplit(const Ray& ray, const Hit& hit, int x, int y, int s, glm::ivec2 cell,
                     RowRecords& row) const {
        const FirstBounce fb = BounceOf(tracer, ray, hit);
        const int budget = tracer.options().fullTreeDepth - 1;
        const Hit h1 = tracer.Intersect(fb.ray, row.counts);
        const bool local = h1.valid && tracer.GroupOf(h1.object) == group;
        if (local)
            out.localSamples.Add(cell.x, cell.y,
                                 tracer.HitRadiance(fb.ray, h1, budget, 1.0, row.counts), 1.0f);
        if (local && s == 0) {
            row.localOrigins.push_back(fb.ray.origin);
            row.localPoints.push_back(fb.ray.origin + h1.t * fb.ray.dir);
        }
        Hit d = h1;
        if (local) {
            d = Hit{};
            for (const Hit& h : tracer.IntersectAll(fb.ray, row.counts))
                if (tracer.GroupOf(h.object) != group) {
                    d = h;
                    break;
                }
        }
        out.distantSamples.Add(cell.x, cell.y,
                               tracer.HitRadiance(fb.ray, d, budget, 1.0, row.counts), 1.0f);
        out.fresnel1.Add(x, y, fb.fresnel, 1.0f);
        if (d.valid) {
            row.distantSum +=
                glm::length(glm::dvec3(fb.ray.origin + d.t * fb.ray.dir) - glm::dvec3(origin));
            ++row.distantCount;
        }
    }

    void Pixel(int x, int y, RowRecords& row) const {
        std::vector<glm::vec3> dirs[2];
        const size_t samples = static_cast<size_t>(k * k);
        for (int t = 0; t < out.terms; ++t) dirs[t].assign(samples, glm::vec3(0.0f));
        for (int s = 0; s < k * k; ++s) {
            const glm::vec2 pos = SamplePosition(x, y, k, s);
            const glm::ivec2 cell = SampleCell(x, y, k, s);
            const Ray ray = raster::PixelRay(camera, pos.x, pos.y);
            const Hit hit = IncomingHit(tracer, ray, group, row.counts);
            if (!hit.valid) continue;
            const GreedySample g = tracer.TraceGreedy(ray, hit, group, row.counts);
            const TermSample* terms[2] = {&g.reflection, &g.refraction};
            for (int t = 0; t < out.terms; ++t) {
                const TermSample& term = *terms[t];
                out.fg[t].Add(x, y, term.F * term.G, 1.0f);
                out.bSamples[t].Add(cell.x, cell.y, term.b, 1.0f);
                if (!term.escaped) continue;
                dirs[t][static_cast<size_t>(s)] = term.exit.dir;
                const uint64_t pixel = static_cast<uint64_t>(y) * camera.width + x;
                if (s == 0) Record(term.exit, 2 * pixel + static_cast<uint64_t>(t), row);
            }
            if (out.mirror) MirrorSplit(ray, hit, x, y, s, cell, row);
        }
        for (int t = 0; t < out.terms; ++t)
            out.confidence[t].At(x, y)[0] = static_cast<float>(PixelConfidence(dirs[t]));
    }
};

}  // namespace

std::vector<Hit> EnvironmentHits(const Tracer& tracer, const Ray& ray, int group,
                                 RayCounts& counts) {
    std::vector<Hit> out;
    for (const Hit& h : tracer.IntersectAll(ray, counts)) {
        if (tracer.GroupOf(h.object) == group || glm::dot(h.ng, ray.dir) >= 0.0f) continue;
        if (!out.empty() && out.back().t == h.t && out.back().object == h.object) continue;
        out.push_back(h);
    }
    return out;
}

Hit IncomingHit(const Tracer& tracer, const Ray& ray, int group, RayCounts& counts) {
    if (!RayMeetsBox(ray, tracer.scene().lensGroups[static_cast<size_t>(group)].bounds))
        return Hit{};
    const Hit hit = tracer.Intersect(ray, counts, true);
    if (hit.valid && tracer.GroupOf(hit.object) == group) return hit;
    if (!hit.valid) return Hit{};
    for (const Hit& h : tracer.IntersectAll(ray, counts))
        if (tracer.GroupOf(h.object) == group) return h;
    return Hit{};
}

GroupSegmentation SegmentGroup(const Tracer& tracer, const raster::Camera& camera, int k, int group,
                               uint32_t viewpoint, const glm::vec3& emOrigin, int threads,
                               const std::function<void(int, int)>& progress) {
    GroupSegmentation out;
    out.group = group;
    out.terms = tracer.GroupHasGlass(group) ? 2 : 1;
    out.mirror = !tracer.GroupHasGlass(group);
    const int w = camera.width, h = camera.height;
    for (int t = 0; t < out.terms; ++t) {
        out.bSamples[t] = FloatImage(k * w, k * h, 4);
        out.fg[t] = FloatImage(w, h, 4);
        out.confidence[t] = FloatImage(w, h, 1);
    }
    if (out.mirror) {
        out.localSamples = FloatImage(k * w, k * h, 4);
        out.distantSamples = FloatImage(k * w, k * h, 4);
        out.fresnel1 = FloatImage(w, h, 4);
    }
    std::vector<RowRecords> rows(static_cast<size_t>(h));
    const Segmenter seg{tracer, camera, k, group, viewpoint, emOrigin, out};
    base::ParallelFor(
        h, threads,
        [&](int y) {
            for (int x = 0; x < w; ++x) seg.Pixel(x, y, rows[static_cast<size_t>(y)]);
        },
        progress);
    // Box filter, then merge the rows' records in row order.
    const float inv = 1.0f / static_cast<float>(k * k);
    for (FloatImage* img : {&out.fg[0], &out.fg[1], &out.fresnel1}) img->Scale(inv);
    for (int t = 0; t < out.terms; ++t) out.b[t] = BoxFilter(out.bSamples[t], k);
    if (out.mirror) {
        out.local = BoxFilter(out.localSamples, k);
        out.distant = BoxFilter(out.distantSamples, k);
    }
    for (RowRecords& r : rows) {
        out.records.insert(out.records.end(), r.records.begin(), r.records.end());
        out.recordPoints.insert(out.recordPoints.end(), r.points.begin(), r.points.end());
        out.recordOrigins.insert(out.recordOrigins.end(), r.origins.begin(), r.origins.end());
        out.localOrigins.insert(out.localOrigins.end(), r.localOrigins.begin(),
                                r.localOrigins.end());
        out.localPoints.insert(out.localPoints.end(), r.localPoints.begin(), r.localPoints.end());
        out.distantDistanceSum += r.distantSum;
        out.distantCount += r.distantCount;
        out.counts += r.counts;
    }
    return out;
}

}  // namespace pem::trace
