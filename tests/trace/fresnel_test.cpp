// SPDX-License-Identifier: MIT
// fresnel_test.cpp — exact Fresnel (s/p, energy, Brewster, normal incidence, TIR), Schlick against
// exact, Snell refraction and mirror reflection.
#include "trace/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace pem::trace {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Transmittances computed independently of R (intensity ratios with the beam-area factor).
double TransmittanceS(double cosI, double cosT, double n1, double n2) {
    const double t = 2.0 * n1 * cosI / (n1 * cosI + n2 * cosT);
    return t * t * (n2 * cosT) / (n1 * cosI);
}
double TransmittanceP(double cosI, double cosT, double n1, double n2) {
    const double t = 2.0 * n1 * cosI / (n2 * cosI + n1 * cosT);
    return t * t * (n2 * cosT) / (n1 * cosI);
}

TEST(Fresnel, ReflectancePlusTransmittanceIsOne) {
    for (auto [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 2.4}}) {
        for (int deg = 0; deg < 90; deg += 3) {
            const double cosI = std::cos(deg * kDeg);
            const std::optional<double> cosT = CosTransmitted(cosI, n1, n2);
            if (!cosT) continue;
            const FresnelSP sp = FresnelDielectricSP(cosI, n1, n2);
            EXPECT_NEAR(sp.rs + TransmittanceS(cosI, *cosT, n1, n2), 1.0, 1e-12) << deg;
            EXPECT_NEAR(sp.rp + TransmittanceP(cosI, *cosT, n1, n2), 1.0, 1e-12) << deg;
            const double r = FresnelDielectric(cosI, n1, n2);
            EXPECT_GE(r, 0.0);
            EXPECT_LE(r, 1.0);
        }
    }
}

TEST(Fresnel, BrewsterAngleZeroesP) {
    for (auto [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.33, 1.9}}) {
        const double brewster = std::atan(n2 / n1);
        const FresnelSP sp = FresnelDielectricSP(std::cos(brewster), n1, n2);
        EXPECT_NEAR(sp.rp, 0.0, 1e-15);
        EXPECT_GT(sp.rs, 0.01);
        // Either side of Brewster's angle the p component is positive again.
        EXPECT_GT(FresnelDielectricSP(std::cos(brewster - 5 * kDeg), n1, n2).rp, 1e-5);
        EXPECT_GT(FresnelDielectricSP(std::cos(brewster + 5 * kDeg), n1, n2).rp, 1e-5);
    }
}

TEST(Fresnel, NormalIncidence) {
    for (auto [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 1.02}}) {
        const double expected = std::pow((n1 - n2) / (n1 + n2), 2.0);
        const FresnelSP sp = FresnelDielectricSP(1.0, n1, n2);
        EXPECT_NEAR(sp.rs, expected, 1e-15);
        EXPECT_NEAR(sp.rp, expected, 1e-15);
        EXPECT_NEAR(FresnelDielectric(1.0, n1, n2), expected, 1e-15);
        EXPECT_DOUBLE_EQ(SchlickF0(n1, n2), expected);
        EXPECT_DOUBLE_EQ(FresnelSchlickDielectric(1.0, n1, n2), expected);
    }
    EXPECT_NEAR(FresnelDielectric(1.0, 1.0, 1.5), 0.04, 1e-15);
    EXPECT_EQ(FresnelDielectric(0.0, 1.3, 1.3), 0.0);  // no interface, even at grazing incidence
}

TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
    const double n1 = 1.5, n2 = 1.0;
    const double critical = std::asin(n2 / n1);
    const double below = std::cos(critical - 0.1 * kDeg);
    const double beyond = std::cos(critical + 0.1 * kDeg);
    EXPECT_LT(FresnelDielectric(below, n1, n2), 1.0);
    EXPECT_TRUE(CosTransmitted(below, n1, n2).has_value());
    EXPECT_FALSE(CosTransmitted(beyond, n1, n2).has_value());
    EXPECT_EQ(FresnelDielectric(beyond, n1, n2), 1.0);
    EXPECT_EQ(FresnelDielectricSP(beyond, n1, n2), (FresnelSP{1.0, 1.0}));
    EXPECT_EQ(FresnelSchlickDielectric(beyond, n1, n2), 1.0);
    EXPECT_EQ(FresnelDielectric(std::cos(80 * kDeg), n1, n2), 1.0);
    // Refract returns nullopt there too.
    const glm::dvec3 dir = glm::normalize(
        glm::dvec3(std::sin(critical + 0.1 * kDeg), 0.0, -std::cos(critical + 0.1 * kDeg)));
    EXPECT_FALSE(Refract(dir, {0, 0, 1}, n1, n2).has_value());
    // From the rare side there is never total reflection.
    EXPECT_LT(FresnelDielectric(std::cos(89.9 * kDeg), n2, n1), 1.0);
}

