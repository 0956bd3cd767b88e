// computePinAccess: components grouped into classes that see the same
// geometry and the same tracks relative to their location, one computation
// per class (and one per IO pin), run on settings.threads workers, then the
// flat per-pinRef table.
//
// Class key: (macro, orientation, location.x mod Px, location.y mod Py,
// clip), where Px (Py) is the least common multiple of the steps of the DEF
// X (Y) track patterns of the macro's pin layers z and z+1, and clip records,
// relative to the location, where each of those patterns and the die cut
// the window that decides the result (the pins' bounding box grown by the
// largest step, and by the reach of a planar exit stub for the die). Inside
// the tracks and the die the clip is the same for every component of a
// macro and orientation; near the ends it separates components whose
// surroundings differ. With no usable period (no tracks, or an LCM beyond
// kMaxPeriod) the key is the exact location. A class is computed on its
// first component (in DEF order) and stored relative to its location.
//
// An IO pin is computed on its own, against the design's shapes around it
// (pad cells, rings, other pins), with its net's id.
#include <algorithm>
#include <atomic>
#include <exception>
#include <map>
#include <numeric>
#include <thread>
#include <tuple>

#include "drc/layer_shapes.hpp"
#include "drc/pair_rules.hpp"
#include "geom/polygon.hpp"
#include "pa/pa_internal.hpp"

