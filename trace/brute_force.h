// SPDX-License-Identifier: MIT
// brute_force.h — O(n) ray/triangle intersection over every triangle of a Scene: Möller–Trumbore
// in double precision. The oracle for embree_scene.h in tests, and the readable version of what
// the BVH computes.
//
// Semantics (same as EmbreeScene): hits with tnear <= t <= tfar, two-sided, edges inclusive
// (0 <= u, 0 <= v, u + v <= 1), a triangle whose plane contains the ray is missed. Nearest hit
// = smallest t; on an exact tie the lowest (object, prim) wins (Embree's tie winner is
// unspecified, so tests compare ties loosely). Hit fields as in hit.h, computed in double and
// rounded to float.
// Not here: acceleration of any kind.
#pragma once

#include <vector>

#include "raster/camera.h"
#include "trace/hit.h"
#include "trace/scene.h"

namespace pem::trace {

Hit BruteForceIntersect(const Scene& scene, const raster::Ray& ray, float tnear, float tfar);
bool BruteForceOccluded(const Scene& scene, const raster::Ray& ray, float tnear, float tfar);
// Every hit, sorted by (t, object, prim).
std::vector<Hit> BruteForceIntersectAll(const Scene& scene, const raster::Ray& ray, float tnear,
                                        float tfar);

}  // namespace pem::trace
