// SPDX-License-Identifier: MIT
// shell_fit.cpp — fitting shells to points (declared in shell.h): minimum-volume ellipsoid search,
// boxes, cylinders, the least-squares quad impostor, and the EM origin.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "trace/shell.h"

namespace pem::trace {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Step: the ellipsoid search. Shape (a, b) means radii proportional to (1, 2^a, 2^b).
struct ShapeFit {
    glm::dvec3 radii{0.0};
    double volume = kInf;  // proportional to the product of the radii
};

ShapeFit FitShape(std::span<const glm::dvec3> squared, double a, double b) {
    const glm::dvec3 shape(1.0, std::exp2(a), std::exp2(b));
    const glm::dvec3 inv2 = 1.0 / (shape * shape);
    double lambda2 = 0.0;  // the smallest scale^2 that contains every point
    for (const glm::dvec3& s : squared) lambda2 = std::max(lambda2, glm::dot(s, inv2));
    const double lambda = std::sqrt(lambda2) * (1.0 + 1e-12);
    const glm::dvec3 radii = lambda * shape;
    return {radii, radii.x * radii.y * radii.z};
}

// Best shape on a (2n+1) x (2n+1) grid of spacing `step` around (a0, b0).
void SearchGrid(std::span<const glm::dvec3> squared, int n, double step, double* a0, double* b0,
                ShapeFit* best) {
    const double ca = *a0;
    const double cb = *b0;
    for (int i = -n; i <= n; ++i) {
        for (int j = -n; j <= n; ++j) {
            const double a = ca + step * i;
            const double b = cb + step * j;
            const ShapeFit fit = FitShape(squared, a, b);
            if (fit.volume < best->volume) {
                *best = fit;
                *a0 = a;
                *b0 = b;
            }
        }
    }
}

// Step: a symmetric 3x3 eigen decomposition by cyclic Jacobi rotations.
struct Eigen3 {
    std::array<double, 3> values;       // ascending
    std::array<glm::dvec3, 3> vectors;  // unit, matching values
};

Eigen3 SymmetricEigen(glm::dmat3 a) {
    glm::dmat3 v(1.0);
    for (int sweep = 0; sweep < 50; ++sweep) {
        const double off = a[1][0] * a[1][0] + a[2][0] * a[2][0] + a[2][1] * a[2][1];
        if (off == 0.0) break;
        for (auto [p, q] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
            if (a[q][p] == 0.0) continue;
            // Rotation in the (p, q) plane that zeroes a[p][q].
            const double theta = (a[q][q] - a[p][p]) / (2.0 * a[q][p]);
            const double t = std::copysign(1.0, theta) / (std::abs(theta) + std::hypot(theta, 1.0));
            const double c = 1.0 / std::sqrt(t * t + 1.0);
            glm::dmat3 j(1.0);
            j[p][p] = c;
            j[q][q] = c;
            j[q][p] = t * c;   // column q, row p
            j[p][q] = -t * c;  // column p, row q
            a = glm::transpose(j) * a * j;
            v = v * j;
        }
    }
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int x, int y) { return a[x][x] < a[y][y]; });
    Eigen3 out{};
    for (int i = 0; i < 3; ++i) {
        out.values[i] = a[order[i]][order[i]];
        out.vectors[i] = glm::normalize(v[order[i]]);
    }
    return out;
}

glm::dvec3 Centroid(std::span<const glm::dvec3> points) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& p : points) sum += p;
    return sum / static_cast<double>(std::max<size_t>(points.size(), 1));
}

glm::dmat3 Covariance(std::span<const glm::dvec3> points, const glm::dvec3& mean) {
    glm::dmat3 c(0.0);
    for (const glm::dvec3& p : points) c += glm::outerProduct(p - mean, p - mean);
    return c;
}

// Sign so that the largest-magnitude component is positive (a deterministic orientation).
glm::dvec3 CanonicalSign(const glm::dvec3& v) {
    int k = 0;
    for (int i = 1; i < 3; ++i) {
        if (std::abs(v[i]) > std::abs(v[k])) k = i;
    }
    return v[k] < 0.0 ? -v : v;
}

// Any unit vector perpendicular to n: n crossed with the axis least aligned with it.
glm::dvec3 Perpendicular(const glm::dvec3& n) {
    const glm::dvec3 a = glm::abs(n);
    const glm::dvec3 axis = a.x <= a.y && a.x <= a.z ? glm::dvec3(1, 0, 0)
                            : a.y <= a.z             ? glm::dvec3(0, 1, 0)
                                                     : glm::dvec3(0, 0, 1);
    return CanonicalSign(glm::normalize(glm::cross(n, axis)));
}

