#include "radiosity/metrics/form_factors.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace cpgi {

namespace {

/// Sutherland–Hodgman against one plane: keeps the part of the polygon with n·(x − p) ≥ 0.
/// A clip of a simple polygon by one plane may leave zero-width "bridges" along the plane when the
/// polygon is not convex; their two edges cancel in the contour integral, so they do no harm.
std::vector<glm::dvec3> clipToFront(const glm::dvec3& p, const glm::dvec3& n,
                                    std::span<const glm::dvec3> poly) {
  std::vector<glm::dvec3> out;
  out.reserve(poly.size() + 2);
  const size_t count = poly.size();
  for (size_t i = 0; i < count; ++i) {
    const glm::dvec3& a = poly[i];
    const glm::dvec3& b = poly[(i + 1) % count];
    const double da = glm::dot(n, a - p);
    const double db = glm::dot(n, b - p);
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) {
      const double t = da / (da - db);
      out.push_back(a + t * (b - a));
    }
  }
  return out;
}

}  // namespace

double pointToPolygonFormFactor(const glm::dvec3& point, const glm::dvec3& normal,
                                std::span<const glm::dvec3> polygon) {
  if (polygon.size() < 3) return 0.0;
  const std::vector<glm::dvec3> front = clipToFront(point, normal, polygon);
  if (front.size() < 3) return 0.0;

  double sum = 0.0;
  const size_t count = front.size();
  for (size_t i = 0; i < count; ++i) {
    const glm::dvec3 r0 = front[i] - point;
    const glm::dvec3 r1 = front[(i + 1) % count] - point;
    const glm::dvec3 c = glm::cross(r0, r1);
    const double cl = glm::length(c);
    // An edge seen end-on (collinear with the point) or of zero length subtends no angle.
    if (cl <= 1e-300) continue;
    const double gamma = std::atan2(cl, glm::dot(r0, r1));
    sum += gamma * glm::dot(normal, c) / cl;
  }
  // The sign follows the polygon's winding as seen from the point; the form factor is its magnitude.
  return std::abs(sum) / (2.0 * std::numbers::pi);
}

double parallelRectanglesFormFactor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double x2 = x * x, y2 = y * y;
  const double sx = std::sqrt(1.0 + x2), sy = std::sqrt(1.0 + y2);
  const double bracket = 0.5 * std::log((1.0 + x2) * (1.0 + y2) / (1.0 + x2 + y2)) +
                         x * sy * std::atan(x / sy) + y * sx * std::atan(y / sx) - x * std::atan(x) -
                         y * std::atan(y);
  return 2.0 / (std::numbers::pi * x * y) * bracket;
}

double perpendicularRectanglesFormFactor(double l, double w, double h) {
  const double W = w / l, H = h / l;
  const double w2 = W * W, h2 = H * H, s2 = w2 + h2;
  const double s = std::sqrt(s2);
  // The logarithm of the catalogue's product, taken term by term so large W or H cannot overflow.
  const double logTerm = std::log((1.0 + w2) * (1.0 + h2) / (1.0 + s2)) +
                         w2 * std::log(w2 * (1.0 + s2) / ((1.0 + w2) * s2)) +
                         h2 * std::log(h2 * (1.0 + s2) / ((1.0 + h2) * s2));
  const double bracket =
      W * std::atan(1.0 / W) + H * std::atan(1.0 / H) - s * std::atan(1.0 / s) + 0.25 * logTerm;
  return bracket / (std::numbers::pi * W);
}

}  // namespace cpgi
