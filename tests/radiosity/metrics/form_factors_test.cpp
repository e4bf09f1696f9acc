#include "radiosity/metrics/form_factors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

namespace cpgi {
namespace {

using glm::dvec3;

/// A rectangle origin + s·u + t·v, s, t in [0, 1], as a 4-vertex polygon.
std::vector<dvec3> rectangle(const dvec3& origin, const dvec3& u, const dvec3& v) {
  return {origin, origin + u, origin + u + v, origin + v};
}

/// F(dA → rectangle) by brute force: the midpoint rule on n × n cells of
/// ∫ cosθ_i cosθ_j / (π r²) dA, counting only the part in front of the receiver.
double bruteForceFormFactor(const dvec3& p, const dvec3& n, const dvec3& origin, const dvec3& u,
                            const dvec3& v, int cells) {
  const dvec3 nj = glm::normalize(glm::cross(u, v));
  const double cellArea = glm::length(glm::cross(u, v)) / (double(cells) * cells);
  double sum = 0.0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const dvec3 y = origin + (i + 0.5) / cells * u + (j + 0.5) / cells * v;
      const dvec3 d = y - p;
      const double r2 = glm::dot(d, d);
      const double cosI = glm::dot(n, d) / std::sqrt(r2);
      const double cosJ = std::abs(glm::dot(nj, d)) / std::sqrt(r2);
      if (cosI > 0.0) sum += cosI * cosJ / (std::numbers::pi * r2) * cellArea;
    }
  return sum;
}

/// F(A1 → A2) = (1/A1) ∫_A1 F(dA → A2) dA by the midpoint rule over rectangle 1 with Lambert inside.
double areaToPolygon(const dvec3& origin, const dvec3& u, const dvec3& v, const dvec3& normal,
                     const std::vector<dvec3>& target, int cells) {
  double sum = 0.0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const dvec3 p = origin + (i + 0.5) / cells * u + (j + 0.5) / cells * v;
      sum += pointToPolygonFormFactor(p, normal, target);
    }
  return sum / (double(cells) * cells);
}

TEST(FormFactors, ParallelUnitSquaresAtUnitDistance) {
  EXPECT_NEAR(parallelRectanglesFormFactor(1.0, 1.0, 1.0), 0.19982, 5e-6);
}

TEST(FormFactors, PerpendicularUnitSquaresWithSharedEdge) {
  EXPECT_NEAR(perpendicularRectanglesFormFactor(1.0, 1.0, 1.0), 0.20004, 5e-6);
}

TEST(FormFactors, ClosedFormsScaleFree) {
  EXPECT_NEAR(parallelRectanglesFormFactor(2.0, 3.0, 1.5), parallelRectanglesFormFactor(4.0, 6.0, 3.0),
              1e-12);
  EXPECT_NEAR(perpendicularRectanglesFormFactor(2.0, 1.0, 0.5),
              perpendicularRectanglesFormFactor(4.0, 2.0, 1.0), 1e-12);
}

TEST(FormFactors, PerpendicularReciprocity) {
  for (const auto& [l, w, h] :
       std::vector<std::array<double, 3>>{{1.0, 2.0, 0.5}, {3.0, 0.2, 1.7}, {0.5, 4.0, 4.5}}) {
    const double f12 = perpendicularRectanglesFormFactor(l, w, h);
    const double f21 = perpendicularRectanglesFormFactor(l, h, w);
    EXPECT_NEAR(w * l * f12, h * l * f21, 1e-12 * w * l) << l << " " << w << " " << h;
    EXPECT_GT(f12, 0.0);
    EXPECT_LT(f12, 0.5);  // a plane sees at most half of its hemisphere through a perpendicular half-plane
  }
}