// Plane frame (normal, u) of the quad: least squares, or the simpler rule for degenerate input.
std::pair<glm::dvec3, glm::dvec3> QuadFrame(std::span<const glm::dvec3> points,
                                            const glm::dvec3& centroid,
                                            const glm::dvec3& lensCentre) {
    const glm::dvec3 toLens = lensCentre - centroid;
    if (points.size() >= 3) {
        const Eigen3 e = SymmetricEigen(Covariance(points, centroid));
        const bool planar = e.values[1] > 1e-12 * std::max(e.values[2], 1e-300);
        if (planar) {
            const glm::dvec3 n =
                glm::dot(e.vectors[0], toLens) < 0.0 ? -e.vectors[0] : e.vectors[0];
            return {n, CanonicalSign(e.vectors[2])};
        }
    }
    const double len = glm::length(toLens);
    const glm::dvec3 n = len > 0.0 ? toLens / len : glm::dvec3(0, 0, 1);
    return {n, Perpendicular(n)};
}

}  // namespace

EllipsoidShell FitEllipsoid(std::span<const glm::dvec3> points, const glm::dvec3& centre) {
    std::vector<glm::dvec3> squared;
    squared.reserve(points.size());
    for (const glm::dvec3& p : points) squared.push_back((p - centre) * (p - centre));
    // Step 1: coarse grid over log2 ratios [-6, 6]^2 (includes the sphere (0, 0)).
    double a = 0.0;
    double b = 0.0;
    ShapeFit best = FitShape(squared, 0.0, 0.0);
    SearchGrid(squared, 12, 0.5, &a, &b, &best);
    // Step 2: six refinements around the best shape, halving the step.
    double step = 0.25;
    for (int round = 0; round < 6; ++round, step *= 0.5)
        SearchGrid(squared, 4, step, &a, &b, &best);
    return {centre, best.radii};
}

BoxShell FitBox(std::span<const glm::dvec3> points, std::optional<double> floorY) {
    BoxShell box{glm::dvec3(kInf), glm::dvec3(-kInf)};
    for (const glm::dvec3& p : points) {
        box.min = glm::min(box.min, p);
        box.max = glm::max(box.max, p);
    }
    if (floorY) box.min.y = *floorY;
    return box;
}

BoxShell BoxAround(const glm::dvec3& centre, double halfSize, std::optional<double> floorY) {
    BoxShell box{centre - glm::dvec3(halfSize), centre + glm::dvec3(halfSize)};
    if (floorY) box.min.y = *floorY;
    return box;
}

CylinderShell FitCylinder(std::span<const glm::dvec3> points, const glm::dvec2& axisXZ,
                          bool infinite) {
    CylinderShell c{axisXZ, 0.0, kInf, -kInf};
    double r2 = 0.0;
    for (const glm::dvec3& p : points) {
        const glm::dvec2 h(p.x - axisXZ.x, p.z - axisXZ.y);
        r2 = std::max(r2, glm::dot(h, h));
        c.yMin = std::min(c.yMin, p.y);
        c.yMax = std::max(c.yMax, p.y);
    }
    c.radius = std::sqrt(r2);
    if (infinite) {
        c.yMin = -kInf;
        c.yMax = kInf;
    }
    return c;
}

QuadShell FitQuad(std::span<const glm::dvec3> points, const glm::dvec3& lensCentre) {
    const glm::dvec3 centroid = Centroid(points);
    const auto [n, u] = QuadFrame(points, centroid, lensCentre);
    const glm::dvec3 v = glm::cross(n, u);
    // Bounding rectangle of the projected points, then recentre.
    glm::dvec2 lo(0.0);
    glm::dvec2 hi(0.0);
    for (const glm::dvec3& p : points) {
        const glm::dvec2 q(glm::dot(p - centroid, u), glm::dot(p - centroid, v));
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
    QuadShell quad;
    quad.centre = centroid + u * (0.5 * (lo.x + hi.x)) + v * (0.5 * (lo.y + hi.y));
    quad.normal = n;
    quad.u = u;
    quad.v = v;
    quad.halfExtent = 0.5 * (hi - lo);
    return quad;
}

glm::vec3 EmOrigin(std::span<const glm::vec3> positions, std::span<const uint32_t> indices) {
    glm::dvec3 weighted(0.0);
    glm::dvec3 plain(0.0);
    double area = 0.0;
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        const glm::dvec3 a(positions[indices[i]]);
        const glm::dvec3 b(positions[indices[i + 1]]);
        const glm::dvec3 c(positions[indices[i + 2]]);
        const double triArea = 0.5 * glm::length(glm::cross(b - a, c - a));
        const glm::dvec3 centroid = (a + b + c) / 3.0;
        weighted += triArea * centroid;
        plain += centroid;
        area += triArea;
    }
    const double nTris = static_cast<double>(indices.size() / 3);
    if (area > 0.0) return glm::vec3(weighted / area);
    return nTris > 0.0 ? glm::vec3(plain / nTris) : glm::vec3(0.0f);
}

}  // namespace pem::trace
