#include "radiosity/cells/cell_job_files.h"

#include <unistd.h>
#include <cstring>
#include <fstream>
#include <string_view>
#include <system_error>

#include "core/error.h"

namespace cpgi {
namespace {

constexpr char kMagic[8] = {'C', 'P', 'G', 'I', 'C', 'E', 'L', 'L'};
constexpr size_t kHeader = 8 + 4 + 4 + 8, kTrailer = 8;

uint64_t fnv1a(std::string_view bytes) {
  uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  return h;
}

// The whole file in one read: a gather reads tens of MB of records, and an istreambuf_iterator's byte at a
// time cost as much as the checksum.
bool readWholeFile(const std::filesystem::path& file, std::string& out) {
  std::ifstream f(file, std::ios::binary | std::ios::ate);
  if (!f) return false;
  const std::streamoff size = f.tellg();
  if (size < 0) return false;
  out.resize(size_t(size));
  f.seekg(0);
  return bool(f.read(out.data(), size));
}

// The payload of a record, field after field (the machines that run cpgi are little-endian).
class Writer {
 public:
  template <class T>
  void put(const T& v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <class V>
  void putVecs(const std::vector<V>& v) {
    put(uint64_t(v.size()));
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(V));
  }
  void putVec3s(const std::vector<glm::vec3>& v) { putVecs(v); }
  // Written next to `file` and renamed over it: a reader sees the whole record or none.
  uint64_t save(const std::filesystem::path& file, CellJobRecord kind) const {
    std::string out(kMagic, 8);
    auto append = [&](const auto& v) { out.append(reinterpret_cast<const char*>(&v), sizeof(v)); };
    append(kCellJobFormat);
    append(uint32_t(kind));
    append(uint64_t(bytes_.size()));
    out += bytes_;
    append(fnv1a(bytes_));
    const std::filesystem::path part = file.string() + ".part-" + std::to_string(::getpid());
    {
      std::ofstream f(part, std::ios::binary | std::ios::trunc);
      f.write(out.data(), std::streamsize(out.size()));
      f.flush();
      if (!f) throw SystemError(file.string() + ": cannot write the cell job file");
    }
    std::error_code ec;
    std::filesystem::rename(part, file, ec);
    if (ec) {
      std::filesystem::remove(part, ec);
      throw SystemError(file.string() + ": cannot write the cell job file");
    }
    return out.size();
  }

 private:
  std::string bytes_;
};

class Reader {
 public:
  Reader(const Reader&) = delete;  // bytes_ views all_
  Reader& operator=(const Reader&) = delete;
  Reader(const std::filesystem::path& file, CellJobRecord kind) : file_(file.string()) {
    if (!readWholeFile(file, all_))
      fail("cannot read the cell job file (missing? run the job that writes it first)");
    const std::string& all = all_;
    if (all.size() < kHeader + kTrailer || std::memcmp(all.data(), kMagic, 8) != 0)
      fail("not a cpgi cell job file (or truncated)");
    uint32_t version = 0, k = 0;
    uint64_t size = 0;
    std::memcpy(&version, all.data() + 8, 4);
    std::memcpy(&k, all.data() + 12, 4);
    std::memcpy(&size, all.data() + 16, 8);
    if (version != kCellJobFormat)
      fail("cell job format " + std::to_string(version) + ", this cpgi reads " +
           std::to_string(kCellJobFormat));
    if (k != uint32_t(kind)) fail("a cell job file of another kind");
    if (size != all.size() - kHeader - kTrailer) fail("truncated cell job file");
    bytes_ = std::string_view(all).substr(kHeader, size);
    uint64_t sum = 0;
    std::memcpy(&sum, all.data() + kHeader + size, 8);
    if (sum != fnv1a(bytes_)) fail("checksum mismatch (damaged cell job file)");
  }
  template <class T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  template <class V>
  std::vector<V> getVecs() {
    const uint64_t n = get<uint64_t>();
    if (n > (bytes_.size() - at_) / sizeof(V)) fail("an array longer than the file");
    std::vector<V> v(n);
    if (n > 0)
      std::memcpy(v.data(), bytes_.data() + at_, n * sizeof(V));  // an empty vector's data() may be null
    at_ += n * sizeof(V);
    return v;
  }
  std::vector<glm::vec3> getVec3s() { return getVecs<glm::vec3>(); }
  void end() const {
    if (at_ != bytes_.size()) fail("bytes left over after the record");
  }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(file_, problem); }
  void expect(bool ok, const std::string& problem) const {
    if (!ok) fail(problem);
  }

