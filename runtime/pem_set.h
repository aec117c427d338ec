// SPDX-License-Identifier: MIT
// pem_set.h — a PEM directory as the run-time renderer sees it: manifest.json (written by
// `pemref infer`) and the 8-bit cube maps the hardware gets, loaded on demand.
//
//   PemSet set = LoadPemSet("out/pem");
//   const raster::Texture* t = set.Map(view, group, "layer_0");   // nullptr if absent
//
// Map names: layer_<l> (hybrid layers, l = 0 innermost, both terms), single and pem_local /
// pem_distant (mirror-only groups, PEM mode), under view_<vvv>/group_<g>/<name>.exr; the texture is
// the 8-bit copy (infer/cube_map.h ToTexture8) with the default sampler (trilinear, seamless).
// Errors: pem::InputError naming the file and the cause.
// Not here: rendering (renderer.h).
#pragma once

#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "raster/camera.h"
#include "raster/frame.h"
#include "trace/shell.h"

namespace pem::runtime {

// The single-layer PEM's shell: a sphere at the EM origin whose radius is the layers' cluster
// radii averaged with their record counts as weights (the one sphere that best stands for all
// the hits; the first radius when no layer has records).
trace::SphereShell SingleLayerShell(const glm::dvec3& emOrigin, const std::vector<double>& radii,
                                    const std::vector<int64_t>& records);

struct PemGroup {
    int index = 0;
    bool glass = false;
    glm::vec3 emOrigin{0.0f};
    std::vector<trace::Shell> layers;  // innermost first
    std::vector<uint8_t> layerEmpty;   // 1: the layer's cluster has no records (no maps)
    trace::Shell singleShell;          // SingleLayerShell of the layers
    bool pem = false;                  // mirror-only: local/distant shells
    trace::Shell localShell, distantShell;
};

struct PemSet {
    std::string dir, scenePath, traceDir;
    int width = 0, height = 0, spp = 1, res = 0;
    std::vector<raster::Camera> views;  // eye and target of every viewpoint sample
    std::vector<int> inferred;          // the samples with maps
    std::vector<PemGroup> groups;

    // The 8-bit map, loaded once; nullptr when the file does not exist.
    const raster::Texture* Map(int view, int group, const std::string& name) const;

  private:
    mutable std::map<std::string, std::unique_ptr<raster::Texture>> cache_;
};

PemSet LoadPemSet(const std::string& dir);

// trace.json / manifest.json shell objects.
trace::Shell ShellFromJson(const std::string& jsonText);

}  // namespace pem::runtime
