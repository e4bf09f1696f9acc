// The files cell jobs exchange (docs/cell-jobs.md describes the contract). Every file is one record:
//
//   bytes 0..7    "CPGICELL"
//   u32           format version (kCellJobFormat)
//   u32           record kind (CellJobRecord)
//   u64           payload bytes
//   payload       the record's fields, little-endian, packed (below)
//   u64           FNV-1a 64 checksum of the payload
//
// A file is written beside its final name and renamed into place, so a reader sees a whole record or
// none, and a job rerun after a lost worker rewrites the same bytes. A reader refuses a file that is
// short, of another kind or version, or whose checksum differs, with an InputError naming the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/cells/cell_round.h"
#include "radiosity/cells/first_shot_groups.h"

namespace cpgi {

/// 2: directional portals' moments; 3: binned portals' bins; 4: the figures of the stop per cell
/// (round_stop.h); 5: binned portals' bins per channel
inline constexpr uint32_t kCellJobFormat = 5;

enum class CellJobRecord : uint32_t {
  CellState = 1,       ///< a cell's own light after a round: kept, carried, radiosity gained
  PortalLight = 2,     ///< light one cell sends another in a round (every portal between them)
  Summary = 3,         ///< a cell's round in figures: what the next round's budget and the driver read
  FirstShot = 4,       ///< the lamps' first shot over the whole scene, summed and landed in the cells
  FirstShotGroup = 5,  ///< one emitter group's irradiance over the whole scene (a first-shot job)
};

/// A cell's round in figures (a CellRound without its per-texel arrays) and the job's own measures.
struct CellRoundSummary {
  int round = 0;
  CellRound figures;         ///< kept, carried, radiosity and sends' exitance left empty
  double jobSeconds = 0.0;   ///< wall time of the job's part for this cell (solve and files)
  uint64_t portalBytes = 0;  ///< bytes of the portal-light files it wrote
};

/// The first shot's results for the gather (radiosity/cells/cell_first_shot.h).
struct FirstShotRecord {
  double emitted = 0.0, landed = 0.0;
  std::vector<double> absorbed;     ///< per cell
  std::vector<glm::vec3> emission;  ///< per global texel
};

/// `round`'s state file of a cell (kept, carried, radiosity of `r`).
void writeCellState(const std::filesystem::path& file, int round, const CellRound& r);
/// Reads it into kept, carried, radiosity, cell and solved; checks round and cell.
CellRound readCellState(const std::filesystem::path& file, int round, int cell);

/// The sends of `r` to cell `to` (none when it waited); returns the file's size in bytes.
uint64_t writePortalLight(const std::filesystem::path& file, int round, const CellRound& r, int to);
/// Reads the sends of `from` to `to`.
std::vector<PortalSend> readPortalLight(const std::filesystem::path& file, int round, int from, int to);

void writeSummary(const std::filesystem::path& file, const CellRoundSummary& s);
CellRoundSummary readSummary(const std::filesystem::path& file, int round, int cell);

void writeFirstShot(const std::filesystem::path& file, const FirstShotRecord& r);
FirstShotRecord readFirstShot(const std::filesystem::path& file);

/// Group `group`'s shot (its emitters' cell, -1 for the punctual lights) over a global atlas of
/// `atlasTexels` texels.
void writeFirstShotGroup(const std::filesystem::path& file, int group, int cell, size_t atlasTexels,
                         const FirstShotContribution& c);
/// Reads it; checks group, cell and atlas size, and that every texel is in the atlas (ascending).
FirstShotContribution readFirstShotGroup(const std::filesystem::path& file, int group, int cell,
                                         size_t atlasTexels);

}  // namespace cpgi
