// SPDX-License-Identifier: MIT
// fresnel.h — Fresnel reflectance of a smooth interface and the reflected/refracted directions.
//
// Conventions: `cosThetaI` is the cosine of the angle between the incident ray and the normal,
// taken as |cos| (either side works); n1 is the index of refraction on the incident side, n2 the
// other side. `dir` is the incident propagation direction (pointing *toward* the surface), unit
// length; `normal` is a unit normal of either orientation (it is flipped internally to face the
// incident side). Returned directions are unit and point away from the surface. All double.
//
// Not here: polarization tracking, conductors' complex IOR (metals and mirrors use Schlick with a
// given per-channel F0), dispersion.
#pragma once

#include <glm/glm.hpp>
#include <optional>

namespace pem::trace {

enum class FresnelModel { Exact, Schlick };

// Reflectance of the s (perpendicular) and p (parallel) polarized components. Both are 1 under
// total internal reflection.
struct FresnelSP {
    double rs = 0.0;
    double rp = 0.0;
    bool operator==(const FresnelSP&) const = default;
};

// Cosine of the transmitted angle by Snell's law, or nullopt under total internal reflection.
std::optional<double> CosTransmitted(double cosThetaI, double n1, double n2);

FresnelSP FresnelDielectricSP(double cosThetaI, double n1, double n2);
// Unpolarized reflectance R = (rs + rp) / 2; transmittance is 1 - R.
double FresnelDielectric(double cosThetaI, double n1, double n2);

// Schlick: F = F0 + (1 - F0)(1 - cos)^5.
double SchlickF0(double n1, double n2);  // ((n1 - n2) / (n1 + n2))^2
double FresnelSchlick(double cosTheta, double f0);
glm::dvec3 FresnelSchlick(double cosTheta, const glm::dvec3& f0);  // per channel (mirrors, metals)
// Schlick for a dielectric interface: F0 from the IORs; when n1 > n2 the cosine of the transmitted
// angle is used (the usual symmetric form), and R = 1 under total internal reflection.
double FresnelSchlickDielectric(double cosThetaI, double n1, double n2);

// Reflectance of a dielectric interface with the chosen model.
double FresnelReflectance(FresnelModel model, double cosThetaI, double n1, double n2);

// Mirror direction: dir - 2 (dir·n) n. Independent of the normal's orientation.
glm::dvec3 Reflect(const glm::dvec3& dir, const glm::dvec3& normal);
// Snell refraction from the n1 side into the n2 side; nullopt under total internal reflection.
std::optional<glm::dvec3> Refract(const glm::dvec3& dir, const glm::dvec3& normal, double n1,
                                  double n2);

}  // namespace pem::trace
