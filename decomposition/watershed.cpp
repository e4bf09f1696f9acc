#include "decomposition/watershed.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace cpgi::decomp {
namespace {

// Labels every empty voxel of the grid's border as basin 0, the outside (no contacts: nothing else is
// labelled yet).
void markOutside(const DistanceGrid& distance, WatershedLabels& out) {
  const GridFrame& f = distance.frame;
  for (int z = 0; z < f.dims.z; ++z)
    for (int y = 0; y < f.dims.y; ++y) {
      const bool wholeRow = z == 0 || y == 0 || z == f.dims.z - 1 || y == f.dims.y - 1;
      for (int x = 0; x < f.dims.x; x += (wholeRow ? 1 : std::max(1, f.dims.x - 1))) {
        const size_t i = f.index(x, y, z);
        if (!distance.d2[i]) continue;
        if (out.outsideBasin < 0) {
          out.outsideBasin = 0;
          out.peak.push_back(0.0f);
          out.volume.push_back(0);
        }
        out.basin[i] = 0;
        ++out.volume[0];
      }
    }
}

}  // namespace

WatershedLabels floodWatershed(const DistanceGrid& distance, const WatershedParams& params, Context& ctx) {
  auto timer = ctx.time("watershed");
  const GridFrame& f = distance.frame;
  const size_t n = f.count();
  WatershedLabels out;
  out.frame = f;
  out.basin.assign(n, -1);

  // Bucket the inside voxels by level, highest first (a counting sort: levels are few).
  const double step = params.levelStep > 0.0 ? params.levelStep : 0.5;
  auto levelOf = [&](uint32_t d2) { return int(std::sqrt(double(d2)) / step); };
  const int levels = levelOf(distance.maxD2) + 1;
  // The border layer is the outside marker, not flooded level by level: every other empty voxel is
  // still unlabelled.
  markOutside(distance, out);
  auto flooded = [&](size_t i) { return distance.d2[i] && out.basin[i] < 0; };
  std::vector<size_t> start(size_t(levels) + 1, 0);
  for (size_t i = 0; i < n; ++i)
    if (flooded(i)) ++start[size_t(levels - 1 - levelOf(distance.d2[i])) + 1];
  for (int l = 0; l < levels; ++l) start[size_t(l) + 1] += start[size_t(l)];
  // 32-bit voxel indices (voxelize's limit keeps grids far below 2³²): half the memory of size_t.
  if (n > std::numeric_limits<uint32_t>::max()) throw std::length_error("watershed: more than 2^32 voxels");
  std::vector<uint32_t> order(start.back());
  {
    std::vector<size_t> fillAt(start.begin(), start.end() - 1);
    for (size_t i = 0; i < n; ++i)
      if (flooded(i)) order[fillAt[size_t(levels - 1 - levelOf(distance.d2[i]))]++] = uint32_t(i);
  }

  // Only voxels off the border are flooded, so face neighbours of a flooded voxel are in range.
  const ptrdiff_t sy = f.dims.x, sz = ptrdiff_t(f.dims.x) * f.dims.y;
  const ptrdiff_t offsets[6] = {-1, 1, -sy, sy, -sz, sz};
  std::vector<uint8_t> atLevel(n, 0);
  std::unordered_map<uint64_t, BasinContact> contacts;
  auto metres = [&](size_t i) { return float(std::sqrt(double(distance.d2[i])) * f.voxel); };

  // Labels voxel i with basin b and records its contacts with already-labelled neighbours.
  auto label = [&](size_t i, int b) {
    out.basin[i] = b;
    ++out.volume[size_t(b)];
    for (int k = 0; k < 6; ++k) {
      const size_t j = size_t(ptrdiff_t(i) + offsets[k]);
      const int nb = out.basin[j];
      if (nb < 0 || nb == b) continue;
      const int lo = std::min(nb, b), hi = std::max(nb, b);
      BasinContact& c = contacts[(uint64_t(uint32_t(lo)) << 32) | uint32_t(hi)];
      c.a = lo, c.b = hi;
      // The lower of the two distances, converted once it is known to be needed.
      c.saddle = std::max(c.saddle, metres(distance.d2[i] < distance.d2[j] ? i : j));
      ++c.faces;
      if (k == 2 || k == 3) ++c.facesUp;
    }
  };

  std::vector<size_t> queue;
  for (int l = 0; l < levels; ++l) {
    const size_t lo = start[size_t(l)], hi = start[size_t(l) + 1];
    for (size_t k = lo; k < hi; ++k) atLevel[order[k]] = 1;

    // 1. Existing basins expand into this level, breadth-first, each voxel taking the basin of the
    //    neighbour that reached it first.
    queue.clear();
    for (size_t k = lo; k < hi; ++k) {
      const size_t i = order[k];
      for (ptrdiff_t o : offsets)
        if (out.basin[size_t(ptrdiff_t(i) + o)] >= 0) {
          queue.push_back(i);
          break;
        }
    }
    for (size_t head = 0; head < queue.size(); ++head) {
      const size_t i = queue[head];
      if (out.basin[i] >= 0) continue;
      // The first labelled neighbour in wavefront order: prefer the highest, so ties go uphill.
      int best = -1;
      uint32_t bestD = 0;
      for (ptrdiff_t o : offsets) {
        const size_t j = size_t(ptrdiff_t(i) + o);
        if (out.basin[j] >= 0 && distance.d2[j] >= bestD) best = out.basin[j], bestD = distance.d2[j];
      }
      label(i, best);
      for (ptrdiff_t o : offsets) {
        const size_t j = size_t(ptrdiff_t(i) + o);
        if (atLevel[j] && out.basin[j] < 0) queue.push_back(j);
      }
    }

    // 2. What is left of the level starts new basins, one per connected patch.
    for (size_t k = lo; k < hi; ++k) {
      const size_t seed = order[k];
      if (out.basin[seed] >= 0) continue;
      const int b = int(out.peak.size());
      out.peak.push_back(0.0f);
      out.volume.push_back(0);
      queue.assign(1, seed);
      label(seed, b);
      for (size_t head = 0; head < queue.size(); ++head) {
        const size_t i = queue[head];
        out.peak[size_t(b)] = std::max(out.peak[size_t(b)], metres(i));
        for (ptrdiff_t o : offsets) {
          const size_t j = size_t(ptrdiff_t(i) + o);
          if (atLevel[j] && out.basin[j] < 0) label(j, b), queue.push_back(j);
        }
      }
    }
    for (size_t k = lo; k < hi; ++k) atLevel[order[k]] = 0;
    if ((l & 15) == 0) ctx.progress("watershed", double(l) / levels);
  }

  if (out.outsideBasin >= 0)
    for (size_t i = 0; i < n; ++i)
      if (out.basin[i] == out.outsideBasin)
        out.peak[size_t(out.outsideBasin)] = std::max(out.peak[size_t(out.outsideBasin)], metres(i));
  out.contacts.reserve(contacts.size());
  for (const auto& [key, c] : contacts) out.contacts.push_back(c);
  std::sort(out.contacts.begin(), out.contacts.end(),
            [](const BasinContact& x, const BasinContact& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  ctx.progress("watershed", 1.0);
  return out;
}

}  // namespace cpgi::decomp
