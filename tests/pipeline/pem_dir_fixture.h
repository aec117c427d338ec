// SPDX-License-Identifier: MIT
// pem_dir_fixture.h — a small PEM directory for the tests of its readers: the mirror sphere
// scene copied beside it, one viewpoint sample, one map.
#pragma once

#include "infer/pem_file.h"
#include "pipeline/layout.h"
#include "pipeline/pem_manifest.h"
#include "tests/pipeline/pipeline_test_util.h"
#include "trace/scene.h"

namespace pem::pipeline {

// A cube map of face size n, every level and texel (r, g, b, a).
inline infer::EnvMapF ConstantMap(int n, float r, float g, float b, float a) {
    infer::EnvMapF m;
    m.size = n;
    for (int s = n; s >= 1; s /= 2) {
        std::vector<float>& level = m.levels.emplace_back();
        for (int k = 0; k < 6 * s * s; ++k) level.insert(level.end(), {r, g, b, a});
    }
    return m;
}

// dir/scene and dir/env (the mirror sphere and its sky), dir/pem with one sample whose map is
// `pem_distant`.
inline PemManifest MakePemDir(const fs::path& dir) {
    fs::create_directories(dir / "scene");
    fs::create_directories(dir / "env");
    fs::copy_file(kRoot + "/data/scenes/mirror_sphere.gltf", dir / "scene" / "m.gltf");
    fs::copy_file(kRoot + "/data/scenes/mirror_sphere.bin", dir / "scene" / "mirror_sphere.bin");
    fs::copy_file(kRoot + "/data/env/sky.exr", dir / "env" / "sky.exr");
    TraceManifest t;
    t.dir = (dir / "trace").string();
    t.scene = SceneForStorage(t.dir, (dir / "scene" / "m.gltf").string());
    t.sceneGiven = "m.gltf";
    t.width = 32, t.height = 24, t.spp = 1;
    const trace::Scene scene = trace::LoadScene(kMirrorSphere);
    const raster::Camera c = trace::CameraForSize(*scene.camera, 32, 24);
    t.views = {{c, 0, 0, {}, {}, {}, {}, {}, {}, {}, {}}};
    runtime::LensGroupEm g;
    g.objects = {"mirror_sphere"};
    g.layers = {{"sphere", trace::SphereShell{{0.0, 0.5, 0.0}, 5.0}, 5.0, 10, {}, 1.0, 0.0, {}}};
    g.pem = true;
    g.localShell = trace::EllipsoidShell{{0.0, 0.5, 0.0}, {0.6, 0.6, 0.6}};
    g.distantShell = trace::BoxShell{{-5.0, -0.5, -5.0}, {5.0, 4.0, 5.0}};
    t.groups = {g};
    PemManifest m = PemManifestFor(t, (dir / "pem").string(), 8, false, {});
    fs::create_directories(GroupDir(m.dir, 0, 0));
    WritePemManifest(m);
    infer::WriteEnvMapExr(ConstantMap(8, 0.5f, 0.25f, 1.0f, 1.0f),
                          MapPath(m.dir, 0, 0, "pem_distant"));
    return m;
}

}  // namespace pem::pipeline
