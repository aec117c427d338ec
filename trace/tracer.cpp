// SPDX-License-Identifier: MIT
// tracer.cpp — shading, the lens-group SurfaceHitFn, full tree and greedy radiance (tracer.h).
#include "trace/tracer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace pem::trace {

namespace {

// Shadow rays start this far (× max(1, |p|∞)) off the surface along the geometric normal.
constexpr float kShadowOffset = 1e-4f;

float Scale(const glm::vec3& p) {
    return std::max({1.0f, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

double MaxOf(const glm::dvec3& v) {
    return std::max({v.x, v.y, v.z});
}

// ray_path.h's view of one lens group: the nearest scene hit if it is one of the group's
// objects, otherwise the ray has left the local system (and what it hit is kept, so the exit
// ray's radiance needs no second intersection). The first query may be answered by a seed hit
// (the camera ray's hit, possibly behind occluders).
class GroupHits final : public SurfaceHitFn {
  public:
    using Exit = Tracer::RadianceTape::Exit;

    // `exits` is the caller's buffer (cleared here).
    GroupHits(const Tracer& tracer, int group, const Hit& seed, RayCounts& counts,
              std::vector<Exit>& exits)
        : tracer_(tracer), group_(group), seed_(seed), counts_(counts), exits_(exits) {
        exits_.clear();
    }

    std::optional<SurfaceHit> Next(const Ray& ray) override {
        Hit hit = seed_;
        if (seeded_) {
            seeded_ = false;
        } else {
            hit = tracer_.Intersect(ray, counts_);
        }
        if (hit.valid && tracer_.GroupOf(hit.object) == group_)
            return tracer_.MakeSurfaceHit(ray, hit);
        exits_.push_back({ray, hit});
        return std::nullopt;
    }

    // What an exit ray (one that Next() answered with nullopt) hit.
    Hit ExitHit(const Ray& ray) {
        for (auto it = exits_.rbegin(); it != exits_.rend(); ++it)
            if (it->ray == ray) return it->hit;
        return tracer_.Intersect(ray, counts_);
    }

  private:
    const Tracer& tracer_;
    int group_;
    Hit seed_;
    bool seeded_ = true;
    RayCounts& counts_;
    std::vector<Exit>& exits_;
};

SurfaceMaterial SurfaceMaterialOf(const Material& m, FresnelModel fresnel) {
    SurfaceMaterial s;
    s.kind = m.kind == MaterialKind::Glass ? SurfaceKind::Dielectric : SurfaceKind::Mirror;
    s.ior = static_cast<double>(m.ior);
    s.absorption = glm::dvec3(m.absorption);
    s.mirrorF0 = glm::dvec3(m.baseColor);
    s.fresnel = fresnel;
    return s;
}

// glTF KHR_lights_punctual range window: (1 − (d/range)^4)^2 clamped, 1 for an infinite range.
float RangeWindow(float range, float distance) {
    if (range <= 0.0f) return 1.0f;
    const float r = distance / range;
    const float w = std::clamp(1.0f - r * r * r * r, 0.0f, 1.0f);
    return w * w;
}

// glTF spot cone: smooth falloff between the outer and inner cone angles.
float SpotFactor(const Light& light, const glm::vec3& toSurface) {
    const float cosOuter = std::cos(light.outerCone);
    const float scale = 1.0f / std::max(0.001f, std::cos(light.innerCone) - cosOuter);
    const float t =
        std::clamp((glm::dot(toSurface, light.direction) - cosOuter) * scale, 0.0f, 1.0f);
    return t * t;
}

}  // namespace

glm::vec2 SampleOffset(int k, int s) {
    const float fk = static_cast<float>(k);
    const float i = static_cast<float>(s % k), j = static_cast<float>(s / k);
    return {(i + 0.5f) / fk, (j + 0.5f) / fk};
}

glm::vec2 SamplePosition(int x, int y, int k, int s) {
    const glm::vec2 o = SampleOffset(k, s);
    return {static_cast<float>(x) + o.x, static_cast<float>(y) + o.y};
}

Tracer::Tracer(const Scene& scene, const EmbreeScene& embree, const TraceOptions& options)
    : scene_(scene), embree_(embree), options_(options) {
    groupOf_.assign(scene.objects.size(), -1);
    surface_.resize(scene.objects.size());
    for (size_t i = 0; i < scene.objects.size(); ++i)
        surface_[i] = SurfaceMaterialOf(
            scene.materials[static_cast<size_t>(scene.objects[i].material)], options.fresnel);
    groupHasGlass_.assign(scene.lensGroups.size(), false);
    lensCorners_.resize(scene.objects.size());
    for (size_t g = 0; g < scene.lensGroups.size(); ++g)
        for (int o : scene.lensGroups[g].objects) {
            groupOf_[static_cast<size_t>(o)] = static_cast<int>(g);
            const Object& obj = scene.objects[static_cast<size_t>(o)];
            std::vector<TriangleCorners>& corners = lensCorners_[static_cast<size_t>(o)];
            corners.reserve(obj.triangles.size());
            for (size_t t = 0; t < obj.triangles.size(); ++t)
                corners.push_back(CornersOf(obj, static_cast<int>(t)));
            if (surface_[static_cast<size_t>(o)].kind == SurfaceKind::Dielectric)
                groupHasGlass_[g] = true;
        }
}

bool Tracer::GroupHasGlass(int group) const {
    return groupHasGlass_[static_cast<size_t>(group)];
}

Hit Tracer::Intersect(const Ray& ray, RayCounts& counts, bool primary) const {
    ++(primary ? counts.primary : counts.secondary);
    return embree_.Intersect(ray, primary ? 0.0f : kSelfHitEpsilon * Scale(ray.origin));
}

void Tracer::IntersectCamera(std::span<const Ray> rays, std::span<Hit> hits,
                             RayCounts& counts) const {
    constexpr size_t kN = EmbreeScene::kPacketSize;
    RayQuery queries[kN];
    for (size_t base = 0; base < rays.size(); base += kN) {
        const size_t m = std::min(kN, rays.size() - base);
        for (size_t i = 0; i < m; ++i) queries[i] = {rays[base + i], 0.0f, EmbreeScene::kInfinity};
        embree_.IntersectPacket8({queries, m}, hits.subspan(base, m));
    }
    counts.primary += rays.size();
}

std::vector<Hit> Tracer::IntersectAll(const Ray& ray, RayCounts& counts) const {
    ++counts.secondary;
    return embree_.IntersectAll(ray, kSelfHitEpsilon * Scale(ray.origin));
}

SurfaceHit Tracer::MakeSurfaceHit(const Ray& ray, const Hit& hit) const {
    // SurfaceAt on the packed corners (the same values; fewer cache misses).
    const std::vector<TriangleCorners>& corners = lensCorners_[static_cast<size_t>(hit.object)];
    const SurfacePoint sp =
        corners.empty()
            ? SurfaceAt(scene_.objects[static_cast<size_t>(hit.object)], hit.prim, hit.u, hit.v)
            : SurfaceAt(corners[static_cast<size_t>(hit.prim)], hit.u, hit.v);
    SurfaceHit s;
    s.t = hit.t;
    s.position = sp.position;
    s.geometricNormal = hit.ng;
    s.shadingNormal = sp.normal;
    s.material = surface_[static_cast<size_t>(hit.object)];
    s.entering = glm::dot(ray.dir, hit.ng) < 0.0f;
    s.objectId = static_cast<uint32_t>(hit.object);
    s.primId = static_cast<uint32_t>(hit.prim);
    return s;
}

glm::vec3 Tracer::Radiance(const Ray& cameraRay, RayCounts& counts) const {
    const Hit hit = Intersect(cameraRay, counts, true);
    return HitRadiance(cameraRay, hit, options_.fullTreeDepth, 1.0, counts);
}

glm::vec3 Tracer::GreedyRadiance(const Ray& cameraRay, RayCounts& counts) const {
    const Hit hit = Intersect(cameraRay, counts, true);
    if (hit.valid && GroupOf(hit.object) >= 0)
        return TraceGreedy(cameraRay, hit, GroupOf(hit.object), counts).Radiance();
    return HitRadiance(cameraRay, hit, options_.fullTreeDepth, 1.0, counts);
}

glm::vec3 Tracer::HitRadiance(const Ray& ray, const Hit& hit, int depthBudget, double weight,
                              RayCounts& counts) const {
    if (!hit.valid) return EnvRadiance(scene_.environment, ray.dir);
    if (GroupOf(hit.object) < 0) return ShadeDiffuse(ray, hit, counts);
    if (depthBudget <= 0) return glm::vec3(0.0f);
    return LensRadiance(ray, hit, depthBudget, weight, counts);
}

glm::vec3 Tracer::LensRadiance(const Ray& ray, const Hit& hit, int depthBudget, double weight,
                               RayCounts& counts) const {
    std::vector<GroupHits::Exit> exits;
    GroupHits hits(*this, GroupOf(hit.object), hit, counts, exits);
    const std::vector<ExitRay> leaves =
        TraceFullTree(ray, hits, depthBudget, options_.minWeight / weight);
    glm::vec3 sum(0.0f);
    for (const ExitRay& leaf : leaves) {
        if (!leaf.escaped) continue;  // cut by depth or weight: black
        const Hit exitHit = hits.ExitHit(leaf.ray);
        const glm::vec3 l = HitRadiance(leaf.ray, exitHit, depthBudget - leaf.depth,
                                        weight * MaxOf(leaf.weight), counts);
        sum += glm::vec3(leaf.weight) * l;
    }
    return sum;
}

void Tracer::RecordHitRadiance(const Ray& ray, const Hit& hit, int depthBudget, double weight,
                               RadianceTape& tape, RayCounts& counts) const {
    RecordHitRadiance(ray, hit, depthBudget, weight, tape, 0, counts);
}

void Tracer::RecordHitRadiance(const Ray& ray, const Hit& hit, int depthBudget, double weight,
                               RadianceTape& tape, size_t level, RayCounts& counts) const {
    using Op = RadianceTape::Op;
    // HitRadiance, step by step.
    if (!hit.valid) {
        tape.ops.push_back({Op::Value, 0, EnvRadiance(scene_.environment, ray.dir)});
        return;
    }
    if (GroupOf(hit.object) < 0) {
        tape.ops.push_back({Op::Diffuse, static_cast<uint32_t>(tape.points.size()), {}});
        tape.points.push_back(DiffuseAt(ray, hit));
        return;
    }
    if (depthBudget <= 0) {
        tape.ops.push_back({Op::Value, 0, glm::vec3(0.0f)});
        return;
    }
    // LensRadiance: sum = 0; sum += vec3(leaf.weight) * l per escaped leaf, in leaf order.
    if (tape.levels.size() <= level) tape.levels.resize(level + 1);
    RadianceTape::Level& scratch = tape.levels[level];
    GroupHits hits(*this, GroupOf(hit.object), hit, counts, scratch.exits);
    TraceFullTree(ray, hits, depthBudget, options_.minWeight / weight, scratch.leaves);
    tape.ops.push_back({Op::BeginSum, 0, {}});
    for (const ExitRay& leaf : scratch.leaves) {
        if (!leaf.escaped) continue;
        const Hit exitHit = hits.ExitHit(leaf.ray);
        RecordHitRadiance(leaf.ray, exitHit, depthBudget - leaf.depth, weight * MaxOf(leaf.weight),
                          tape, level + 1, counts);
        tape.ops.push_back({Op::AddWeighted, 0, glm::vec3(leaf.weight)});
    }
}

glm::vec3 Tracer::EvalTape(std::span<const RadianceTape::Entry> ops,
                           std::span<const DiffusePoint> points,
                           std::span<const glm::vec3> irradiance, std::vector<glm::vec3>& stack) {
    using Op = RadianceTape::Op;
    stack.clear();
    for (const RadianceTape::Entry& e : ops) {
        switch (e.op) {
            case Op::Value:
                stack.push_back(e.v);
                break;
            case Op::Diffuse:
                stack.push_back(Finish(points[e.point], irradiance[e.point]));
                break;
            case Op::BeginSum:
                stack.push_back(glm::vec3(0.0f));
                break;
            case Op::AddWeighted: {
                const glm::vec3 l = stack.back();
                stack.pop_back();
                stack.back() += e.v * l;
                break;
            }
        }
    }
    return stack.back();
}

GreedySample Tracer::TraceGreedy(const Ray& ray, const Hit& first, int group,
                                 RayCounts& counts) const {
    std::vector<GroupHits::Exit> exits;
    GroupHits hits(*this, group, first, counts, exits);
    const std::optional<GreedyPaths> paths =
        TraceGreedyPaths(ray, hits, options_.fullTreeDepth, options_.minWeight);
    GreedySample sample;
    if (!paths) return sample;  // the seed was not a hit of the group
    auto term = [&](const RayPath& path, TermSample& t) {
        t.F = glm::vec3(path.F);
        t.G = glm::vec3(path.G);
        t.events = static_cast<int>(path.vertices.size());
        t.escaped = path.escaped;
        if (!path.escaped) return;
        t.exit = {path.exitOrigin, path.exitDir};
        t.exitHit = hits.ExitHit(t.exit);
        t.b = HitRadiance(t.exit, t.exitHit, options_.fullTreeDepth - t.events,
                          std::max(1e-30, MaxOf(path.Weight())), counts);
    };
    term(paths->reflection, sample.reflection);
    term(paths->refraction, sample.refraction);
    return sample;
}

std::optional<GreedyPaths> Tracer::GreedyPathsAt(const Ray& ray, const Hit& first, int group,
                                                 RayCounts& counts) const {
    thread_local std::vector<GroupHits::Exit> exits;  // not read here: kept to save allocations
    GroupHits hits(*this, group, first, counts, exits);
    return TraceGreedyPaths(ray, hits, options_.fullTreeDepth, options_.minWeight);
}

Tracer::DiffusePoint Tracer::DiffuseAt(const Ray& ray, const Hit& hit) const {
    const Object& obj = scene_.objects[static_cast<size_t>(hit.object)];
    const SurfacePoint sp = SurfaceAt(obj, hit.prim, hit.u, hit.v);
    DiffusePoint dp;
    dp.albedo = BaseColorAt(scene_, obj, sp);
    dp.base = EmissionAt(scene_, obj, sp) + dp.albedo * options_.ambient;
    // Both normals on the side the ray comes from.
    dp.ng = glm::dot(hit.ng, ray.dir) > 0.0f ? -hit.ng : hit.ng;
    dp.ns = glm::dot(sp.normal, dp.ng) < 0.0f ? -sp.normal : sp.normal;
    dp.p = sp.position + dp.ng * (kShadowOffset * Scale(sp.position));
    return dp;
}

glm::vec3 Tracer::Finish(const DiffusePoint& dp, const glm::vec3& irradiance) {
    return dp.base + dp.albedo * irradiance * static_cast<float>(1.0 / std::numbers::pi);
}

glm::vec3 Tracer::ShadeDiffuse(const Ray& ray, const Hit& hit, RayCounts& counts) const {
    const DiffusePoint dp = DiffuseAt(ray, hit);
    glm::vec3 irradiance(0.0f);
    for (const Light& light : scene_.lights) irradiance += LightIrradiance(light, dp, counts);
    return Finish(dp, irradiance);
}

bool Tracer::PrepareLight(const Light& light, const DiffusePoint& dp, RayQuery* shadow,
                          glm::vec3* value) const {
    glm::vec3 toLight = -light.direction;
    float distance = EmbreeScene::kInfinity;
    glm::vec3 e = light.intensity;
    if (light.kind != Light::Kind::Directional) {
        const glm::vec3 d = light.position - dp.p;
        const float d2 = glm::dot(d, d);
        if (!(d2 > 0.0f)) return false;
        distance = std::sqrt(d2);
        toLight = d / distance;
        e *= RangeWindow(light.range, distance) / d2;
        if (light.kind == Light::Kind::Spot) e *= SpotFactor(light, -toLight);
    }
    const float cosN = glm::dot(dp.ns, toLight);
    if (cosN <= 0.0f || glm::dot(dp.ng, toLight) <= 0.0f || e == glm::vec3(0.0f)) return false;
    shadow->ray.origin = dp.p;
    shadow->ray.dir = toLight;
    shadow->tnear = 0.0f;
    shadow->tfar = light.kind == Light::Kind::Directional ? distance : distance * 0.9999f;
    *value = e * cosN;
    return true;
}

glm::vec3 Tracer::LightIrradiance(const Light& light, const DiffusePoint& dp,
                                  RayCounts& counts) const {
    RayQuery shadow;
    glm::vec3 value;
    if (!PrepareLight(light, dp, &shadow, &value)) return glm::vec3(0.0f);
    ++counts.shadow;
    if (embree_.Occluded(shadow.ray, shadow.tnear, shadow.tfar)) return glm::vec3(0.0f);
    return value;
}

void Tracer::AddLightIrradiance(const Light& light, std::span<const DiffusePoint> points,
                                std::span<glm::vec3> irradiance, RayCounts& counts) const {
    constexpr size_t kN = EmbreeScene::kPacketSize;
    RayQuery queries[kN];
    glm::vec3 values[kN];
    size_t target[kN];
    size_t m = 0;
    auto flush = [&] {
        const unsigned occluded = embree_.OccludedPacket8({queries, m});
        for (size_t i = 0; i < m; ++i)
            irradiance[target[i]] += (occluded >> i) & 1u ? glm::vec3(0.0f) : values[i];
        counts.shadow += m;
        m = 0;
    };
    for (size_t j = 0; j < points.size(); ++j) {
        if (!PrepareLight(light, points[j], &queries[m], &values[m])) {
            irradiance[j] += glm::vec3(0.0f);  // as LightIrradiance's zero (keeps -0 → +0)
            continue;
        }
        target[m] = j;
        if (++m == kN) flush();
    }
    if (m > 0) flush();
}

}  // namespace pem::trace
