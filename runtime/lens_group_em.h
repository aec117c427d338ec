// SPDX-License-Identifier: MIT
// lens_group_em.h — what a lens group's environment maps are drawn on: the EM origin, each
// layer's shell (innermost first) and, for mirror-only groups, the PEM paper's local and distant
// shells (PEM §4). `pemref trace` computes it (trace/layers.h); trace.json and manifest.json
// store it (pipeline/json_values.h); inference and every renderer read it from there.
//
//   const LensGroupEm& g = maps.groups[1];
//   for (const EmLayer& l : g.layers) if (!l.Empty()) ... l.shell ...
//
// Not here: the maps themselves (map_set.h), the layering (trace/layers.h).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <utility>
#include <vector>

#include "trace/shell.h"

namespace pem::runtime {

struct EmLayer {
    std::string kind;  // the shell's type: "sphere", "quad", "ellipsoid", "box", "cylinder"
    trace::Shell shell;
    double radius = 0.0;               // the LBG cluster's radius about the EM origin
    int64_t records = 0;               // traced hits in the cluster (0: the layer has no maps)
    std::vector<std::string> objects;  // scene objects whose hits the cluster holds
    double occupancy = 0.0;            // fraction of direction cells holding a record
    double parallaxDeg = 0.0;  // the shell's mean parallax over the layer's records (layers.h)
    std::vector<std::pair<std::string, double>> candidates;  // every shell tried, its parallax

    bool Empty() const { return records == 0; }
};

struct LensGroupEm {
    int index = 0;                     // the scene's lens group
    std::vector<std::string> objects;  // its objects' names
    bool glass = false;                // glass: R and T terms; otherwise R only
    glm::vec3 emOrigin{0.0f};
    std::vector<EmLayer> layers;  // innermost first
    int64_t records = 0;          // hit records over all viewpoints
    int lbgIterations = 0;
    bool lbgConverged = false;
    bool pem = false;  // mirror-only: the local/distant shells below are set
    trace::Shell localShell, distantShell;
    double localParallaxDeg = 0.0;  // the local shell's parallax over the self hits (layers.h)
    double distantMeanDistance = 0.0;

    int Terms() const { return glass ? 2 : 1; }
};

// The single-layer PEM's shell: a sphere at the EM origin whose radius is the layers' cluster
// radii averaged with their record counts as weights (the one sphere that best stands for all
// the hits; the first radius when no layer has records).
trace::SphereShell SingleLayerShell(const LensGroupEm& group);

// "R" (reflection) or "T" (transmission): the names of the two terms in file names.
const char* TermName(int term);

}  // namespace pem::runtime
