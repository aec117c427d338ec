// SPDX-License-Identifier: MIT
// scene.h — a glTF 2.0 scene flattened for ray tracing: world-space triangle meshes, materials,
// the camera, punctual lights, the environment and the lens groups.
//
// Conventions:
//  - One Object per (node, mesh primitive) instance, in scene traversal order (depth first,
//    children in file order). Positions and normals are in WORLD space: normals transformed
//    with the inverse transpose of the node's world matrix and renormalized; when a node's
//    matrix mirrors (det < 0) each triangle's winding is swapped so triangles stay
//    counter-clockwise seen from the side their normals point to.
//  - A primitive without NORMAL gets flat normals (its vertices are split per triangle).
//  - Triangles (mode 4), strips (5) and fans (6) are read; points and lines (modes 0–3) are
//    skipped with a note. Zero-area triangles are dropped and counted (Scene::droppedDegenerate).
//  - Materials: material.h. Primitives without a material use a default diffuse material
//    (appended to Scene::materials, named "default").
//  - Lens objects are the objects whose material is mirror or glass. Lens groups are the
//    connected components of "bounding boxes touch, overlap or nest".
//  - Camera: the first node (traversal order) with a perspective camera; looks down its local −Z
//    with +Y up. Default image size: 480 rows, width = round(480 · aspectRatio) (640 × 480 for
//    4:3); CameraForSize picks another size. `pemref_look_at` (node extras) sets the target
//    distance. Without a camera node, hasCamera is false.
//  - Lights: KHR_lights_punctual; colour × intensity (cd for point/spot, lux for directional).
// Errors: every malformed or unsupported input throws pem::base::InputError with one line
// "<gltf path>: <cause>" (base/input_error.h).
// Not here: animation, skins and morph targets (ignored with a note), Draco/meshopt (rejected),
// ray intersection (embree_scene.h, brute_force.h).
#pragma once

#include <glm/glm.hpp>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "raster/camera.h"
#include "trace/environment.h"
#include "trace/material.h"

namespace pem::trace {

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    bool operator==(const Bounds&) const = default;

    bool Empty() const { return lo.x > hi.x; }
    void Extend(const glm::vec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
    void Extend(const Bounds& b) { lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi); }
    glm::vec3 Center() const { return 0.5f * (lo + hi); }
};

// Closed boxes: touching faces count as overlapping, and so does nesting.
bool Overlaps(const Bounds& a, const Bounds& b);

struct Object {
    std::string name;  // node name (or "node<i>"), plus "#<p>" when the mesh has > 1 primitive
    int node = -1, mesh = -1, primitive = -1;  // where it came from in the glTF
    int material = -1;                         // Scene::materials index (always valid)
    bool lensRole = false;                     // node extras pemref_role == "lens"
    std::vector<glm::vec3> positions;          // world space
    std::vector<glm::vec3> normals;            // world space, unit, one per position
    std::vector<glm::vec2> uvs;                // TEXCOORD_0, empty when absent
    std::vector<glm::uvec3> triangles;         // indices into positions, CCW from outside
    Bounds bounds;                             // of the positions used by triangles
    bool operator==(const Object&) const = default;
};

struct Light {
    enum class Kind { Point, Spot, Directional };
    std::string name;
    Kind kind = Kind::Point;
    glm::vec3 position{0.0f};                // world (point, spot)
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world, unit, the way light travels (spot, dir.)
    glm::vec3 intensity{1.0f};               // colour × intensity
    float range = 0.0f;                      // 0 = infinite
    float innerCone = 0.0f, outerCone = 0.785398163f;  // spot only, radians
    bool operator==(const Light&) const = default;
};

struct SceneCamera {
    std::string name;
    raster::Camera camera;  // at the default size (see above)
    float aspect = 1.0f;    // from the glTF (or 1 when absent)
    float zNear = 0.05f, zFar = 1000.0f;
    bool operator==(const SceneCamera&) const = default;
};

// scenes[0].extras.pemref_viewpoints (data/README.md): a circle of eyes looking at `center`.
struct Viewpoints {
    glm::vec3 center{0.0f};
    float radius = 0.0f, height = 0.0f, startDeg = 0.0f, stepDeg = 0.0f;
    int count = 0;  // 0: none given
    bool operator==(const Viewpoints&) const = default;
};

struct LensGroup {
    std::vector<int> objects;  // ascending Scene::objects indices
    Bounds bounds;
    bool operator==(const LensGroup&) const = default;
};

struct Scene {
    std::string path;
    std::vector<Object> objects;
    std::vector<Material> materials;
    std::vector<Texture2D> textures;
    std::vector<Light> lights;
    std::optional<SceneCamera> camera;
    Viewpoints viewpoints;
    Environment environment;
    std::vector<LensGroup> lensGroups;
    int droppedDegenerate = 0;       // zero-area triangles removed at load
    std::vector<std::string> notes;  // what was skipped or approximated, one line each
    bool operator==(const Scene&) const = default;

    size_t NumTriangles() const;
    bool IsLens(int object) const;
};

// Loads a .gltf or .glb file (tinygltf). Throws pem::base::InputError on any bad input.
Scene LoadScene(const std::string& gltfPath);

// Lens groups of a set of objects (used by LoadScene; exposed for tests).
std::vector<LensGroup> FindLensGroups(const std::vector<Object>& objects,
                                      const std::vector<Material>& materials);

// The material of a lens group's first object (the groups's objects are of one kind: a
// mirror-only group's F0 is its first mirror's base colour).
const Material& GroupMaterial(const Scene& scene, int group);

// Centre of all lens objects' bounds (the scene bounds' centre without lenses).
glm::vec3 LensCentre(const Scene& scene);

// The scene camera at another image size (same eye, target, up, fovY).
raster::Camera CameraForSize(const SceneCamera& camera, int width, int height);

// Viewpoint sample k (0 <= k < count) at the given size, using the scene camera's fovY.
raster::Camera ViewpointCamera(const Scene& scene, int k, int width, int height);

// Interpolated surface data at a hit (barycentrics u, v of triangle prim).
struct SurfacePoint {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};  // interpolated shading normal, unit
    glm::vec2 uv{0.0f};                  // (0, 0) without TEXCOORD_0
};
SurfacePoint SurfaceAt(const Object& object, int prim, float u, float v);

// A triangle's corner positions and normals, copied out of an Object (so a tracer can keep the
// lens triangles packed: one or two cache lines per hit instead of seven scattered loads).
struct TriangleCorners {
    glm::vec3 p[3];
    glm::vec3 n[3];
};
TriangleCorners CornersOf(const Object& object, int prim);
// SurfaceAt's position and normal (not uv) from the corners: the same values bit for bit.
SurfacePoint SurfaceAt(const TriangleCorners& corners, float u, float v);

// Material colour terms at a surface point (textures applied).
glm::vec3 BaseColorAt(const Scene& scene, const Object& object, const SurfacePoint& sp);
glm::vec3 EmissionAt(const Scene& scene, const Object& object, const SurfacePoint& sp);

}  // namespace pem::trace
