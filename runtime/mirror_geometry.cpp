// SPDX-License-Identifier: MIT
// mirror_geometry.cpp — PEM-mode texgen geometry (mirror_geometry.h).
#include "runtime/mirror_geometry.h"

namespace pem::runtime {

MirrorGeometry MakeMirrorGeometry(const trace::Scene& scene, int group,
                                  const raster::Camera& camera, int threads) {
    MirrorGeometry m;
    m.mesh = GroupMesh(scene, group);
    const PassMesh pass = m.Pass();
    m.exits = ReflectionExits(pass, camera.eye, trace::GroupMaterial(scene, group).baseColor);
    m.order = DrawOrder(pass, camera, threads);
    m.viewProjection = PassViewProjection(pass, camera);
    return m;
}

std::vector<uint32_t> OffHull(const std::vector<uint32_t>& order,
                              const std::vector<uint8_t>& hull) {
    std::vector<uint32_t> inner;
    for (uint32_t t : order)
        if (!hull[t]) inner.push_back(t);
    return inner;
}

}  // namespace pem::runtime
