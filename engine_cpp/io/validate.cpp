#include "io/validate.hpp"

#include "io/input_error.hpp"

namespace xroute {

namespace {
constexpr int64_t kMaxGCells = 25000000;  // ISPD 2019's largest design has about 400,000
}  // namespace

void validateTech(const Tech& tech, const std::vector<std::string>& lefPaths) {
  const std::string first = lefPaths.empty() ? std::string("LEF") : lefPaths.front();
  if (tech.dbuPerMicron <= 0) throw InputError(first, 0, "no UNITS DATABASE MICRONS in the LEF");
  if (tech.routingLayers.empty()) throw InputError(first, 0, "no routing layer (LAYER ... TYPE ROUTING) in the LEF");
  for (LayerId id : tech.routingLayers) {
    const Layer& l = tech.layer(id);
    const std::string where = l.path.empty() ? first : l.path;
    if (l.width <= 0) throw InputError(where, l.line, "routing LAYER '" + l.name + "' has no positive WIDTH");
    if (l.pitchX <= 0 || l.pitchY <= 0) {
      throw InputError(where, l.line, "routing LAYER '" + l.name + "' has no positive PITCH");
    }
  }
}

namespace {

void warn(Design& design, const std::string& defPath, int line, const std::string& message) {
  design.warnings.push_back(defPath + ":" + std::to_string(line) + ": " + message);
  ++design.warningCount;
}

bool outside(const Rect& die, Point p) { return p.x < die.xlo || p.x > die.xhi || p.y < die.ylo || p.y > die.yhi; }

}  // namespace

void validateDesign(const Tech& tech, Design& design, const std::string& defPath) {
  if (design.dieLine <= 0) {
    // Nothing placed and nothing to route (an empty design) needs no die; anything else does.
    if (design.components.empty() && design.ioPins.empty() && design.nets.empty() && design.specialNets.empty()) return;
    throw InputError(defPath, design.endLine, "no DIEAREA in the DEF");
  }
  int64_t linesX = 0, linesY = 0;
  for (const GCellPattern& g : design.gcellGrid) (g.isX ? linesX : linesY) += g.count;
  if (linesX > 1 && linesY > 1 && (linesX - 1) * (linesY - 1) > kMaxGCells) {
    throw InputError(defPath, design.gcellLine,
                     "GCELLGRID makes " + std::to_string(linesX - 1) + " x " + std::to_string(linesY - 1) +
                         " GCells; at most " + std::to_string(kMaxGCells) + " are supported");
  }
  const Rect& die = design.dieArea;
  const std::string dieText = "(" + std::to_string(die.xlo) + " " + std::to_string(die.ylo) + " " +
                              std::to_string(die.xhi) + " " + std::to_string(die.yhi) + ")";
  int comps = 0;
  std::string firstComp;
  for (const Component& c : design.components) {
    if (c.status != PlaceStatus::Unplaced && outside(die, c.location) && comps++ == 0) firstComp = c.name;
  }
  if (comps > 0) {
    warn(design, defPath, design.dieLine,
         std::to_string(comps) + " component(s) placed outside the die area " + dieText + ", e.g. '" + firstComp + "'");
  }
  int pins = 0;
  std::string firstPin;
  for (const IoPin& p : design.ioPins) {
    if (p.status != PlaceStatus::Unplaced && outside(die, p.location) && pins++ == 0) firstPin = p.name;
  }
  if (pins > 0) {
    warn(design, defPath, design.dieLine,
         std::to_string(pins) + " IO pin(s) placed outside the die area " + dieText + ", e.g. '" + firstPin + "'");
  }
  int tracks = 0;
  for (const TrackPattern& t : design.tracks) {
    const Dbu lo = t.isX ? die.xlo : die.ylo;
    const Dbu hi = t.isX ? die.xhi : die.yhi;
    const int64_t last = static_cast<int64_t>(t.start) + static_cast<int64_t>(t.step) * (t.count - 1);
    if (last < lo || t.start > hi) ++tracks;
  }
  if (tracks > 0) {
    warn(design, defPath, design.dieLine, std::to_string(tracks) + " TRACKS pattern(s) with no track in the die area " + dieText);
  }
  for (LayerId id : tech.routingLayers) {
    bool has = false;
    for (const TrackPattern& t : design.tracks) has = has || t.layer == id;
    if (!has && !design.tracks.empty()) {
      warn(design, defPath, design.dieLine, "no TRACKS for routing layer '" + tech.layer(id).name + "'");
    }
  }
}

}  // namespace xroute
