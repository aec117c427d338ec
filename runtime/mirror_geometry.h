// SPDX-License-Identifier: MIT
// mirror_geometry.h — the PEM paper's texgen for a mirror-only lens group (PEM §4): the model's
// own vertices, the eye ray reflected off each vertex normal, colour = Schlick's F per vertex
// with F0 = the group's material colour. Inference (pem_local / pem_distant maps) and the PEM
// renderer use this one function, so the maps are looked up as they were fitted.
//
//   const MirrorGeometry m = MakeMirrorGeometry(scene, group, camera, threads);
//   raster::Pass p = LayerPass(m.Pass(), m.order, ShellCoords(m.exits, shell, origin), ...);
//
// The local layer is drawn only on the polygons off the reflector's convex hull (a polygon on
// the hull cannot see the reflector): OffHull(m.order, HullTriangles(m.mesh)).
// Not here: the hybrid renderer's vertex paths (lens_paths.h).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "raster/camera.h"
#include "runtime/lens_paths.h"
#include "runtime/texgen.h"
#include "trace/scene.h"

namespace pem::runtime {

struct MirrorGeometry {
    LensMesh mesh;                // the group's triangles as the scene holds them
    std::vector<ExitRay> exits;   // per vertex: reflected eye ray, weight = Schlick's F
    std::vector<uint32_t> order;  // front-facing triangles in mesh order (DrawOrder)
    glm::mat4 viewProjection{1.0f};

    PassMesh Pass() const { return MeshOf(mesh); }
};

MirrorGeometry MakeMirrorGeometry(const trace::Scene& scene, int group,
                                  const raster::Camera& camera, int threads = 1);

// The triangles of `order` that are not on the hull (hull[t] == 0), in order.
std::vector<uint32_t> OffHull(const std::vector<uint32_t>& order, const std::vector<uint8_t>& hull);

}  // namespace pem::runtime
