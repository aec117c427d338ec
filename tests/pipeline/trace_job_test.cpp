// SPDX-License-Identifier: MIT
// trace_job_test.cpp — pemref trace as a job: the same image bytes for any thread count,
// trace.json read back whole (every sample's camera exactly as traced), viewpoints.
#include "pipeline/trace_job.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "pipeline/layout.h"
#include "pipeline/viewpoints.h"
#include "tests/pipeline/pipeline_test_util.h"

namespace pem::pipeline {
namespace {

TEST(TraceJob, SameBytesForOneAndTwoThreads) {
    TraceJobOptions o;
    o.scene = kHybrid;
    o.views = "circle:2:8";
    o.width = 64, o.height = 48, o.spp = 2;
    std::map<std::string, std::string> out[2];
    for (int threads : {1, 2}) {
        o.threads = threads;
        o.outDir = FreshDir("threads" + std::to_string(threads)).string();
        RunTraceJob(o);
        out[threads - 1] = ReadTree(o.outDir);
        out[threads - 1].erase(kTraceJson);  // timings and the thread count
        fs::remove_all(o.outDir);
    }
    ASSERT_GT(out[0].size(), 20u);
    ASSERT_EQ(out[0].size(), out[1].size());
    for (const auto& [name, bytes] : out[0]) {
        ASSERT_TRUE(out[1].count(name)) << name;
        EXPECT_TRUE(bytes == out[1].at(name)) << name << " differs between 1 and 2 threads";
    }
}

TEST(TraceJob, ManifestHoldsTheCamerasAsTraced) {
    TraceJobOptions o;
    o.scene = kHybrid;
    o.views = "circle:3:10";
    o.width = 40, o.height = 30, o.spp = 1;
    o.outDir = FreshDir("cameras").string();
    const TraceManifest written = RunTraceJob(o);
    const TraceManifest read = ReadTraceManifest(o.outDir);
    const std::vector<raster::Camera> expected =
        SampleViews(trace::LoadScene(kHybrid), "circle:3:10", 40, 30);
    ASSERT_EQ(read.views.size(), 3u);
    for (size_t v = 0; v < 3; ++v) {
        EXPECT_EQ(std::memcmp(&read.views[v].camera, &expected[v], sizeof(raster::Camera)), 0)
            << "sample " << v;
        EXPECT_EQ(read.views[v].camera, written.views[v].camera);
    }
    ASSERT_EQ(read.groups.size(), written.groups.size());
    for (size_t g = 0; g < read.groups.size(); ++g) {
        EXPECT_EQ(read.groups[g].emOrigin, written.groups[g].emOrigin);
        ASSERT_EQ(read.groups[g].layers.size(), written.groups[g].layers.size());
        for (size_t l = 0; l < read.groups[g].layers.size(); ++l)
            EXPECT_TRUE(read.groups[g].layers[l].shell == written.groups[g].layers[l].shell);
    }
    EXPECT_EQ(read.width, 40);
    EXPECT_EQ(read.spp, 1);
    std::filesystem::remove_all(o.outDir);
}

TEST(Viewpoints, CircleViewsKeepHeightAndDistance) {
    raster::Camera cam;
    cam.eye = {1.0f, 2.0f, 3.0f};
    const glm::vec3 c(1.0f, 0.5f, 0.0f);
    const auto views = CircleViews(cam, c, 4, 90.0);
    ASSERT_EQ(views.size(), 4u);
    EXPECT_NEAR(views[0].eye.x, 1.0f, 1e-6f);
    EXPECT_NEAR(views[0].eye.z, 3.0f, 1e-6f);
    EXPECT_NEAR(views[1].eye.x, 4.0f, 1e-5f);  // +90°: from +Z toward +X
    EXPECT_NEAR(views[1].eye.z, 0.0f, 1e-5f);
    for (const raster::Camera& v : views) {
        EXPECT_EQ(v.eye.y, 2.0f);
        EXPECT_NEAR(std::hypot(v.eye.x - c.x, v.eye.z - c.z), 3.0f, 1e-5f);
        EXPECT_EQ(v.target, c);
        EXPECT_EQ(v.up, glm::vec3(0.0f, 1.0f, 0.0f));
    }
}

}  // namespace
}  // namespace pem::pipeline
