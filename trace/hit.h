// SPDX-License-Identifier: MIT
// hit.h — the result of intersecting one ray with a trace::Scene (Embree or brute force).
//
// Conventions:
//  - t is the ray parameter: hit point = origin + t · dir (dir need not be unit length).
//  - object indexes Scene::objects (= Embree geomID), prim indexes Object::triangles.
//  - (u, v) are Embree's barycentrics: p = (1 − u − v)·v0 + u·v1 + v·v2.
//  - ng is the UNIT geometric normal along (v1 − v0) × (v2 − v0), i.e. it points to the side from
//    which the triangle winds counter-clockwise (the outside of a glTF mesh, scene.h).
//  - A miss has valid == false and the other fields at their defaults.
// Not here: shading normals, uv interpolation (scene.h: SurfaceAt).
#pragma once

#include <glm/glm.hpp>
#include <limits>

namespace pem::trace {

struct Hit {
    float t = std::numeric_limits<float>::infinity();
    int object = -1;
    int prim = -1;
    float u = 0.0f, v = 0.0f;
    glm::vec3 ng{0.0f};
    bool valid = false;
    bool operator==(const Hit&) const = default;
};

}  // namespace pem::trace
