// SPDX-License-Identifier: MIT
// scene_query.cpp — what a tracer asks of a loaded Scene: lens groups (union-find over touching
// bounding boxes), cameras at other sizes and viewpoint samples, surface interpolation at a hit,
// textured material colours. Not here: loading (scene.cpp), intersection (embree_scene.h).
#include <cmath>
#include <numbers>
#include <numeric>

#include "trace/scene.h"

namespace pem::trace {

bool Overlaps(const Bounds& a, const Bounds& b) {
    return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
           a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
}

size_t Scene::NumTriangles() const {
    size_t n = 0;
    for (const Object& o : objects) n += o.triangles.size();
    return n;
}

bool Scene::IsLens(int object) const {
    return materials[static_cast<size_t>(objects[static_cast<size_t>(object)].material)].IsLens();
}

namespace {

int FindRoot(std::vector<int>& parent, int i) {
    while (parent[static_cast<size_t>(i)] != i) {
        parent[static_cast<size_t>(i)] =
            parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
        i = parent[static_cast<size_t>(i)];
    }
    return i;
}

}  // namespace

std::vector<LensGroup> FindLensGroups(const std::vector<Object>& objects,
                                      const std::vector<Material>& materials) {
    // Step 1: the lens objects.
    std::vector<int> lens;
    for (size_t i = 0; i < objects.size(); ++i)
        if (materials[static_cast<size_t>(objects[i].material)].IsLens())
            lens.push_back(static_cast<int>(i));
    // Step 2: union-find over pairs whose boxes touch, overlap or nest (O(n²); lenses are few).
    std::vector<int> parent(lens.size());
    std::iota(parent.begin(), parent.end(), 0);
    for (size_t a = 0; a < lens.size(); ++a)
        for (size_t b = a + 1; b < lens.size(); ++b)
            if (Overlaps(objects[static_cast<size_t>(lens[a])].bounds,
                         objects[static_cast<size_t>(lens[b])].bounds)) {
                const int ra = FindRoot(parent, static_cast<int>(a)),
                          rb = FindRoot(parent, static_cast<int>(b));
                parent[static_cast<size_t>(std::max(ra, rb))] = std::min(ra, rb);
            }
    // Step 3: groups in order of their first (lowest) object index.
    std::vector<LensGroup> groups;
    std::vector<int> groupOfRoot(lens.size(), -1);
    for (size_t a = 0; a < lens.size(); ++a) {
        const size_t r = static_cast<size_t>(FindRoot(parent, static_cast<int>(a)));
        if (groupOfRoot[r] < 0) {
            groupOfRoot[r] = static_cast<int>(groups.size());
            groups.emplace_back();
        }
        LensGroup& g = groups[static_cast<size_t>(groupOfRoot[r])];
        g.objects.push_back(lens[a]);
        g.bounds.Extend(objects[static_cast<size_t>(lens[a])].bounds);
    }
    return groups;
}

const Material& GroupMaterial(const Scene& scene, int group) {
    const int object = scene.lensGroups.at(static_cast<size_t>(group)).objects.at(0);
    return scene.materials.at(
        static_cast<size_t>(scene.objects[static_cast<size_t>(object)].material));
}

glm::vec3 LensCentre(const Scene& scene) {
    Bounds b;
    for (const LensGroup& g : scene.lensGroups) b.Extend(g.bounds);
    if (b.Empty())
        for (const Object& o : scene.objects) b.Extend(o.bounds);
    return b.Empty() ? glm::vec3(0.0f) : b.Center();
}

raster::Camera CameraForSize(const SceneCamera& camera, int width, int height) {
    raster::Camera c = camera.camera;
    c.width = width;
    c.height = height;
    return c;
}

raster::Camera ViewpointCamera(const Scene& scene, int k, int width, int height) {
    const Viewpoints& v = scene.viewpoints;
    raster::Camera c;
    if (scene.camera) c = scene.camera->camera;
    const double a = (static_cast<double>(v.startDeg) + k * static_cast<double>(v.stepDeg)) *
                     std::numbers::pi / 180.0;
    const double r = static_cast<double>(v.radius);
    c.eye =
        glm::vec3(static_cast<float>(static_cast<double>(v.center.x) + r * std::sin(a)), v.height,
                  static_cast<float>(static_cast<double>(v.center.z) + r * std::cos(a)));
    c.target = v.center;
    c.up = {0.0f, 1.0f, 0.0f};
    c.width = width;
    c.height = height;
    return c;
}

TriangleCorners CornersOf(const Object& object, int prim) {
    const glm::uvec3 t = object.triangles[static_cast<size_t>(prim)];
    return {{object.positions[t.x], object.positions[t.y], object.positions[t.z]},
            {object.normals[t.x], object.normals[t.y], object.normals[t.z]}};
}

SurfacePoint SurfaceAt(const TriangleCorners& c, float u, float v) {
    const float w = 1.0f - u - v;
    SurfacePoint sp;
    sp.position = w * c.p[0] + u * c.p[1] + v * c.p[2];
    const glm::vec3 n = w * c.n[0] + u * c.n[1] + v * c.n[2];
    const float len = glm::length(n);
    if (len > 0.0f) sp.normal = n / len;
    return sp;
}

SurfacePoint SurfaceAt(const Object& object, int prim, float u, float v) {
    SurfacePoint sp = SurfaceAt(CornersOf(object, prim), u, v);
    if (!object.uvs.empty()) {
        const glm::uvec3 t = object.triangles[static_cast<size_t>(prim)];
        const float w = 1.0f - u - v;
        sp.uv = w * object.uvs[t.x] + u * object.uvs[t.y] + v * object.uvs[t.z];
    }
    return sp;
}

glm::vec3 BaseColorAt(const Scene& scene, const Object& object, const SurfacePoint& sp) {
    const Material& m = scene.materials[static_cast<size_t>(object.material)];
    if (m.baseColorTexture < 0) return m.baseColor;
    return m.baseColor *
           SampleTexture(scene.textures[static_cast<size_t>(m.baseColorTexture)], sp.uv);
}

glm::vec3 EmissionAt(const Scene& scene, const Object& object, const SurfacePoint& sp) {
    const Material& m = scene.materials[static_cast<size_t>(object.material)];
    if (m.emissiveTexture < 0) return m.emission;
    return m.emission *
           SampleTexture(scene.textures[static_cast<size_t>(m.emissiveTexture)], sp.uv);
}

}  // namespace pem::trace