TEST(FormFactors, ParallelFarApartTendsToPointFormula) {
  // Two 0.1 m squares 10 m apart: F → A cos cos / (π r²) = A / (π c²).
  const double a = 0.1, c = 10.0;
  EXPECT_NEAR(parallelRectanglesFormFactor(a, a, c) / (a * a / (std::numbers::pi * c * c)), 1.0, 1e-4);
}

TEST(FormFactors, ParallelCloseTendsToOne) {
  EXPECT_NEAR(parallelRectanglesFormFactor(1.0, 1.0, 1e-4), 1.0, 1e-3);
}

TEST(FormFactors, LambertMatchesBruteForceIntegration) {
  const dvec3 origin(-0.3, 0.4, 1.2), u(1.0, 0.2, 0.0), v(0.1, 0.3, 0.9);
  const std::vector<dvec3> poly = rectangle(origin, u, v);
  const dvec3 p(0.1, -0.2, 0.0);
  for (const dvec3& n :
       {dvec3(0, 0, 1), glm::normalize(dvec3(0.3, 0.5, 1.0)), glm::normalize(dvec3(1, -0.4, 0.2))}) {
    const double exact = pointToPolygonFormFactor(p, n, poly);
    EXPECT_NEAR(exact, bruteForceFormFactor(p, n, origin, u, v, 800), 2e-5 * std::max(1.0, exact * 10.0));
    EXPECT_GT(exact, 0.0);
  }
}

TEST(FormFactors, LambertClipsPolygonPartlyBehind) {
  // A vertical square straddling the receiver's plane z = 0; only its upper half is visible.
  const dvec3 origin(-0.5, 1.0, -0.5), u(1.0, 0.0, 0.0), v(0.0, 0.0, 1.0);
  const std::vector<dvec3> poly = rectangle(origin, u, v);
  const dvec3 p(0.0, 0.0, 0.0), n(0.0, 0.0, 1.0);
  const double clipped = pointToPolygonFormFactor(p, n, poly);
  EXPECT_NEAR(clipped, bruteForceFormFactor(p, n, origin, u, v, 1000), 2e-5);
  // Equal to the front half alone.
  EXPECT_NEAR(clipped, pointToPolygonFormFactor(p, n, rectangle(dvec3(-0.5, 1.0, 0.0), u, 0.5 * v)), 1e-12);
  // Entirely behind: nothing.
  EXPECT_EQ(pointToPolygonFormFactor(p, n, rectangle(dvec3(-0.5, 1.0, -2.0), u, v)), 0.0);
}

TEST(FormFactors, LambertIndependentOfWinding) {
  std::vector<dvec3> poly = rectangle(dvec3(-1, -1, 2), dvec3(2, 0, 0), dvec3(0, 2, 0));
  const double f = pointToPolygonFormFactor(dvec3(0), dvec3(0, 0, 1), poly);
  std::reverse(poly.begin(), poly.end());
  EXPECT_NEAR(f, pointToPolygonFormFactor(dvec3(0), dvec3(0, 0, 1), poly), 1e-15);
}

TEST(FormFactors, LambertInfinitePlaneIsOne) {
  const double big = 1e5;
  const std::vector<dvec3> plane =
      rectangle(dvec3(-big, -big, 1.0), dvec3(2 * big, 0, 0), dvec3(0, 2 * big, 0));
  EXPECT_NEAR(pointToPolygonFormFactor(dvec3(0), dvec3(0, 0, 1), plane), 1.0, 1e-4);
}

TEST(FormFactors, LambertDiskOnAxisClosedForm) {
  // A regular 256-gon approximates a disk of radius R at height h: F = R² / (R² + h²).
  const double radius = 0.7, h = 1.3;
  const int sides = 256;
  std::vector<dvec3> poly;
  for (int k = 0; k < sides; ++k) {
    const double a = 2.0 * std::numbers::pi * k / sides;
    poly.emplace_back(radius * std::cos(a), radius * std::sin(a), h);
  }
  // The polygon's area is sin(2π/n)·n/(2π) of the disk's; compare against the inscribed polygon's value.
  const double polygonArea = 0.5 * sides * radius * radius * std::sin(2.0 * std::numbers::pi / sides);
  const double diskArea = std::numbers::pi * radius * radius;
  const double expected = radius * radius / (radius * radius + h * h);
  EXPECT_NEAR(pointToPolygonFormFactor(dvec3(0), dvec3(0, 0, 1), poly), expected,
              expected * (1 - polygonArea / diskArea) * 1.5 + 1e-9);
}

