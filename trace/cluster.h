// SPDX-License-Identifier: MIT
// cluster.h — layer partition of the environment by LBG clustering of hit distances (hybrid §4.2).
//
// Input: one HitRecord per front-facing environment intersection of an outgoing ray, from all
// viewpoints together. Continued rays (hybrid §4.1: a ray continued through occluders records every
// front-facing hit) are given as several records with the same (viewpointId, rayId); a ray that was
// not continued simply has one record.
//
// Algorithm: 1D LBG (k-means) on distance. Deterministic start: centre k is the distance at
// quantile (k + 0.5) / N of the sorted distances. Assign each record to the nearest centre (ties to
// the lower index), recompute each centre as its records' mean, repeat until no record changes
// cluster (or maxIterations). Then every object goes whole to the single cluster holding most of
// its records (ties to the lower index). Shell radius = mean distance of the cluster's records,
// where the records of one continued ray count only through its frontmost record in that cluster.
// Clusters left without records are removed and reported. Layers are ordered by increasing radius.
//
// Not here: choosing N, building shells from layers (shell.h), discarding all but the first hit
// per layer when building the layer images.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <span>
#include <vector>

namespace pem::trace {

struct HitRecord {
    double distance = 0.0;  // from the lens object's EM origin to the intersection
    uint32_t objectId = 0;
    uint32_t viewpointId = 0;
    uint64_t rayId = 0;  // records with equal (viewpointId, rayId) lie on one continued ray

    bool operator==(const HitRecord&) const = default;
};

struct LayerCluster {
    double radius = 0.0;            // shell radius: mean distance (frontmost rule)
    std::vector<uint32_t> objects;  // member objects, ascending
    size_t recordCount = 0;         // all records of the layer
    size_t shellSampleCount = 0;    // records that entered the mean (frontmost per ray)

    bool operator==(const LayerCluster&) const = default;
};

struct LayerClustering {
    std::vector<LayerCluster> layers;    // increasing radius
    std::vector<int> recordLayer;        // per input record: index into layers
    std::vector<double> removedCentres;  // final LBG centres of clusters that ended empty
    int iterations = 0;                  // assign/recompute rounds
    bool converged = false;              // no reassignment in the last round

    bool operator==(const LayerClustering&) const = default;
};

LayerClustering ClusterLayers(std::span<const HitRecord> records, int nLayers,
                              int maxIterations = 1000);

std::ostream& operator<<(std::ostream& os, const LayerCluster& layer);

}  // namespace pem::trace
