// SPDX-License-Identifier: MIT
// cluster.cpp — LBG clustering of hit distances into layers, whole objects per layer.
#include "trace/cluster.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <ostream>
#include <tuple>
#include <utility>

namespace pem::trace {

namespace {

// Centre k at quantile (k + 0.5) / n of the sorted distances.
std::vector<double> QuantileCentres(std::span<const HitRecord> records, int n) {
    std::vector<double> sorted;
    sorted.reserve(records.size());
    for (const HitRecord& r : records) sorted.push_back(r.distance);
    std::sort(sorted.begin(), sorted.end());
    std::vector<double> centres;
    for (int k = 0; k < n; ++k) {
        const double q = (static_cast<double>(k) + 0.5) / static_cast<double>(n);
        const auto index = static_cast<size_t>(q * static_cast<double>(sorted.size()));
        centres.push_back(sorted[std::min(index, sorted.size() - 1)]);
    }
    return centres;
}

int NearestCentre(const std::vector<double>& centres, double distance) {
    int best = 0;
    for (int k = 1; k < static_cast<int>(centres.size()); ++k) {
        if (std::abs(distance - centres[k]) < std::abs(distance - centres[best])) best = k;
    }
    return best;
}

// Mean distance per cluster; empty clusters keep their centre.
void RecomputeCentres(std::span<const HitRecord> records, const std::vector<int>& assignment,
                      std::vector<double>* centres) {
    std::vector<double> sum(centres->size(), 0.0);
    std::vector<size_t> count(centres->size(), 0);
    for (size_t i = 0; i < records.size(); ++i) {
        sum[assignment[i]] += records[i].distance;
        ++count[assignment[i]];
    }
    for (size_t k = 0; k < centres->size(); ++k) {
        if (count[k] > 0) (*centres)[k] = sum[k] / static_cast<double>(count[k]);
    }
}

// Every record of an object moves to the cluster holding most of that object's records.
void AssignWholeObjects(std::span<const HitRecord> records, int nClusters,
                        std::vector<int>* assignment) {
    std::map<uint32_t, std::vector<size_t>> votes;
    for (size_t i = 0; i < records.size(); ++i) {
        std::vector<size_t>& v = votes[records[i].objectId];
        v.resize(static_cast<size_t>(nClusters), 0);
        ++v[(*assignment)[i]];
    }
    std::map<uint32_t, int> objectCluster;
    for (const auto& [object, v] : votes) {
        objectCluster[object] = static_cast<int>(std::max_element(v.begin(), v.end()) - v.begin());
    }
    for (size_t i = 0; i < records.size(); ++i) {
        (*assignment)[i] = objectCluster[records[i].objectId];
    }
}

// Per cluster: records, member objects and the shell radius with the frontmost-per-ray rule.
std::vector<LayerCluster> SummarizeClusters(std::span<const HitRecord> records,
                                            const std::vector<int>& assignment, int nClusters) {
    std::vector<LayerCluster> clusters(static_cast<size_t>(nClusters));
    std::map<std::tuple<int, uint32_t, uint64_t>, double> frontmost;  // (cluster, view, ray)
    for (size_t i = 0; i < records.size(); ++i) {
        const HitRecord& r = records[i];
        LayerCluster& layer = clusters[assignment[i]];
        ++layer.recordCount;
        layer.objects.push_back(r.objectId);
        const auto key = std::make_tuple(assignment[i], r.viewpointId, r.rayId);
        const auto [it, inserted] = frontmost.try_emplace(key, r.distance);
        if (!inserted) it->second = std::min(it->second, r.distance);
    }
    for (const auto& [key, distance] : frontmost) {
        LayerCluster& layer = clusters[std::get<0>(key)];
        layer.radius += distance;
        ++layer.shellSampleCount;
    }
    for (LayerCluster& layer : clusters) {
        if (layer.shellSampleCount > 0) layer.radius /= static_cast<double>(layer.shellSampleCount);
        std::sort(layer.objects.begin(), layer.objects.end());
        layer.objects.erase(std::unique(layer.objects.begin(), layer.objects.end()),
                            layer.objects.end());
    }
    return clusters;
}

}  // namespace

LayerClustering ClusterLayers(std::span<const HitRecord> records, int nLayers, int maxIterations) {
    LayerClustering out;
    if (records.empty() || nLayers <= 0) return out;

    // Step 1: LBG on distance from the quantile start.
    std::vector<double> centres = QuantileCentres(records, nLayers);
    std::vector<int> assignment(records.size(), -1);
    while (out.iterations < maxIterations) {
        ++out.iterations;
        bool changed = false;
        for (size_t i = 0; i < records.size(); ++i) {
            const int k = NearestCentre(centres, records[i].distance);
            changed |= k != assignment[i];
            assignment[i] = k;
        }
        RecomputeCentres(records, assignment, &centres);
        if (!changed) {
            out.converged = true;
            break;
        }
    }

    // Step 2: whole objects, then per-cluster summaries.
    AssignWholeObjects(records, nLayers, &assignment);
    std::vector<LayerCluster> clusters = SummarizeClusters(records, assignment, nLayers);

    // Step 3: drop empty clusters, order by radius, remap the records.
    std::vector<int> order;
    for (int k = 0; k < nLayers; ++k) {
        if (clusters[k].recordCount == 0) {
            out.removedCentres.push_back(centres[k]);
        } else {
            order.push_back(k);
        }
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return clusters[a].radius < clusters[b].radius; });
    std::vector<int> layerOf(static_cast<size_t>(nLayers), -1);
    for (size_t i = 0; i < order.size(); ++i) {
        layerOf[order[i]] = static_cast<int>(i);
        out.layers.push_back(std::move(clusters[order[i]]));
    }
    for (int k : assignment) out.recordLayer.push_back(layerOf[k]);
    return out;
}

std::ostream& operator<<(std::ostream& os, const LayerCluster& layer) {
    os << "LayerCluster{radius " << layer.radius << ", records " << layer.recordCount
       << ", samples " << layer.shellSampleCount << ", objects [";
    for (size_t i = 0; i < layer.objects.size(); ++i) os << (i ? " " : "") << layer.objects[i];
    return os << "]}";
}

}  // namespace pem::trace
