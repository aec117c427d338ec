// SPDX-License-Identifier: MIT
// fresnel.cpp — exact dielectric Fresnel equations, Schlick's approximation, Snell refraction.
#include "trace/fresnel.h"

#include <algorithm>
#include <cmath>

namespace pem::trace {

namespace {

double ClampCos(double cosTheta) {
    return std::min(std::abs(cosTheta), 1.0);
}

double Pow5(double x) {
    const double x2 = x * x;
    return x2 * x2 * x;
}

double Square(double x) {
    return x * x;
}

}  // namespace

std::optional<double> CosTransmitted(double cosThetaI, double n1, double n2) {
    const double cosI = ClampCos(cosThetaI);
    // Snell: sin(t) = (n1 / n2) sin(i).
    const double eta = n1 / n2;
    const double sin2T = eta * eta * (1.0 - cosI * cosI);
    if (sin2T >= 1.0) return std::nullopt;
    return std::sqrt(1.0 - sin2T);
}

FresnelSP FresnelDielectricSP(double cosThetaI, double n1, double n2) {
    if (n1 == n2) return {0.0, 0.0};  // no interface (avoids 0/0 at grazing incidence)
    const std::optional<double> cosT = CosTransmitted(cosThetaI, n1, n2);
    if (!cosT) return {1.0, 1.0};  // total internal reflection
    const double cosI = ClampCos(cosThetaI);
    const double c = *cosT;
    // Amplitude ratios of the perpendicular (s) and parallel (p) components.
    const double rs = (n1 * cosI - n2 * c) / (n1 * cosI + n2 * c);
    const double rp = (n2 * cosI - n1 * c) / (n2 * cosI + n1 * c);
    return {rs * rs, rp * rp};
}

double FresnelDielectric(double cosThetaI, double n1, double n2) {
    const FresnelSP sp = FresnelDielectricSP(cosThetaI, n1, n2);
    return 0.5 * (sp.rs + sp.rp);
}

double SchlickF0(double n1, double n2) {
    return Square((n1 - n2) / (n1 + n2));
}

double FresnelSchlick(double cosTheta, double f0) {
    return f0 + (1.0 - f0) * Pow5(1.0 - ClampCos(cosTheta));
}

glm::dvec3 FresnelSchlick(double cosTheta, const glm::dvec3& f0) {
    const double w = Pow5(1.0 - ClampCos(cosTheta));
    return f0 + (glm::dvec3(1.0) - f0) * w;
}

double FresnelSchlickDielectric(double cosThetaI, double n1, double n2) {
    if (n1 <= n2) return FresnelSchlick(cosThetaI, SchlickF0(n1, n2));
    // Leaving the denser medium: use the transmitted angle, R = 1 beyond the critical angle.
    const std::optional<double> cosT = CosTransmitted(cosThetaI, n1, n2);
    if (!cosT) return 1.0;
    return FresnelSchlick(*cosT, SchlickF0(n1, n2));
}

double FresnelReflectance(FresnelModel model, double cosThetaI, double n1, double n2) {
    return model == FresnelModel::Exact ? FresnelDielectric(cosThetaI, n1, n2)
                                        : FresnelSchlickDielectric(cosThetaI, n1, n2);
}

glm::dvec3 Reflect(const glm::dvec3& dir, const glm::dvec3& normal) {
    return glm::normalize(dir - 2.0 * glm::dot(dir, normal) * normal);
}

std::optional<glm::dvec3> Refract(const glm::dvec3& dir, const glm::dvec3& normal, double n1,
                                  double n2) {
    // Face the normal toward the incident side, so cosI = -dir·n >= 0.
    const glm::dvec3 n = glm::dot(dir, normal) < 0.0 ? normal : -normal;
    const double cosI = std::min(-glm::dot(dir, n), 1.0);
    const std::optional<double> cosT = CosTransmitted(cosI, n1, n2);
    if (!cosT) return std::nullopt;
    // t = eta d + (eta cosI - cosT) n: tangential part scaled by eta, normal part of length cosT.
    const double eta = n1 / n2;
    return glm::normalize(eta * dir + (eta * cosI - *cosT) * n);
}

}  // namespace pem::trace