 private:
  void need(size_t n) const {
    if (bytes_.size() - at_ < n) fail("record shorter than its fields");
  }
  std::string file_, all_;  ///< all_: the whole file
  std::string_view bytes_;  ///< the payload, in all_
  size_t at_ = 0;
};

void putFigures(Writer& w, const CellRound& r) {
  w.put(int32_t(r.cell));
  w.put(uint8_t(r.solved));
  w.put(r.keptPower), w.put(r.keptRgb), w.put(r.reflectorGain);
  w.put(int32_t(r.shots));
  for (double v : {r.seconds, r.shot, r.received, r.escaped, r.created, r.worstShotGain, r.absorbed})
    w.put(v);
}

CellRound getFigures(Reader& in) {
  CellRound r;
  r.cell = in.get<int32_t>();
  r.solved = in.get<uint8_t>() != 0;
  r.keptPower = in.get<double>();
  r.keptRgb = in.get<glm::dvec3>();
  r.reflectorGain = in.get<double>();
  r.shots = in.get<int32_t>();
  for (double* v : {&r.seconds, &r.shot, &r.received, &r.escaped, &r.created, &r.worstShotGain, &r.absorbed})
    *v = in.get<double>();
  return r;
}

// Binned portals' bins per texel: count, then (texel, bins) in texel order.
void putTexelBins(Writer& w, const std::map<int32_t, ArrivalBins>& bins) {
  w.put(uint64_t(bins.size()));
  for (const auto& [t, b] : bins) w.put(t), w.put(b);
}

std::map<int32_t, ArrivalBins> getTexelBins(Reader& in) {
  std::map<int32_t, ArrivalBins> bins;
  const uint64_t n = in.get<uint64_t>();
  for (uint64_t k = 0; k < n; ++k) {
    const int32_t t = in.get<int32_t>();
    in.expect(t >= 0, "bins for a negative texel");
    bins[t] = in.get<ArrivalBins>();
  }
  return bins;
}

void putSendFigures(Writer& w, const PortalSend& s) {
  w.put(int32_t(s.portal)), w.put(int32_t(s.from)), w.put(int32_t(s.to));
  w.put(s.scale);
  w.put(s.watts), w.put(s.arriving), w.put(s.arrivingRgb);
}

PortalSend getSendFigures(Reader& in) {
  PortalSend s;
  s.portal = in.get<int32_t>(), s.from = in.get<int32_t>(), s.to = in.get<int32_t>();
  s.scale = in.get<glm::vec3>();
  s.watts = in.get<double>(), s.arriving = in.get<double>();
  s.arrivingRgb = in.get<glm::dvec3>();
  return s;
}

}  // namespace

void writeCellState(const std::filesystem::path& file, int round, const CellRound& r) {
  Writer w;
  w.put(int32_t(round)), w.put(int32_t(r.cell)), w.put(uint8_t(r.solved));
  w.putVec3s(r.kept), w.putVec3s(r.carried), w.putVec3s(r.radiosity);
  w.putVecs(r.keptMoments);
  putTexelBins(w, r.keptBins);
  w.save(file, CellJobRecord::CellState);
}

CellRound readCellState(const std::filesystem::path& file, int round, int cell) {
  Reader in(file, CellJobRecord::CellState);
  CellRound r;
  in.expect(in.get<int32_t>() == round, "of another round");
  r.cell = in.get<int32_t>();
  in.expect(r.cell == cell, "of another cell");
  r.solved = in.get<uint8_t>() != 0;
  r.kept = in.getVec3s(), r.carried = in.getVec3s(), r.radiosity = in.getVec3s();
  r.keptMoments = in.getVecs<glm::vec4>();
  r.keptBins = getTexelBins(in);
  in.expect(r.carried.size() == r.kept.size(), "carried and kept light of different sizes");
  in.expect(r.keptMoments.empty() || r.keptMoments.size() == r.kept.size(),
            "kept light and its moments of different sizes");
  in.end();
  return r;
}

uint64_t writePortalLight(const std::filesystem::path& file, int round, const CellRound& r, int to) {
  Writer w;
  w.put(int32_t(round)), w.put(int32_t(r.cell)), w.put(int32_t(to));
  uint32_t n = 0;
  for (const PortalSend& s : r.sends) n += s.to == to;
  w.put(n);
  for (const PortalSend& s : r.sends) {
    if (s.to != to) continue;
    putSendFigures(w, s);
    w.put(uint64_t(s.exitance.size()));
    for (const auto& [t, e] : s.exitance) w.put(t), w.put(e);
    w.putVecs(s.moments);
    w.putVecs(s.bins);
  }
  return w.save(file, CellJobRecord::PortalLight);
}

