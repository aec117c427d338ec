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
    GroupHits(const Tracer& tracer, int group, const Hit& seed, RayCounts& counts)
        : tracer_(tracer), group_(group), seed_(seed), counts_(counts) {}

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
    struct Exit {
        Ray ray;
        Hit hit;
    };
    const Tracer& tracer_;
    int group_;
    Hit seed_;
    bool seeded_ = true;
    RayCounts& counts_;
    std::vector<Exit> exits_;
};

SurfaceMaterial SurfaceMaterialOf(const Material& m, FresnelModel fresnel) {
    SurfaceMaterial s;
    s.kind = m.kind == MaterialKind::Glass ? SurfaceKind::Dielectric : SurfaceKind::Mirror;
    s.ior = m.ior;
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

glm::vec2 SamplePosition(int x, int y, int k, int s) {
    const float fk = static_cast<float>(k);
    const float i = static_cast<float>(s % k), j = static_cast<float>(s / k);
    return {static_cast<float>(x) + (i + 0.5f) / fk, static_cast<float>(y) + (j + 0.5f) / fk};
}

Tracer::Tracer(const Scene& scene, const EmbreeScene& embree, const TraceOptions& options)
    : scene_(scene), embree_(embree), options_(options) {
    groupOf_.assign(scene.objects.size(), -1);
    surface_.resize(scene.objects.size());
    for (size_t i = 0; i < scene.objects.size(); ++i)
        surface_[i] = SurfaceMaterialOf(
            scene.materials[static_cast<size_t>(scene.objects[i].material)], options.fresnel);
    groupHasGlass_.assign(scene.lensGroups.size(), false);
    for (size_t g = 0; g < scene.lensGroups.size(); ++g)
        for (int o : scene.lensGroups[g].objects) {
            groupOf_[static_cast<size_t>(o)] = static_cast<int>(g);
            if (surface_[static_cast<size_t>(o)].kind == SurfaceKind::Dielectric)
                groupHasGlass_[g] = true;
        }
}

int Tracer::GroupOf(int object) const {
    return groupOf_[static_cast<size_t>(object)];
}

bool Tracer::GroupHasGlass(int group) const {
    return groupHasGlass_[static_cast<size_t>(group)];
}

Hit Tracer::Intersect(const Ray& ray, RayCounts& counts, bool primary) const {
    ++(primary ? counts.primary : counts.secondary);
    return embree_.Intersect(ray, primary ? 0.0f : kSelfHitEpsilon * Scale(ray.origin));
}

std::vector<Hit> Tracer::IntersectAll(const Ray& ray, RayCounts& counts) const {
    ++counts.secondary;
    return embree_.IntersectAll(ray, kSelfHitEpsilon * Scale(ray.origin));
}

SurfaceHit Tracer::MakeSurfaceHit(const Ray& ray, const Hit& hit) const {
    const SurfacePoint sp =
        SurfaceAt(scene_.objects[static_cast<size_t>(hit.object)], hit.prim, hit.u, hit.v);
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
    GroupHits hits(*this, GroupOf(hit.object), hit, counts);
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

GreedySample Tracer::TraceGreedy(const Ray& ray, const Hit& first, int group,
                                 RayCounts& counts) const {
    GroupHits hits(*this, group, first, counts);
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

glm::vec3 Tracer::LightIrradiance(const Light& light, const DiffusePoint& dp,
                                  RayCounts& counts) const {
    glm::vec3 toLight = -light.direction;
    float distance = EmbreeScene::kInfinity;
    glm::vec3 e = light.intensity;
    if (light.kind != Light::Kind::Directional) {
        const glm::vec3 d = light.position - dp.p;
        const float d2 = glm::dot(d, d);
        if (!(d2 > 0.0f)) return glm::vec3(0.0f);
        distance = std::sqrt(d2);
        toLight = d / distance;
        e *= RangeWindow(light.range, distance) / d2;
        if (light.kind == Light::Kind::Spot) e *= SpotFactor(light, -toLight);
    }
    const float cosN = glm::dot(dp.ns, toLight);
    if (cosN <= 0.0f || glm::dot(dp.ng, toLight) <= 0.0f || e == glm::vec3(0.0f))
        return glm::vec3(0.0f);
    ++counts.shadow;
    const float tfar = light.kind == Light::Kind::Directional ? distance : distance * 0.9999f;
    if (embree_.Occluded({dp.p, toLight}, 0.0f, tfar)) return glm::vec3(0.0f);
    return e * cosN;
}

}  // namespace pem::trace