namespace xroute {

namespace {

using pa::PinRect;

constexpr int64_t kMaxPeriod = int64_t(1) << 24;  // DBU: a larger period is treated as none

// What the class key of a macro's components depends on.
struct MacroInfo {
  bool ready = false;
  std::vector<int32_t> patterns;  // indices into Design::tracks
  int64_t periodX = 0;            // DBU, 0 = none (keys of exact locations)
  int64_t periodY = 0;            // DBU
  Dbu maxStep = 0;                // DBU, largest step among `patterns`
  Dbu stubReach = 0;              // DBU, how far a planar exit stub reaches beyond the pins
  bool hasBox = false;
  Rect box;                       // DBU, macro coordinates: bounding box of the routing-layer pin shapes
};

struct ClassKey {
  int32_t macro = 0;
  int32_t orient = 0;
  Dbu x = 0, y = 0;           // DBU: location modulo the periods (the location itself with no period)
  std::vector<int64_t> clip;  // DBU, relative to the location: where the tracks and the die end in the window
  auto tie() const { return std::tie(macro, orient, x, y, clip); }
  bool operator<(const ClassKey& o) const { return tie() < o.tie(); }
};

struct PinJob {
  CompId comp;                 // the class's first component; invalid for an IO pin
  int32_t ioPin = -1;          // IoPinId value for an IO pin job
  int32_t net = -1;            // NetId value of an IO pin's net (its id among the design's shapes)
  std::vector<int32_t> pins;   // macro pin indices to compute (component jobs)
};

struct JobResult {
  std::vector<std::vector<AccessPoint>> points;  // per entry of PinJob::pins (one for an IO pin), relative
  std::vector<uint8_t> fallback;                 // per entry: 1 = fallback point
};

int64_t floorMod(int64_t v, int64_t m) { return ((v % m) + m) % m; }

const MacroInfo& macroInfo(const Tech& tech, const Design& design, const std::vector<pa::LayerAccess>& layers,
                           std::vector<MacroInfo>& cache, MacroId id) {
  MacroInfo& info = cache[*id];
  if (info.ready) return info;
  info.ready = true;
  const Macro& m = tech.macros[*id];
  std::vector<int32_t> zs;
  for (const MacroPin& pin : m.pins) {
    for (const MacroShape& s : pin.shapes) {
      const int32_t z = tech.layer(s.layer).routingIndex;
      if (z < 0) continue;
      zs.push_back(z);
      if (info.hasBox) info.box.expandToInclude(s.rect);
      else info.box = s.rect, info.hasBox = true;
    }
  }
  std::sort(zs.begin(), zs.end());
  zs.erase(std::unique(zs.begin(), zs.end()), zs.end());
  for (int32_t z : zs) {
    for (int32_t p : pa::relevantTrackPatterns(tech, design, z)) info.patterns.push_back(p);
    info.stubReach = std::max(info.stubReach, layers[z].stubLength + layers[z].stubWidth);
  }
  std::sort(info.patterns.begin(), info.patterns.end());
  info.patterns.erase(std::unique(info.patterns.begin(), info.patterns.end()), info.patterns.end());
  int64_t px = 1, py = 1;
  for (int32_t p : info.patterns) {
    const TrackPattern& t = design.tracks[p];
    int64_t& period = t.isX ? px : py;
    if (t.step <= 0 || period == 0) {
      period = 0;
      continue;
    }
    period = std::lcm(period, int64_t(t.step));
    if (period > kMaxPeriod) period = 0;
    info.maxStep = std::max(info.maxStep, t.step);
  }
  info.periodX = px;
  info.periodY = py;
  return info;
}

ClassKey classKey(const Tech& tech, const Design& design, const MacroInfo& info, const Component& c) {
  ClassKey k{*c.macro, int32_t(c.orient), c.location.x, c.location.y, {}};
  if (!info.hasBox || info.periodX == 0 || info.periodY == 0) return k;
  const Rect box = componentTransform(tech, c).apply(info.box);
  const int64_t lx = c.location.x, ly = c.location.y;
  auto clipTo = [&](int64_t first, int64_t last, int64_t lo, int64_t hi, int64_t origin) {
    k.clip.push_back(std::max(first, lo) - origin);
    k.clip.push_back(std::min(last, hi) - origin);
  };
  const int64_t g = info.maxStep;
  for (int32_t p : info.patterns) {
    const TrackPattern& t = design.tracks[p];
    const int64_t first = t.start, last = t.start + int64_t(std::max(t.count, 1) - 1) * t.step;
    if (t.isX) clipTo(first, last, box.xlo - g, box.xhi + g, lx);
    else clipTo(first, last, box.ylo - g, box.yhi + g, ly);
  }
  const int64_t r = info.stubReach;
  const Rect& die = design.dieArea;
  clipTo(die.xlo, die.xhi, box.xlo - r, box.xhi + r, lx);
  clipTo(die.ylo, die.yhi, box.ylo - r, box.yhi + r, ly);
  k.x = Dbu(floorMod(lx, info.periodX));
  k.y = Dbu(floorMod(ly, info.periodY));
  return k;
}

JobResult runComponentJob(const Tech& tech, const Design& design, const std::vector<pa::LayerAccess>& layers,
                          const PinJob& job, int maxPoints) {
  const Component& c = design.components[*job.comp];
  const Macro& m = tech.macros[*c.macro];
  const Transform t = componentTransform(tech, c);

  // Context: every pin with its own id (its index), OBS cut back at the pins.
  std::vector<DrcShape> context;
  std::vector<std::vector<PinRect>> metal(m.pins.size());
  std::vector<std::pair<LayerId, Rect>> pinRects;
  std::vector<Rect> rects;
  for (int32_t k = 0; k < int32_t(m.pins.size()); ++k) {
    for (const MacroShape& s : m.pins[k].shapes) {
      rects.clear();
      placedShapeRects(s, t, rects);
      const int32_t z = tech.layer(s.layer).routingIndex;
      for (const Rect& r : rects) {
        context.push_back({s.layer, r, k, ShapeOrigin::Pin});
        pinRects.push_back({s.layer, r});
        if (z >= 0) metal[k].push_back({z, r});
      }
    }
  }
  std::vector<Rect> pieces, next;
  for (const MacroShape& s : m.obstructions) {
    pieces.clear();
    placedShapeRects(s, t, pieces);
    for (const auto& [layer, r] : pinRects) {
      if (layer != s.layer) continue;
      next.clear();
      for (const Rect& piece : pieces) subtractRect(piece, r, next);
      pieces.swap(next);
    }
    for (const Rect& r : pieces) context.push_back({s.layer, r, -1, ShapeOrigin::Obstruction});
  }

  const pa::AccessChecker checker(tech, std::move(context), design.dieArea, t.apply(Rect{0, 0, m.width, m.height}));
  JobResult out;
  const Point origin = c.location;
  for (int32_t k : job.pins) {
    pa::PinPointsResult r = pa::choosePinPoints(tech, layers, checker, metal[k], k, maxPoints);
    for (AccessPoint& p : r.points) p.at = {p.at.x - origin.x, p.at.y - origin.y};
    out.points.push_back(std::move(r.points));
    out.fallback.push_back(r.fallback);
  }
  return out;
}

// What IO pins are checked against: every metal and cut shape of the design
// (collectDesignShapes: pins with their nets' ids, OBS, special nets), near
// the pin. IO pins sit at the die edge under pad cells and power rings, so
// unlike a cell's pins they cannot be judged alone.
struct IoSurroundings {
  std::vector<DrcShape> shapes;
  BoxIndex index;   // over shapes
  Dbu margin = 0;   // DBU: how far from the pin a shape may matter
};

IoSurroundings ioSurroundings(const Tech& tech, const Design& design, const std::vector<pa::LayerAccess>& layers) {
  IoSurroundings s;
  s.shapes = collectDesignShapes(tech, design);
  std::vector<Rect> rects;
  rects.reserve(s.shapes.size());
  for (const DrcShape& d : s.shapes) rects.push_back(d.rect);
  s.index = BoxIndex(std::move(rects));
  Dbu range = 0, reach = 0, via = 0;
  for (const Layer& l : tech.layers) range = std::max(range, drc::interactionRange(l));
  for (const pa::LayerAccess& la : layers) reach = std::max(reach, la.stubLength + la.stubWidth);
  for (const Via& v : tech.vias)
    for (const ViaShape& vs : v.shapes)
      via = std::max({via, -vs.rect.xlo, -vs.rect.ylo, vs.rect.xhi, vs.rect.yhi});
  s.margin = range + std::max(reach, via) + 1;
  return s;
}

JobResult runIoJob(const Tech& tech, const Design& design, const std::vector<pa::LayerAccess>& layers,
                   const IoSurroundings& around, const PinJob& job, int maxPoints) {
  const IoPin& pin = design.ioPins[job.ioPin];
  const Transform t{pin.location, pin.orient, 0, 0};
  std::vector<DrcShape> context;
  std::vector<PinRect> metal;
  Rect box;
  for (const IoPinShape& s : pin.shapes) {
    const Rect r = t.apply(s.rect);
    if (context.empty()) box = r;
    box.expandToInclude(r);
    context.push_back({s.layer, r, job.net, ShapeOrigin::Pin});
    const int32_t z = tech.layer(s.layer).routingIndex;
    if (z >= 0) metal.push_back({z, r});
  }
  if (!context.empty()) {
    const Dbu m = around.margin;
    around.index.query(Rect{box.xlo - m, box.ylo - m, box.xhi + m, box.yhi + m},
                       [&](int32_t i) { context.push_back(around.shapes[i]); });
  }
  const pa::AccessChecker checker(tech, std::move(context), design.dieArea);
  pa::PinPointsResult r = pa::choosePinPoints(tech, layers, checker, metal, job.net, maxPoints);
  JobResult out;
  out.points.push_back(std::move(r.points));
  out.fallback.push_back(r.fallback);
  return out;
}

// Runs fn(i) for i in [0, n) on `threads` workers (each i once; fn writes only
// its own slot, so the result does not depend on the thread count).
template <typename Fn>
void parallelFor(size_t n, int threads, Fn fn) {
  std::atomic<size_t> next{0};
  std::exception_ptr failure;
  std::atomic<bool> failed{false};
  auto work = [&]() {
    for (size_t i; !failed && (i = next.fetch_add(1)) < n;) {
      try {
        fn(i);
      } catch (...) {
        if (!failed.exchange(true)) failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < std::clamp(threads, 1, std::max(1, int(n))); ++t) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
  if (failure) std::rethrow_exception(failure);
}

// Per LEF via: how far from its shapes another shape can matter to them (the
// largest interaction range among the via's own layers; the largest of all
// layers made the windows of asap7's M1 vias reach shapes that no rule of
// theirs can see, and the in-context check took 1.0 of gcd's 1.1 s).
std::vector<Dbu> viaRanges(const Tech& tech) {
  std::vector<Dbu> out(tech.vias.size(), 0);
  for (size_t v = 0; v < tech.vias.size(); ++v)
    for (const ViaShape& vs : tech.vias[v].shapes) out[v] = std::max(out[v], drc::interactionRange(tech.layer(vs.layer)));
  return out;
}

// Whether an access via's shapes at `at` (net `net`) keep the spacing the
// checker asks of them from `other`, a shape its component's class did not
// see (drc/pair_rules.hpp: metal by the spacing table and end of line, cuts
// by the plain cut spacing rules).
bool viaClearOf(const Tech& tech, const Via& via, Point at, int32_t net, const DrcShape& other) {
  if (other.net >= 0 && other.net == net) return true;
  for (const ViaShape& vs : via.shapes) {
    if (vs.layer != other.layer) continue;
    const Rect r = vs.rect.translated(at);
    const Layer& layer = tech.layer(vs.layer);
    Dbu need = 0;
    if (layer.type == LayerType::Routing) {
      need = drc::metalNeed(layer, r, other.rect);
    } else {
      for (const CutSpacingRule& c : layer.cutSpacings) {
        if (!c.sameNet && c.adjacentCuts == 0 && !c.centerToCenter) need = std::max(need, c.space);
      }
    }
    if (r.overlaps(other.rect) || drc::rectGap(r, other.rect) < need) return false;
  }
  return true;
}

// A component pin's access vias were checked against its own component only
// (its class). Each is checked again against every design shape around it
// that the class did not see (neighbouring cells' pins and OBS, special nets,
// blockages); one too close loses its via exit (the point stays, planar
// only, dearer, and the pin's points are sorted again by cost).
void checkViasInContext(const Tech& tech, const Design& design, const IoSurroundings& around,
                        const std::vector<int32_t>& netOf, PinAccessTable& table, int threads) {
  const int32_t refs = int32_t(design.pinRefs.size());
  const std::vector<Dbu> ranges = viaRanges(tech);
  parallelFor(size_t(refs), threads, [&](size_t r) {
    if (design.pinRefs[r].isIo()) return;
    // The component's own pins and OBS lie inside its placed box: its class saw them.
    const Component& c = design.components[*design.pinRefs[r].comp];
    const Macro& mac = tech.macros[*c.macro];
    const Rect cell = componentTransform(tech, c).apply(Rect{0, 0, mac.width, mac.height});
    AccessPoint* first = table.points.data() + table.start[r];
    AccessPoint* last = table.points.data() + table.start[r + 1];
    bool changed = false;
    for (AccessPoint* p = first; p != last; ++p) {
      if (!(p->dirs & kAccessUp) || !p->upVia.valid()) continue;
      const Via& via = tech.vias[*p->upVia];
      Rect reach{p->at.x, p->at.y, p->at.x, p->at.y};
      for (const ViaShape& vs : via.shapes) reach.expandToInclude(vs.rect.translated(p->at));
      bool clear = true;
      const Dbu range = ranges[*p->upVia];
      const Rect near{reach.xlo - range, reach.ylo - range, reach.xhi + range, reach.yhi + range};
      around.index.query(near, [&](int32_t i) {
        const DrcShape& s = around.shapes[i];
        const bool own = (s.origin == ShapeOrigin::Pin || s.origin == ShapeOrigin::Obstruction) &&
                         s.rect.xlo >= cell.xlo && s.rect.xhi <= cell.xhi && s.rect.ylo >= cell.ylo &&
                         s.rect.yhi <= cell.yhi;
        clear = clear && (own || viaClearOf(tech, via, p->at, netOf[r], s));
      });
      if (clear) continue;
      p->dirs &= uint8_t(~kAccessUp);
      p->upVia = ViaId();
      p->cost += pa::kCostPlanarOnly;
      changed = true;
    }
    if (changed) {
      std::stable_sort(first, last, [](const AccessPoint& a, const AccessPoint& b) { return a.cost < b.cost; });
    }
  });
}

}  // namespace

PinAccessTable computePinAccess(const Tech& tech, const Design& design, const TrackSet& tracks,
                                const PinAccessSettings& settings) {
  const std::vector<pa::LayerAccess> layers = pa::buildLayerAccess(tech, tracks);
  const int32_t refs = int32_t(design.pinRefs.size());

  // Jobs: one per class of components, one per IO pin.
  std::vector<MacroInfo> infos(tech.macros.size());
  std::map<ClassKey, int32_t> classOf;
  std::vector<int32_t> compClass(design.components.size(), -1);
  std::vector<int32_t> ioJob(design.ioPins.size(), -1);
  std::vector<PinJob> jobs;
  std::vector<int32_t> netOf(refs, -1);  // per pinRef: its net
  for (size_t n = 0; n + 1 < design.netPinStart.size(); ++n)
    for (int32_t r = design.netPinStart[n]; r < design.netPinStart[n + 1]; ++r) netOf[r] = int32_t(n);
  for (int32_t r = 0; r < refs; ++r) {
    const PinRef& ref = design.pinRefs[r];
    if (ref.isIo()) {
      if (ioJob[ref.pin] < 0) {
        ioJob[ref.pin] = int32_t(jobs.size());
        jobs.push_back({CompId(), ref.pin, netOf[r], {}});
      }
      continue;
    }
    int32_t& cls = compClass[*ref.comp];
    if (cls < 0) {
      const Component& c = design.components[*ref.comp];
      ClassKey key = classKey(tech, design, macroInfo(tech, design, layers, infos, c.macro), c);
      if (!settings.shareClasses) key = ClassKey{*ref.comp, 0, 0, 0, {}};
      auto [it, fresh] = classOf.try_emplace(key, int32_t(jobs.size()));
      if (fresh) jobs.push_back({ref.comp, -1, -1, {}});
      cls = it->second;
    }
    jobs[cls].pins.push_back(ref.pin);
  }
  for (PinJob& j : jobs) {
    std::sort(j.pins.begin(), j.pins.end());
    j.pins.erase(std::unique(j.pins.begin(), j.pins.end()), j.pins.end());
  }

  // Compute the jobs, each into its own slot: the result does not depend on
  // the number of threads.
  const bool anyIo = std::any_of(jobs.begin(), jobs.end(), [](const PinJob& j) { return !j.comp.valid(); });
  const IoSurroundings around =
      anyIo || settings.checkInContext ? ioSurroundings(tech, design, layers) : IoSurroundings{};
  std::vector<JobResult> results(jobs.size());
  const int maxPoints = std::max(settings.maxPointsPerPin, 1);
  parallelFor(jobs.size(), settings.threads, [&](size_t j) {
    results[j] = jobs[j].comp.valid() ? runComponentJob(tech, design, layers, jobs[j], maxPoints)
                                      : runIoJob(tech, design, layers, around, jobs[j], maxPoints);
  });

  // The flat table, translated to each component's location.
  PinAccessTable table;
  table.classes = int32_t(classOf.size());
  table.start.reserve(refs + 1);
  table.start.push_back(0);
  for (int32_t r = 0; r < refs; ++r) {
    const PinRef& ref = design.pinRefs[r];
    const int32_t j = ref.isIo() ? ioJob[ref.pin] : compClass[*ref.comp];
    const PinJob& job = jobs[j];
    const size_t slot = ref.isIo() ? 0 : size_t(std::lower_bound(job.pins.begin(), job.pins.end(), ref.pin) - job.pins.begin());
    const Point origin = ref.isIo() ? Point{} : design.components[*ref.comp].location;
    for (AccessPoint p : results[j].points[slot]) {
      p.at = {p.at.x + origin.x, p.at.y + origin.y};
      table.points.push_back(p);
    }
    table.fallbackPins += results[j].fallback[slot];
    table.start.push_back(int32_t(table.points.size()));
  }
  if (settings.checkInContext) checkViasInContext(tech, design, around, netOf, table, settings.threads);
  return table;
}

double soleViaShare(const PinAccessTable& table) {
  const int32_t refs = int32_t(table.start.size()) - 1;
  if (refs <= 0) return 0.0;
  int32_t sole = 0;
  for (int32_t r = 0; r < refs; ++r) {
    const int32_t vias = int32_t(std::count_if(table.begin(r), table.end(r),
                                               [](const AccessPoint& p) { return (p.dirs & kAccessUp) != 0; }));
    sole += vias == 1;
  }
  return double(sole) / refs;
}

}  // namespace xroute