TEST(Fresnel, SchlickCloseToExactAtSmallAngles) {
    for (auto [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}, std::pair{1.0, 1.33}}) {
        // "Small": up to 30 degrees, and up to half the critical angle from the dense side.
        const double maxDeg = n1 > n2 ? 0.5 * std::asin(n2 / n1) / kDeg : 30.0;
        for (int deg = 0; deg <= maxDeg; ++deg) {
            const double cosI = std::cos(deg * kDeg);
            const double exact = FresnelDielectric(cosI, n1, n2);
            EXPECT_NEAR(FresnelReflectance(FresnelModel::Schlick, cosI, n1, n2), exact, 2e-3)
                << n1 << " -> " << n2 << " at " << deg;
            EXPECT_EQ(FresnelReflectance(FresnelModel::Exact, cosI, n1, n2), exact);
        }
    }
}

TEST(Fresnel, SchlickPerChannelF0) {
    const glm::dvec3 f0(0.95, 0.64, 0.54);  // gold-like
    EXPECT_EQ(FresnelSchlick(1.0, f0), f0);
    const glm::dvec3 grazing = FresnelSchlick(0.0, f0);
    EXPECT_NEAR(grazing.x, 1.0, 1e-15);
    EXPECT_NEAR(grazing.y, 1.0, 1e-15);
    EXPECT_NEAR(grazing.z, 1.0, 1e-15);
    EXPECT_DOUBLE_EQ(FresnelSchlick(0.5, f0).y, FresnelSchlick(0.5, f0.y));
}

TEST(Fresnel, RefractionObeysSnell) {
    const glm::dvec3 normal = glm::normalize(glm::dvec3(0.2, 1.0, -0.3));
    const glm::dvec3 axis = glm::normalize(glm::cross(normal, glm::dvec3(1, 0, 0)));
    for (auto [n1, n2] : {std::pair{1.0, 1.5}, std::pair{1.5, 1.0}}) {
        for (int deg = 0; deg < 90; deg += 7) {
            // Incident direction at `deg` from -normal, pointing toward the surface.
            const double a = deg * kDeg;
            const glm::dvec3 dir = -std::cos(a) * normal + std::sin(a) * axis;
            const std::optional<glm::dvec3> t = Refract(dir, normal, n1, n2);
            if (n1 * std::sin(a) >= n2) {
                EXPECT_FALSE(t.has_value());
                continue;
            }
            ASSERT_TRUE(t.has_value());
            EXPECT_NEAR(glm::length(*t), 1.0, 1e-14);
            EXPECT_LT(glm::dot(*t, normal), 0.0);  // continues to the other side
            const double sinT = glm::length(glm::cross(*t, normal));
            EXPECT_NEAR(n1 * std::sin(a), n2 * sinT, 1e-13);
            EXPECT_NEAR(glm::dot(glm::cross(dir, normal), *t), 0.0, 1e-14);  // plane of incidence
            // The normal's orientation does not matter.
            const glm::dvec3 flipped = *Refract(dir, -normal, n1, n2);
            EXPECT_NEAR(glm::length(flipped - *t), 0.0, 1e-15);
        }
    }
}

TEST(Fresnel, ReflectionMirrorsAboutTheNormal) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(1.0, 2.0, 2.0));
    const glm::dvec3 dir = glm::normalize(glm::dvec3(0.3, -1.0, 0.1));
    const glm::dvec3 r = Reflect(dir, n);
    EXPECT_NEAR(glm::dot(r, n), -glm::dot(dir, n), 1e-15);
    EXPECT_NEAR(glm::length(glm::cross(dir, n) - glm::cross(r, n)), 0.0, 1e-15);  // same tangent
    EXPECT_NEAR(glm::length(Reflect(dir, -n) - r), 0.0, 1e-15);
}

}  // namespace
}  // namespace pem::trace
