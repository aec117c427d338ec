// SPDX-License-Identifier: MIT
// cluster_test.cpp — LBG layer clustering: three known shells seen from several viewpoints, whole
// objects in one layer, the frontmost rule for continued rays, removal of empty clusters.
#include "trace/cluster.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace pem::trace {
namespace {

// Three shells (radius 2, 5, 12) of four objects each; each object is seen by three viewpoints
// over a small range of distances (deterministic spread, no RNG).
std::vector<HitRecord> ThreeShellScene() {
    const double radii[3] = {2.0, 5.0, 12.0};
    std::vector<HitRecord> records;
    uint64_t ray = 0;
    for (uint32_t shell = 0; shell < 3; ++shell) {
        for (uint32_t obj = 0; obj < 4; ++obj) {
            const uint32_t objectId = 10 * shell + obj;
            for (uint32_t view = 0; view < 3; ++view) {
                for (int k = 0; k < 20; ++k) {
                    const double spread = 0.4 * std::sin(0.7 * k + 1.3 * obj + 0.5 * view);
                    records.push_back({radii[shell] + spread, objectId, view, ray++});
                }
            }
        }
    }
    return records;
}

TEST(Cluster, RecoversThreeShells) {
    const std::vector<HitRecord> records = ThreeShellScene();
    const LayerClustering c = ClusterLayers(records, 3);
    EXPECT_TRUE(c.converged);
    EXPECT_TRUE(c.removedCentres.empty());
    ASSERT_EQ(c.layers.size(), 3u);
    const double radii[3] = {2.0, 5.0, 12.0};
    for (uint32_t shell = 0; shell < 3; ++shell) {
        const LayerCluster& layer = c.layers[shell];
        EXPECT_NEAR(layer.radius, radii[shell], 0.1) << layer;
        EXPECT_EQ(layer.recordCount, 240u);
        EXPECT_EQ(layer.shellSampleCount, 240u);
        const std::vector<uint32_t> expected{10 * shell, 10 * shell + 1, 10 * shell + 2,
                                             10 * shell + 3};
        EXPECT_EQ(layer.objects, expected);
    }
    ASSERT_EQ(c.recordLayer.size(), records.size());
    for (size_t i = 0; i < records.size(); ++i) {
        EXPECT_EQ(c.recordLayer[i], static_cast<int>(records[i].objectId / 10));
    }
}

TEST(Cluster, WholeObjectsEndInOneLayer) {
    std::vector<HitRecord> records = ThreeShellScene();
    // Object 99 is mostly near the first shell, with a tail reaching into the second one.
    uint64_t ray = 100000;
    for (int k = 0; k < 12; ++k) records.push_back({2.3 + 0.05 * k, 99, 0, ray++});
    for (int k = 0; k < 4; ++k) records.push_back({4.6 + 0.1 * k, 99, 1, ray++});
    const LayerClustering c = ClusterLayers(records, 3);
    ASSERT_EQ(c.layers.size(), 3u);
    std::set<int> layersOf99;
    for (size_t i = 0; i < records.size(); ++i) {
        if (records[i].objectId == 99) layersOf99.insert(c.recordLayer[i]);
    }
    EXPECT_EQ(layersOf99, std::set<int>{0});
    // Every object appears in exactly one layer.
    std::set<uint32_t> seen;
    for (const LayerCluster& layer : c.layers) {
        for (uint32_t object : layer.objects) EXPECT_TRUE(seen.insert(object).second) << object;
    }
    EXPECT_EQ(seen.size(), 13u);
}

TEST(Cluster, ContinuedRaysCountOnlyTheirFrontmostRecordPerLayer) {
    // Near layer at ~1; far layer: ray 7 continues through two far hits (9 and 11), ray 8 has 10.
    const std::vector<HitRecord> records = {
        {1.0, 1, 0, 1}, {1.2, 1, 0, 2}, {9.0, 2, 0, 7}, {11.0, 3, 0, 7}, {10.0, 2, 0, 8},
    };
    const LayerClustering c = ClusterLayers(records, 2);
    ASSERT_EQ(c.layers.size(), 2u);
    EXPECT_NEAR(c.layers[0].radius, 1.1, 1e-12);
    EXPECT_EQ(c.layers[1].recordCount, 3u);
    EXPECT_EQ(c.layers[1].shellSampleCount, 2u);
    EXPECT_NEAR(c.layers[1].radius, 9.5, 1e-12);  // (9 + 10) / 2, not (9 + 11 + 10) / 3
    // The same ray id under another viewpoint is another ray.
    std::vector<HitRecord> twoViews = records;
    twoViews[3].viewpointId = 1;
    EXPECT_NEAR(ClusterLayers(twoViews, 2).layers[1].radius, 10.0, 1e-12);
}

TEST(Cluster, EmptyClustersAreRemovedAndReported) {
    std::vector<HitRecord> records;
    for (uint64_t k = 0; k < 8; ++k) records.push_back({k < 4 ? 1.0 : 9.0, k < 4 ? 0u : 1u, 0, k});
    const LayerClustering c = ClusterLayers(records, 4);
    ASSERT_EQ(c.layers.size(), 2u);
    EXPECT_EQ(c.removedCentres.size(), 2u);
    EXPECT_DOUBLE_EQ(c.layers[0].radius, 1.0);
    EXPECT_DOUBLE_EQ(c.layers[1].radius, 9.0);
    EXPECT_TRUE(ClusterLayers({}, 3).layers.empty());
}

TEST(Cluster, IsDeterministic) {
    const std::vector<HitRecord> records = ThreeShellScene();
    EXPECT_EQ(ClusterLayers(records, 3), ClusterLayers(records, 3));
    EXPECT_EQ(ClusterLayers(records, 2).layers.size(), 2u);
}

}  // namespace
}  // namespace pem::trace