TEST(FormFactors, LambertFarAwayTendsToPointFormula) {
  const dvec3 p(0.0), n = glm::normalize(dvec3(0.2, 0.1, 1.0));
  const dvec3 centre(3.0, -2.0, 20.0);
  const dvec3 nj = glm::normalize(dvec3(-0.1, 0.4, -1.0));
  const dvec3 u = 0.01 * glm::normalize(glm::cross(nj, dvec3(1, 0, 0)));
  const dvec3 v = glm::cross(nj, u);
  const std::vector<dvec3> poly = rectangle(centre - 0.5 * u - 0.5 * v, u, v);
  const dvec3 d = centre - p;
  const double r2 = glm::dot(d, d);
  const double approx =
      glm::dot(u, u) * glm::dot(n, d) * std::abs(glm::dot(nj, d)) / (r2 * r2 * std::numbers::pi);
  EXPECT_NEAR(pointToPolygonFormFactor(p, n, poly) / approx, 1.0, 1e-6);
}

TEST(FormFactors, LambertIntegratedMatchesParallelClosedForm) {
  const std::vector<dvec3> top = rectangle(dvec3(0, 0, 1), dvec3(1, 0, 0), dvec3(0, 1, 0));
  const double f = areaToPolygon(dvec3(0), dvec3(1, 0, 0), dvec3(0, 1, 0), dvec3(0, 0, 1), top, 100);
  EXPECT_NEAR(f, parallelRectanglesFormFactor(1.0, 1.0, 1.0), 2e-5);
}

TEST(FormFactors, LambertIntegratedMatchesPerpendicularClosedForm) {
  // Rectangle 1: floor [0,l]×[0,w] at z = 0; rectangle 2: wall x ∈ [0,l], y = 0, z ∈ [0,h].
  const double l = 1.0, w = 2.0, h = 0.5;
  const std::vector<dvec3> wall = rectangle(dvec3(0), dvec3(l, 0, 0), dvec3(0, 0, h));
  const double f = areaToPolygon(dvec3(0), dvec3(l, 0, 0), dvec3(0, w, 0), dvec3(0, 0, 1), wall, 400);
  // The integrand has a logarithmic singularity at the shared edge; the midpoint rule converges slowly.
  EXPECT_NEAR(f, perpendicularRectanglesFormFactor(l, w, h), 1e-3);
}

TEST(FormFactors, LambertReciprocityBetweenTiltedRectangles) {
  const dvec3 o1(0, 0, 0), u1(1.0, 0, 0), v1(0, 0.6, 0.0);
  const dvec3 o2(0.3, -0.2, 0.8), u2(0.7, 0.1, 0.2), v2(-0.1, 0.9, 0.3);
  const dvec3 n1 = glm::normalize(glm::cross(u1, v1));
  const dvec3 n2 = -glm::normalize(glm::cross(u2, v2));  // facing rectangle 1
  const double a1 = glm::length(glm::cross(u1, v1)), a2 = glm::length(glm::cross(u2, v2));
  const double f12 = areaToPolygon(o1, u1, v1, n1, rectangle(o2, u2, v2), 120);
  const double f21 = areaToPolygon(o2, u2, v2, n2, rectangle(o1, u1, v1), 120);
  EXPECT_GT(f12, 0.05);
  EXPECT_NEAR(a1 * f12, a2 * f21, 1e-4 * a1 * f12);
}

}  // namespace
}  // namespace cpgi
