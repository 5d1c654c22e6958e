#include "stress/stress.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <string_view>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "common/json_keys.h"
#include "driver/job.h"
#include "driver/report.h"
#include "oracle/exact.h"

namespace lancer::stress {

namespace {

constexpr std::array<const char*, 4> kVerdictKeys = {"correct", "tie", "within_bound", "beyond_bound"};

// A ray id or null, as the report writes the first rays of a kind.
struct OptionalJson {
  nlohmann::json operator()(const std::optional<uint32_t>& v) const { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }
};

double share(uint64_t part, uint64_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0.0; }

// The hardware's answers of one path and model on the base placement, for the invariance check.
struct BaseAnswers {
  std::vector<std::optional<QuantizedRay>> rays;
  std::vector<std::optional<fx::IsectResult>> hits;
};

bool sameQuantizedRay(const std::optional<QuantizedRay>& a, const std::optional<QuantizedRay>& b) {
  return a.has_value() == b.has_value() && (!a || a->q == b->q);
}

// Whether ray i's answer differs from the base placement's: every bit of the
// lattice ray and of the hit record when the lattice is the same, the hit and
// its triangle otherwise.
bool differsFromBase(const JobResult& job, const BaseAnswers& base, size_t i, bool latticeExact) {
  if (latticeExact) return !sameQuantizedRay(job.rays[i], base.rays[i]) || job.hits[i] != base.hits[i];
  const auto& a = job.hits[i];
  const auto& b = base.hits[i];
  return a.has_value() != b.has_value() || (a && a->primId != b->primId);
}

std::string describeHit(const std::optional<Hit>& hit) {
  return hit ? fmt::format("triangle {} at t {:.9g}", hit->prim, hit->t) : "miss";
}

std::string describeBeyond(const Ray& ray, const Judgement& judgement, const std::optional<Hit>& hardware,
                           const std::optional<ExactHit>& truth) {
  return fmt::format("{}: ray origin ({:a}, {:a}, {:a}) dir ({:a}, {:a}, {:a}); hardware {}, exact {}",
                     judgement.reason, ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z,
                     describeHit(hardware),
                     truth ? fmt::format("triangle {} at t {:.9g}{}", truth->prim, truth->t,
                                         truth->onBoundary ? " (on its boundary)" : "")
                           : "miss");
}

// The scene as the hardware holds it: every triangle's lattice integers.
Scene latticeScene(const Scene& scene, const Quantizer& quantizer) {
  Scene out;
  out.name = scene.name + " on the lattice";
  for (const fx::QTriangle& q : quantizer.quantize(scene)) {
    const auto vertex = [&](int k) { return glm::vec3(float(q.v[k][0]), float(q.v[k][1]), float(q.v[k][2])); };
    out.triangles.push_back({vertex(0), vertex(1), vertex(2)});
  }
  out.materials.push_back(Material{});
  out.materialOf.assign(out.size(), 0);
  out.computeBounds();
  return out;
}

// Whether the hardware's ray, exactly, misses the hardware's mesh (then a miss
// of a closed surface is the rounding of the ray, not a leak). A ray that never
// entered the lattice, or one with a segment end, is not excused.
bool latticeRayMisses(const ExactOracle& lattice, const std::optional<QuantizedRay>& q) {
  if (!q || q->q.bounded()) return false;
  const Ray ray{glm::vec3(float(q->q.org[0]), float(q->q.org[1]), float(q->q.org[2])),
                glm::vec3(float(q->q.dir[0]), float(q->q.dir[1]), float(q->q.dir[2])), kInfinity};
  return !lattice.intersect(ray).has_value();
}

}  // namespace

// A report row's keys, each with the member it holds, once
// (common/json_keys.h): StressRow::toJson and StressRow::fromJson read this table (toJson adds the share that differs,
// differs_from_exact_percent, which fromJson has no member for).
static void forEachKey(json_keys::Of<StressRow> auto& r, auto&& fn) {
  fn("case", r.caseName), fn("variant", r.variant), fn("unit", r.unit), fn("model", r.model);
  fn("rays", r.rays), fn("rays_in_lattice", r.inLattice), fn("hits", r.hits), fn("mismatches", r.mismatches);
  fn("differs_from_exact", r.differs), fn("hit_miss_differs_from_exact", r.hitMissDiffers);
  fn("verdicts", r.verdicts), fn("must_hit", r.mustHit), fn("cracks", r.cracks);
  fn("lattice_misses", r.latticeMisses), fn("lattice_exact", r.latticeExact), fn("differs_from_base", r.baseDiffers);
  fn("first_beyond_bound", r.firstBeyond), fn("first_beyond_bound_details", r.firstBeyondDetails);
  fn("first_crack", r.firstCrack), fn("first_differs_from_base", r.firstBaseDiffers);
  fn("host_seconds", r.hostSeconds);
}

// A placement's keys, likewise (PlacementInfo::toJson, PlacementInfo::fromJson).
static void forEachKey(json_keys::Of<PlacementInfo> auto& p, auto&& fn) {
  fn("case", p.caseName), fn("variant", p.variant), fn("description", p.description), fn("rays", p.rays);
  fn("triangles", p.triangles), fn("lattice_rays_rejected", p.latticeRejected), fn("lattice", p.fit);
}

bool StressRow::failed(bool warned) const {
  return mismatches || verdicts[3] || (latticeExact && baseDiffers) || (cracks && !warned);
}

nlohmann::json StressRow::toJson() const {
  const auto verdictsJson = [](const std::array<uint64_t, 4>& counts) {
    nlohmann::json v;
    for (size_t k = 0; k < kVerdictKeys.size(); ++k) v[kVerdictKeys[k]] = counts[k];
    return v;
  };
  nlohmann::json j = json_keys::write(*this, json_keys::Overloaded{verdictsJson, OptionalJson{}, json_keys::Plain{}});
  j["differs_from_exact_percent"] = share(differs, rays);
  return j;
}

nlohmann::json PlacementInfo::toJson() const {
  const auto fitJson = [](const LatticeFit& f) { return f.toJson(); };
  return json_keys::write(*this, json_keys::Overloaded{fitJson, json_keys::Plain{}});
}

PlacementInfo PlacementInfo::fromJson(const nlohmann::json& p) {
  const auto fit = [](const nlohmann::json& j, const char* key, LatticeFit& f) { f = LatticeFit::fromJson(j.at(key)); };
  PlacementInfo info;
  json_keys::read(p, info, json_keys::Overloaded{fit, json_keys::Plain{}});
  return info;
}

StressRow StressRow::fromJson(const nlohmann::json& row) {
  const auto verdicts = [](const nlohmann::json& j, const char* key, std::array<uint64_t, 4>& counts) {
    for (size_t k = 0; k < kVerdictKeys.size(); ++k) counts[k] = j.at(key).at(kVerdictKeys[k]).get<uint64_t>();
  };
  const auto first = [](const nlohmann::json& j, const char* key, std::optional<uint32_t>& id) {
    if (!j.at(key).is_null()) id = j.at(key).get<uint32_t>();
  };
  const auto count = [](const nlohmann::json& j, const char* key, uint64_t& n) {
    // lattice_misses is absent from the reports written before it was counted.
    n = std::string_view(key) == "lattice_misses" ? j.value(key, uint64_t(0)) : j.at(key).get<uint64_t>();
  };
  StressRow s;
  json_keys::read(row, s, json_keys::Overloaded{verdicts, first, count, json_keys::Plain{}});
  return s;
}

StressResult StressResult::fromJson(const nlohmann::json& j) {
  StressResult r;
  for (const auto& p : j.at("placements")) r.placements.push_back(PlacementInfo::fromJson(p));
  for (const auto& row : j.at("rows")) r.rows.push_back(StressRow::fromJson(row));
  return r;
}

bool StressResult::warned(const StressRow& row) const {
  return std::any_of(placements.begin(), placements.end(), [&](const PlacementInfo& p) {
    return p.caseName == row.caseName && p.variant == row.variant && !p.fit.warning.empty();
  });
}

uint64_t StressResult::failures() const {
  return uint64_t(std::count_if(rows.begin(), rows.end(), [&](const StressRow& r) { return failed(r); }));
}

nlohmann::json StressResult::toJson() const {
  nlohmann::json p = nlohmann::json::array(), r = nlohmann::json::array();
  for (const PlacementInfo& i : placements) p.push_back(i.toJson());
  for (const StressRow& row : rows) r.push_back(row.toJson());
  return {{"pos_bits", fx::kPosBits}, {"dir_bits", fx::kDirBits}, {"placements", p}, {"rows", r},
          {"failures", failures()}};
}

StressResult runStress(const StressOptions& options, const StressProgress& progress) {
  const std::vector<std::string> cases = options.cases.empty() ? caseNames() : options.cases;
  const std::vector<std::string> all = hardwarePathNames();
  std::vector<fx::UnitKind> units;
  for (const std::string& u : options.units) {
    if (std::find(all.begin(), all.end(), u) == all.end()) {
      throw InputError(fmt::format("--units {}: no such hardware path (available: {})", u, fmt::join(all, ", ")));
    }
    units.push_back(parseHardwarePath(u));
  }
  if (units.empty()) units = hardwarePaths();
  for (fx::UnitKind u : units) {
    for (const std::string& m : options.models) {
      const auto have = modelsFor(u);
      if (std::find(have.begin(), have.end(), m) == have.end()) {
        throw InputError(fmt::format("--models {}: the {} path has no such model in this build (available: {})", m,
                                     toString(u), fmt::join(have, ", ")));
      }
    }
  }
  const std::vector<Variant> variants = makeVariants(options.scales, options.translations, options.stretches);
  StressResult result;
  const size_t total = cases.size() * variants.size();
  size_t index = 0;
  for (const std::string& name : cases) {
    const StressCase base = makeCase(name, options.rays, options.seed);
    std::map<std::string, BaseAnswers> baseAnswers;  // by unit/model
    for (const Variant& variant : variants) {
      const StressCase placed = place(base, variant);
      const Quantizer quantizer(placed.scene.bounds);
      PlacementInfo info;
      info.caseName = name;
      info.variant = variant.name();
      info.description = placed.description;
      info.rays = placed.rays.size();
      info.triangles = placed.scene.size();
      info.latticeRejected = placed.latticeRejected;
      info.fit = latticeFit(placed.scene, quantizer);
      if (progress) progress(info, index++, total);
      result.placements.push_back(info);

      const ExactOracle oracle(placed.scene);
      // The hardware's own geometry, exactly: lattice integers are floats below 2^24.
      const Scene lattice = latticeScene(placed.scene, quantizer);
      const ExactOracle latticeOracle(lattice);
      std::vector<std::optional<ExactHit>> truth(placed.rays.size());
      for (size_t i = 0; i < placed.rays.size(); ++i) truth[i] = oracle.intersect(placed.rays[i]);
      const QuantizedRays qrays = quantizeRays(quantizer, placed.rays);
      JobConfig config;
      config.accel = placed.accel;

      for (fx::UnitKind unit : units) {
        const std::vector<std::string> models = options.models.empty() ? modelsFor(unit) : options.models;
        for (const std::string& model : models) {
          const auto start = std::chrono::steady_clock::now();
          config.model = model;
          const JobResult job = makeHardwarePath(unit, placed.scene, quantizer, config)->run(qrays);
          StressRow row;
          row.caseName = name;
          row.variant = variant.name();
          row.unit = toString(unit);
          row.model = model;
          row.rays = placed.rays.size();
          row.mismatches = job.mismatchedRays;
          row.latticeExact = variant.latticeExact();
          row.mustHit = placed.mustHit;
          const std::string key = row.unit + "/" + model;
          const bool isBase = variant.kind == Variant::Kind::Base;
          if (isBase) baseAnswers[key] = {job.rays, job.hits};
          const BaseAnswers& baseOf = baseAnswers.at(key);
          for (size_t i = 0; i < placed.rays.size(); ++i) {
            const Ray& ray = placed.rays[i];
            row.inLattice += job.rays[i].has_value();
            const std::optional<Hit> hw = sceneHit(job, i);
            row.hits += hw.has_value();
            const std::optional<ExactHit>& t = truth[i];
            if (hw.has_value() != t.has_value() || (hw && hw->prim != t->prim)) ++row.differs;
            if (hw.has_value() != t.has_value()) ++row.hitMissDiffers;
            ToleranceOf lattice;
            if (job.rays[i]) {
              lattice = [&](const Triangle& tri) { return latticeTolerance(*job.rays[i], quantizer, ray, tri); };
            }
            const Judgement judgement = judge(oracle, ray, hw, t, lattice);
            ++row.verdicts[size_t(judgement.verdict)];
            if (judgement.verdict == Verdict::Wrong && !row.firstBeyond) {
              row.firstBeyond = uint32_t(i);
              row.firstBeyondDetails = describeBeyond(ray, judgement, hw, t);
            }
            if (i < placed.mustHit && !hw) {
              if (latticeRayMisses(latticeOracle, job.rays[i])) {
                ++row.latticeMisses;
              } else {
                ++row.cracks;
                if (!row.firstCrack) row.firstCrack = uint32_t(i);
              }
            }
            if (!isBase && differsFromBase(job, baseOf, i, variant.latticeExact())) {
              ++row.baseDiffers;
              if (!row.firstBaseDiffers) row.firstBaseDiffers = uint32_t(i);
            }
          }
          row.hostSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          result.rows.push_back(std::move(row));
        }
      }
    }
  }
  return result;
}

namespace {

// Rows folded by a key: sums, and the worst share of differences.
struct Folded {
  uint64_t rays = 0, mismatches = 0, differs = 0, ties = 0, within = 0, beyond = 0, cracks = 0, baseDiffers = 0;
  double worstDiffersPercent = 0, worstHitMissPercent = 0;
  void add(const StressRow& r) {
    rays += r.rays;
    mismatches += r.mismatches;
    differs += r.differs;
    ties += r.verdicts[1];
    within += r.verdicts[2];
    beyond += r.verdicts[3];
    cracks += r.cracks;
    baseDiffers += r.baseDiffers;
    worstDiffersPercent = std::max(worstDiffersPercent, share(r.differs, r.rays));
    worstHitMissPercent = std::max(worstHitMissPercent, share(r.hitMissDiffers, r.rays));
  }
};

}  // namespace

std::string placementTable(const StressResult& result) {
  std::string out = fmt::format("{:<18} {:<16} {:>8} {:>8} {:>9} {:>10} {:>8} {:>8} {:>7} {:>7} {:>9}\n", "case",
                                "placement", "rays", "mismatch", "differ %", "hit/miss %", "tie", "bound", "beyond",
                                "cracks", "vs base");
  for (const PlacementInfo& p : result.placements) {
    Folded f;
    for (const StressRow& r : result.rows) {
      if (r.caseName == p.caseName && r.variant == p.variant) f.add(r);
    }
    out += fmt::format("{:<18} {:<16} {:>8} {:>8} {:>9.3f} {:>10.3f} {:>8} {:>8} {:>7} {:>7} {:>9}{}\n", p.caseName,
                       p.variant, f.rays, f.mismatches, f.worstDiffersPercent, f.worstHitMissPercent, f.ties, f.within,
                       f.beyond, f.cracks, f.baseDiffers, p.fit.warning.empty() ? "" : "  (!)");
  }
  return out;
}

std::string caseLegend(const StressResult& result) {
  std::string out;
  for (const PlacementInfo& p : result.placements) {
    if (p.variant == "base") {
      out += fmt::format("  {:<18} {} ({} triangles, {} rays)\n", p.caseName, p.description, p.triangles, p.rays);
    }
  }
  return out;
}

std::string modelTable(const StressResult& result) {
  std::vector<std::string> keys;
  std::map<std::string, Folded> folded;
  for (const StressRow& r : result.rows) {
    const std::string key = fmt::format("{:<18} {:<7} {:<12}", r.caseName, r.unit, r.model);
    if (!folded.count(key)) keys.push_back(key);
    folded[key].add(r);
  }
  std::string out = fmt::format("{:<18} {:<7} {:<12} {:>8} {:>8} {:>9} {:>8} {:>7}\n", "case", "unit", "model", "rays",
                                "mismatch", "differ %", "bound", "beyond");
  for (const std::string& key : keys) {
    const Folded& f = folded[key];
    out += fmt::format("{} {:>8} {:>8} {:>9.3f} {:>8} {:>7}\n", key, f.rays, f.mismatches, share(f.differs, f.rays),
                       f.within, f.beyond);
  }
  return out;
}

}  // namespace lancer::stress
