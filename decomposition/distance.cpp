#include "decomposition/distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

namespace cpgi::decomp {
namespace {

// Squared distances are computed in 64 bits along a line and stored in the grid's 32 bits between the
// passes; kFar (no solid voxel on the lines so far) is the largest stored value, and finite squared
// distances saturate just below it (past 65 535 voxels, more than any grid the decomposition allows).
constexpr uint32_t kFar = std::numeric_limits<uint32_t>::max();
constexpr int64_t kFarLine = int64_t(1) << 40;

// One pass of the 1D squared distance transform along a line of n samples with the given stride:
// d[i] = min_j (f[j] + (i - j)²). v/z/f are scratch of size n + 1, n + 2, n.
void transformLine(uint32_t* data, int n, size_t stride, std::vector<int>& v, std::vector<double>& z,
                   std::vector<int64_t>& f) {
  for (int i = 0; i < n; ++i) {
    const uint32_t d = data[size_t(i) * stride];
    f[size_t(i)] = d == kFar ? kFarLine : int64_t(d);
  }
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] >= kFarLine) continue;
    while (k >= 0) {
      const int p = v[k];
      const double s = (double(f[q] + int64_t(q) * q) - double(f[p] + int64_t(p) * p)) / (2.0 * (q - p));
      if (s <= z[k]) --k;
      else break;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -std::numeric_limits<double>::infinity()
                  : (double(f[q] + int64_t(q) * q) - double(f[v[k - 1]] + int64_t(v[k - 1]) * v[k - 1])) /
                        (2.0 * (q - v[k - 1]));
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  if (k < 0) return;  // no finite sample on this line: stays far
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < q) ++j;
    const int64_t dq = q - v[j];
    data[size_t(q) * stride] = uint32_t(std::min<int64_t>(f[v[j]] + dq * dq, int64_t(kFar) - 1));
  }
}

}  // namespace

DistanceGrid distanceToGeometry(const SolidGrid& solid, const SpaceGrid& space, Context& ctx) {
  auto timer = ctx.time("distance");
  const GridFrame& f = solid.frame;
  DistanceGrid out;
  out.frame = f;
  // Transformed in place: solid voxels are the sources, every other voxel starts far.
  std::vector<uint32_t>& d = out.d2;
  d.resize(f.count());
  for (size_t i = 0; i < d.size(); ++i) d[i] = solid.solid[i] ? 0 : kFar;

  const int nx = f.dims.x, ny = f.dims.y, nz = f.dims.z;
  const size_t sx = 1, sy = size_t(nx), sz = size_t(nx) * size_t(ny);
  auto pass = [&](int lines, int n, size_t stride, auto lineStart) {
    tbb::parallel_for(tbb::blocked_range<int>(0, lines), [&](const tbb::blocked_range<int>& r) {
      std::vector<int> v(size_t(n) + 1);
      std::vector<double> z(size_t(n) + 2);
      std::vector<int64_t> buf(static_cast<size_t>(n));
      for (int line = r.begin(); line != r.end(); ++line)
        transformLine(d.data() + lineStart(line), n, stride, v, z, buf);
    });
  };
  pass(ny * nz, nx, sx, [&](int line) { return size_t(line) * sy; });
  pass(nx * nz, ny, sy, [&](int line) { return size_t(line % nx) + size_t(line / nx) * sz; });
  pass(nx * ny, nz, sz, [&](int line) { return size_t(line); });

  // Only inside and outside voxels keep their distance.
  for (size_t i = 0; i < d.size(); ++i) {
    if (space.space[i] != Space::Inside && space.space[i] != Space::Outside) d[i] = 0;
    out.maxD2 = std::max(out.maxD2, d[i]);
  }
  ctx.progress("distance", 1.0);
  return out;
}

}  // namespace cpgi::decomp
