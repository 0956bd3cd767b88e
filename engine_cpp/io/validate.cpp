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

// The bounding box of the rows, the placed components (with their macro's size) and the placed
// IO pins; false when nothing is placed or the box has no area.
bool placedBox(const Tech& tech, const Design& design, Rect& box) {
  bool any = false;
  auto add = [&](Point lo, Dbu w, Dbu h) {
    const Rect r{lo.x, lo.y, lo.x + w, lo.y + h};
    if (!any) box = r;
    box.expandToInclude(r);
    any = true;
  };
  for (const Row& r : design.rows) {
    const auto site = tech.siteIndex.find(r.site);
    const Site* s = site == tech.siteIndex.end() ? nullptr : &tech.sites[*site->second];
    add(r.origin, Dbu(r.stepX * (r.numX - 1) + (s ? s->width : 0)), Dbu(r.stepY * (r.numY - 1) + (s ? s->height : 0)));
  }
  for (const Component& c : design.components) {
    if (c.status == PlaceStatus::Unplaced) continue;
    const Macro& m = tech.macros[*c.macro];
    const bool turned = c.orient == Orient::W || c.orient == Orient::E || c.orient == Orient::FW || c.orient == Orient::FE;
    add(c.location, turned ? m.height : m.width, turned ? m.width : m.height);
  }
  for (const IoPin& p : design.ioPins) {
    if (p.status != PlaceStatus::Unplaced) add(p.location, 0, 0);
  }
  return any && box.xhi > box.xlo && box.yhi > box.ylo;
}

bool outside(const Rect& die, Point p) { return p.x < die.xlo || p.x > die.xhi || p.y < die.ylo || p.y > die.yhi; }

// Routed wires, vias and patches of NETS with a point outside the die: checked and drawn as read
// (a routed DEF from elsewhere may have them), but worth a word.
void warnRoutingOutsideDie(Design& design, const std::string& defPath, const std::string& dieText) {
  if (design.dieLine <= 0) return;
  const Rect& die = design.dieArea;
  int64_t count = 0;
  std::string firstNet;
  for (const Net& n : design.nets) {
    const NetRouting& r = n.routing;
    int64_t here = 0;
    for (const RouteWire& w : r.wires) here += (outside(die, w.from) || outside(die, w.to)) ? 1 : 0;
    for (const RouteVia& v : r.vias) here += outside(die, v.at) ? 1 : 0;
    for (const RoutePatch& p : r.patches) here += outside(die, {p.rect.xlo, p.rect.ylo}) || outside(die, {p.rect.xhi, p.rect.yhi});
    if (here > 0 && count == 0) firstNet = n.name;
    count += here;
  }
  if (count > 0) {
    warn(design, defPath, design.dieLine,
         std::to_string(count) + " routed wire(s), via(s) or patch(es) reach outside the die area " + dieText +
             ", e.g. in net '" + firstNet + "'");
  }
}

}  // namespace

void validateDesign(const Tech& tech, Design& design, const std::string& defPath) {
  if (design.dieLine <= 0) {
    // DIEAREA is optional (OpenROAD's dft/rmp/rsz tests lack it): the box of what is placed
    // stands in, with a warning; a design with nothing placed keeps no die.
    Rect b;
    if (!placedBox(tech, design, b)) return;
    design.dieArea = b;
    design.diePolygon = {{b.xlo, b.ylo}, {b.xhi, b.yhi}};
    design.dieLine = design.endLine;
    warn(design, defPath, design.endLine,
         "no DIEAREA: the box of the rows, placed components and IO pins stands in (" + std::to_string(b.xlo) + " " +
             std::to_string(b.ylo) + " " + std::to_string(b.xhi) + " " + std::to_string(b.yhi) + ")");
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
  warnRoutingOutsideDie(design, defPath, dieText);
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
    const Layer& l = tech.layer(id);
    const bool horizontal = l.direction != Direction::Vertical;  // as the router takes it (grid/tracks.cpp)
    const TrackPattern* any = nullptr;
    bool preferred = false;
    for (const TrackPattern& t : design.tracks) {
      if (t.layer != id) continue;
      any = any ? any : &t;
      preferred = preferred || t.isX != horizontal;  // "TRACKS Y" lines carry horizontal wires
    }
    if (!any && !design.tracks.empty()) {
      warn(design, defPath, design.dieLine, "no TRACKS for routing layer '" + l.name + "'");
    } else if (any && !preferred) {
      warn(design, defPath, any->line,
           "routing layer '" + l.name + "' has TRACKS " + (horizontal ? "X" : "Y") + " only, none in its preferred (" +
               (horizontal ? "horizontal" : "vertical") + ") direction: it cannot be routed without TRACKS " +
               (horizontal ? "Y" : "X"));
    }
  }
}

}  // namespace xroute