std::vector<PortalSend> readPortalLight(const std::filesystem::path& file, int round, int from, int to) {
  Reader in(file, CellJobRecord::PortalLight);
  in.expect(in.get<int32_t>() == round, "of another round");
  in.expect(in.get<int32_t>() == from && in.get<int32_t>() == to, "between other cells");
  std::vector<PortalSend> sends(in.get<uint32_t>());
  for (PortalSend& s : sends) {
    s = getSendFigures(in);
    in.expect(s.from == from && s.to == to, "a send between other cells");
    const uint64_t n = in.get<uint64_t>();
    for (uint64_t k = 0; k < n; ++k) {
      const int32_t t = in.get<int32_t>();
      in.expect(t >= 0, "a negative texel");
      s.exitance.push_back({t, in.get<glm::vec3>()});
    }
    s.moments = in.getVecs<glm::vec4>();
    in.expect(s.moments.empty() || s.moments.size() == s.exitance.size(),
              "exitance and its moments of different sizes");
    s.bins = in.getVecs<ArrivalBins>();
    in.expect(s.bins.empty() || s.bins.size() == s.exitance.size(),
              "exitance and its bins of different sizes");
  }
  in.end();
  return sends;
}

void writeSummary(const std::filesystem::path& file, const CellRoundSummary& s) {
  Writer w;
  w.put(int32_t(s.round));
  putFigures(w, s.figures);
  w.put(uint32_t(s.figures.sends.size()));
  for (const PortalSend& send : s.figures.sends) putSendFigures(w, send);
  w.put(s.jobSeconds), w.put(s.portalBytes);
  w.save(file, CellJobRecord::Summary);
}

CellRoundSummary readSummary(const std::filesystem::path& file, int round, int cell) {
  Reader in(file, CellJobRecord::Summary);
  CellRoundSummary s;
  s.round = in.get<int32_t>();
  in.expect(s.round == round, "of another round");
  s.figures = getFigures(in);
  in.expect(s.figures.cell == cell, "of another cell");
  s.figures.sends.resize(in.get<uint32_t>());
  for (PortalSend& send : s.figures.sends) send = getSendFigures(in);
  s.jobSeconds = in.get<double>(), s.portalBytes = in.get<uint64_t>();
  in.end();
  return s;
}

void writeFirstShot(const std::filesystem::path& file, const FirstShotRecord& r) {
  Writer w;
  w.put(r.emitted), w.put(r.landed);
  w.put(uint64_t(r.absorbed.size()));
  for (double a : r.absorbed) w.put(a);
  w.putVec3s(r.emission);
  w.save(file, CellJobRecord::FirstShot);
}

FirstShotRecord readFirstShot(const std::filesystem::path& file) {
  Reader in(file, CellJobRecord::FirstShot);
  FirstShotRecord r;
  r.emitted = in.get<double>(), r.landed = in.get<double>();
  const uint64_t n = in.get<uint64_t>();
  for (uint64_t k = 0; k < n; ++k) r.absorbed.push_back(in.get<double>());
  r.emission = in.getVec3s();
  in.end();
  return r;
}

void writeFirstShotGroup(const std::filesystem::path& file, int group, int cell, size_t atlasTexels,
                         const FirstShotContribution& c) {
  Writer w;
  w.put(int32_t(group)), w.put(int32_t(cell)), w.put(uint64_t(atlasTexels));
  w.put(c.emitted), w.put(int32_t(c.shots)), w.put(c.seconds);
  w.put(uint64_t(c.texels.size()));
  for (uint32_t t : c.texels) w.put(t);
  w.putVec3s(c.incident);
  w.save(file, CellJobRecord::FirstShotGroup);
}

FirstShotContribution readFirstShotGroup(const std::filesystem::path& file, int group, int cell,
                                         size_t atlasTexels) {
  Reader in(file, CellJobRecord::FirstShotGroup);
  in.expect(in.get<int32_t>() == group, "the shot of another emitter group than its name says");
  in.expect(in.get<int32_t>() == cell, "the shot of another cell's emitters than the plan's group");
  in.expect(in.get<uint64_t>() == atlasTexels, "made for another atlas than the plan's");
  FirstShotContribution c;
  c.emitted = in.get<double>(), c.shots = in.get<int32_t>(), c.seconds = in.get<double>();
  const uint64_t n = in.get<uint64_t>();
  in.expect(n <= atlasTexels, "more texels than the atlas has");
  c.texels.reserve(n);
  for (uint64_t k = 0; k < n; ++k) {
    c.texels.push_back(in.get<uint32_t>());
    in.expect(c.texels.back() < atlasTexels && (k == 0 || c.texels[k - 1] < c.texels.back()),
              "a texel outside the atlas or out of order");
  }
  c.incident = in.getVec3s();
  in.expect(c.incident.size() == n, "as many irradiances as texels expected");
  in.end();
  return c;
}

}  // namespace cpgi
