// SPDX-License-Identifier: MIT
// confidence_test.cpp — c = 1 - min(theta_m, theta_c)^2 / theta_c^2 with theta_c = 5 degrees.
#include "trace/confidence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pem::trace {
namespace {

glm::vec3 DirAt(double deg) {
    const double a = deg * std::numbers::pi / 180.0;
    return {static_cast<float>(std::sin(a)), 0.0f, static_cast<float>(std::cos(a))};
}

TEST(Confidence, Formula) {
    EXPECT_EQ(Confidence(0.0), 1.0);
    EXPECT_DOUBLE_EQ(Confidence(2.5), 0.75);
    EXPECT_EQ(Confidence(5.0), 0.0);
    EXPECT_EQ(Confidence(30.0), 0.0);
    EXPECT_DOUBLE_EQ(Confidence(5.0, 10.0), 0.75);
}

TEST(Confidence, ParallelRaysAreFullyTrusted) {
    const std::vector<glm::vec3> dirs(4, glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f)));
    EXPECT_EQ(MaxPairAngleDeg(dirs), 0.0);
    EXPECT_EQ(PixelConfidence(dirs), 1.0);
}

TEST(Confidence, MaximumOverAllPairs) {
    const std::vector<glm::vec3> dirs{DirAt(1.0), DirAt(-1.0), DirAt(2.0), DirAt(0.0)};
    EXPECT_NEAR(MaxPairAngleDeg(dirs), 3.0, 1e-5);
    EXPECT_NEAR(PixelConfidence(dirs), 1.0 - 9.0 / 25.0, 1e-5);
    const std::vector<glm::vec3> wide{DirAt(0.0), DirAt(5.5)};
    EXPECT_EQ(PixelConfidence(wide), 0.0);
}

TEST(Confidence, Image) {
    // 2 x 1 pixels, 3 samples each: pixel 0 parallel (+ one sample without an exit ray),
    // pixel 1 spread over 2.5 degrees. A pixel without exit rays gets 0.
    const std::vector<glm::vec3> dirs{DirAt(0.0), glm::vec3(0.0f), DirAt(0.0),
                                      DirAt(0.0), DirAt(2.5),      DirAt(1.0)};
    const ConfidenceImage image = MakeConfidenceImage(2, 1, 3, dirs);
    ASSERT_EQ(image.values.size(), 2u);
    EXPECT_EQ(image.values[0], 1.0f);
    EXPECT_NEAR(image.values[1], 0.75f, 1e-5f);
    const std::vector<glm::vec3> none(2, glm::vec3(0.0f));
    EXPECT_EQ(MakeConfidenceImage(1, 1, 2, none).values[0], 0.0f);
}

}  // namespace
}  // namespace pem::trace
