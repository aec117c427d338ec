// SPDX-License-Identifier: MIT
// convex_hull.cpp — triangles on a mesh's convex hull (convex_hull.h).
#include "runtime/convex_hull.h"

#include <algorithm>

namespace pem::runtime {

std::vector<uint8_t> HullTriangles(const LensMesh& mesh, double tolerance) {
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, glm::dvec3(p));
        hi = glm::max(hi, glm::dvec3(p));
    }
    const double eps = tolerance * (mesh.positions.empty() ? 0.0 : glm::length(hi - lo));
    std::vector<uint8_t> hull(mesh.triangles.size(), 1);
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::uvec3 tri = mesh.triangles[t];
        const glm::dvec3 a(mesh.positions[tri.x]), b(mesh.positions[tri.y]),
            c(mesh.positions[tri.z]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double len = glm::length(n);
        if (!(len > 0.0)) continue;
        const glm::dvec3 u = n / len;
        for (const glm::vec3& p : mesh.positions)
            if (glm::dot(glm::dvec3(p) - a, u) > eps) {
                hull[t] = 0;
                break;
            }
    }
    return hull;
}

bool AllOnHull(const std::vector<uint8_t>& hull) {
    return std::all_of(hull.begin(), hull.end(), [](uint8_t h) { return h != 0; });
}

}  // namespace pem::runtime
