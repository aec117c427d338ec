// SPDX-License-Identifier: MIT
// lens_group_em.cpp — the single-layer shell (lens_group_em.h).
#include "runtime/lens_group_em.h"

namespace pem::runtime {

trace::SphereShell SingleLayerShell(const LensGroupEm& group) {
    double sum = 0.0, weight = 0.0;
    for (const EmLayer& l : group.layers) {
        sum += static_cast<double>(l.records) * l.radius;
        weight += static_cast<double>(l.records);
    }
    const double radius =
        weight > 0.0 ? sum / weight : (group.layers.empty() ? 1.0 : group.layers[0].radius);
    return {glm::dvec3(group.emOrigin), radius};
}

const char* TermName(int term) {
    return term == 0 ? "R" : "T";
}

}  // namespace pem::runtime
