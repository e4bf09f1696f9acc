// Exact form factors, the oracles that every approximation in cpgi is measured against (design.md §5).
// They share nothing with the solvers: closed forms from Siegel & Howell's catalogue ("Thermal Radiation
// Heat Transfer", configurations C-11 and C-14) and Lambert's contour integral (Lambert 1760; the form of
// Baum, Rushmeier & Winget, "Improving radiosity solutions through the use of analytically determined
// form-factors", SIGGRAPH 1989). Everything is in double precision.
#pragma once

#include <span>

#include <glm/glm.hpp>

namespace cpgi {

/// Differential-area-to-polygon form factor F(dA → A) by Lambert's contour formula
///   F = (1/2π) Σ_i γ_i · n·(R_i × R_{i+1}) / |R_i × R_{i+1}|,
/// where R_i = v_i − point and γ_i is the angle between R_i and R_{i+1}.
/// The polygon is first clipped to the half-space in front of the point (n·(x − point) > 0), so polygons
/// partly or wholly behind the receiver's plane are handled; the result is ≥ 0 whatever the winding.
/// @param point    receiver position (metres)
/// @param normal   receiver unit normal
/// @param polygon  planar simple polygon, ≥ 3 vertices in boundary order (either winding)
/// Occlusion is not considered: this is the unoccluded form factor.
double pointToPolygonFormFactor(const glm::dvec3& point, const glm::dvec3& normal,
                                std::span<const glm::dvec3> polygon);

/// F(1 → 2) between two parallel, directly opposed a × b rectangles a distance c apart
/// (Siegel & Howell C-11). Unit squares at unit distance: 0.19982.
/// @param a, b  rectangle sides (metres, > 0);  @param c  separation (metres, > 0)
double parallelRectanglesFormFactor(double a, double b, double c);

/// F(1 → 2) between two perpendicular rectangles sharing an edge of length l (Siegel & Howell C-14).
/// Rectangle 1 extends `w` away from the shared edge, rectangle 2 extends `h`.
/// Unit squares: 0.20004. Reciprocity: w·F(l, w, h) = h·F(l, h, w).
/// @param l  shared edge length; @param w  width of rectangle 1; @param h  width of rectangle 2 (metres, > 0)
double perpendicularRectanglesFormFactor(double l, double w, double h);

}  // namespace cpgi
