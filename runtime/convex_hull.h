// SPDX-License-Identifier: MIT
// convex_hull.h — which triangles of a reflector lie on its convex hull (PEM §4: a polygon on
// the hull cannot see the object itself, so it needs only the distant layer; a reflector whose
// every polygon is on the hull needs no local layer at all).
//
//   std::vector<uint8_t> hull = HullTriangles(mesh);     // 1: on the hull
//   bool convex = AllOnHull(hull);
//
// A triangle is on the hull when no vertex of the mesh lies in front of its plane by more than
// tolerance × the mesh's bounding-box diagonal (double arithmetic; degenerate triangles count
// as on the hull). O(triangles × vertices), with an early exit per triangle.
// Not here: building hulls, rendering (renderer.h), the inference's choice (pipeline/infer_job.h).
#pragma once

#include <cstdint>
#include <vector>

#include "runtime/lens_paths.h"

namespace pem::runtime {

std::vector<uint8_t> HullTriangles(const LensMesh& mesh, double tolerance = 1e-4);
bool AllOnHull(const std::vector<uint8_t>& hull);

}  // namespace pem::runtime
