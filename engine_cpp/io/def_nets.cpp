// DEF NETS and SPECIALNETS: net pins into the flat Design::pinRefs array,
// and routing paths into wires, vias and patches.
//
// A path "LAYER ( a ) ( b ) ( c ) VIA ( d )" gives one straight wire per
// consecutive pair of points (a-b, b-c on LAYER), a via at the current point
// (c), after which the path goes on on the via's other layer (c-d). "*"
// repeats the previous coordinate. A path of one point and nothing else gives
// a point wire (from == to).
#include <algorithm>

#include "io/def_parser.hpp"

namespace xroute {

namespace {

bool isOrientName(const Token& t) {
  Orient o;
  return !t.quoted && parseOrient(t.text, o);
}

// Where a path stands: its layer, the current point and what it produced.
struct PathCursor {
  LayerId layer;
  bool havePoint = false;
  Point at;        // DBU
  Dbu ext = -1;    // DBU, extension written at the current point (-1 = none)
  bool emitted = false;
};

}  // namespace

// ---------------------------------------------------------------------------
// Path helpers (members so they can use the lexer and the counters)

namespace {

// Reads "( x|* y|* [ext] )"; "*" repeats the cursor's coordinate.
Point readPathPoint(Lexer& lex, const PathCursor& cur, Dbu& ext) {
  const Token open = lex.next();
  if (open.quoted || open.text != "(") lex.failAt(open, "expected '(', found " + quoteToken(open.text));
  Point p;
  for (int i = 0; i < 2; ++i) {
    const Token& t = lex.peek();
    Dbu& v = i == 0 ? p.x : p.y;
    if (!t.quoted && t.text == "*") {
      if (!cur.havePoint) lex.failAt(t, "'*' with no previous point");
      lex.next();
      v = i == 0 ? cur.at.x : cur.at.y;
    } else {
      v = lex.dbu();
    }
  }
  ext = -1;
  const Token& t = lex.peek();
  if (t.quoted || t.text != ")") {
    const Token e = t;
    ext = lex.dbu();
    if (ext < 0) lex.failAt(e, "negative wire extension");
  }
  lex.expect(")");
  return p;
}

}  // namespace

ViaRef DefParser::readPathVia(const Token& viaTok, bool havePoint, std::string_view section) {
  if (viaTok.quoted || viaTok.text == ")") unexpected(viaTok, "a point or a via name");
  const ViaRef ref = findVia(viaTok.text);
  if (!ref.valid()) lex_.failAt(viaTok, "unknown via " + quoteToken(viaTok.text));
  if (!havePoint) lex_.failAt(viaTok, "via " + quoteToken(viaTok.text) + " before any point");
  if (isOrientName(lex_.peek())) {
    const Token o = lex_.next();
    if (o.text != "N") {
      countSkip(std::string(section) + ".VIA.ORIENT");
      ++design_.warningCount;
    }
  }
  return ref;
}

LayerId DefParser::layerAfterVia(const Token& viaTok, ViaRef ref, LayerId layer) const {
  const Via& via = design_.via(tech_, ref);
  if (layer == via.bottom) return via.top;
  if (layer == via.top) return via.bottom;
  lex_.failAt(viaTok, "via " + quoteToken(viaTok.text) + " does not connect to layer " +
                          quoteToken(tech_.layer(layer).name));
}

void DefParser::requireInRange(int line, const Rect& r, std::string_view what) const {
  if (withinDbuRange(r.xlo) && withinDbuRange(r.ylo) && withinDbuRange(r.xhi) && withinDbuRange(r.yhi)) return;
  lex_.fail(line, std::string(what) + " (" + std::to_string(r.xlo) + " " + std::to_string(r.ylo) + " " +
                      std::to_string(r.xhi) + " " + std::to_string(r.yhi) + ") reaches beyond the engine's range, " +
                      dbuRangeText());
}

void DefParser::requireViaInRange(int line, ViaRef ref, Point at) const {
  const std::vector<ViaShape>& shapes = design_.via(tech_, ref).shapes;
  if (shapes.empty()) return;
  Rect box = shapes.front().rect;
  for (const ViaShape& s : shapes) box.expandToInclude(s.rect);
  requireInRange(line, box.translated(at), "via");  // each term is within kMaxDbu: the sum fits
}

// ---------------------------------------------------------------------------
// SPECIALNETS

void DefParser::readSpecialNets() {
  const int declared = readSectionCount();
  design_.specialNets.reserve(design_.specialNets.size() + saneReserve(declared));
  readEntries("SPECIALNETS", declared, [&] { readSpecialNet(); });
}

void DefParser::readSpecialNet() {
  SpecialNet net;
  net.name = plainWord("a net name");
  while (peekIs("(")) {
    lex_.next();
    std::string comp = plainWord("a component name");
    std::string pin = plainWord("a pin name");
    if (lex_.accept("+")) {
      lex_.expect("SYNTHESIZED");
      countSkip("SPECIALNETS.SYNTHESIZED");
    }
    lex_.expect(")");
    net.pins.emplace_back(std::move(comp), std::move(pin));
  }
  for (Token kw; nextOption(kw);) {
    const std::string_view k = kw.quoted ? std::string_view() : kw.text;
    if (k == "ROUTED" || k == "FIXED" || k == "COVER") {
      if (k != "ROUTED") countSkip("SPECIALNETS." + std::string(k));
      readSpecialWiring(net);
    } else if (k == "SHIELD") {
      lex_.word("a shield net name");
      countSkip("SPECIALNETS.SHIELD");
      readSpecialWiring(net);
    } else if (k == "USE") {
      net.use = plainWord("a net use");
    } else if (k == "RECT") {
      const LayerId layer = layerAt(lex_.next());
      if (lex_.accept("+")) {
        lex_.expect("MASK");
        const Token v = lex_.peek();
        checkMask(v, lex_.integer(), false);
      }
      const Point a = readPoint();
      const Point b = readPoint();
      checkCorners(kw.line, a, b, "SPECIALNETS RECT");
      net.rects.push_back({layer, Rect::fromCorners(a, b)});
    } else if (k == "POLYGON") {
      const LayerId layer = layerAt(lex_.next());
      if (lex_.accept("+")) {
        lex_.expect("MASK");
        lex_.integer();
      }
      const std::vector<Point> pts = readPolygonPoints(kw);
      Rect r{pts[0].x, pts[0].y, pts[0].x, pts[0].y};
      for (const Point& p : pts) r.expandToInclude(Rect{p.x, p.y, p.x, p.y});
      net.rects.push_back({layer, r});
      countSkip("SPECIALNETS.POLYGON");
      ++design_.warningCount;
    } else if (k == "VIA") {
      const Token viaTok = lex_.next();
      const ViaRef ref = findVia(viaTok.text);
      if (!ref.valid() || viaTok.quoted) lex_.failAt(viaTok, "unknown via " + quoteToken(viaTok.text));
      if (isOrientName(lex_.peek())) {
        const Token o = lex_.next();
        if (o.text != "N") {
          countSkip("SPECIALNETS.VIA.ORIENT");
          ++design_.warningCount;
        }
      }
      if (!peekIs("(")) unexpected(lex_.peek(), "'('");
      while (peekIs("(")) net.vias.push_back({ref, readPoint(), std::string()});
    } else if (k.empty() || k == ";") {
      unexpected(kw, "a special net option");
    } else {
      skipToOptionEnd();
      countSkip("SPECIALNETS." + std::string(k));
    }
  }
  design_.specialNets.push_back(std::move(net));
}

// A special via at `at`, or "DO nx BY ny STEP dx dy": an array of them from `at`.
void DefParser::readSpecialViaArray(SpecialNet& net, ViaRef ref, Point at, const std::string& shape) {
  int numX = 1, numY = 1;
  Dbu stepX = 0, stepY = 0;
  if (lex_.accept("DO")) {
    const Token nt = lex_.peek();
    const int64_t nx = lex_.integer();
    lex_.expect("BY");
    const int64_t ny = lex_.integer();
    if (nx < 1 || ny < 1 || nx * ny > 1000000) lex_.failAt(nt, "bad via array size");
    numX = static_cast<int>(nx);
    numY = static_cast<int>(ny);
    lex_.expect("STEP");
    stepX = lex_.dbu();
    stepY = lex_.dbu();
    const int64_t lastX = at.x + (nx - 1) * stepX, lastY = at.y + (ny - 1) * stepY;
    if (!withinDbuRange(lastX) || !withinDbuRange(lastY)) {
      lex_.failAt(nt, "via array ends at (" + std::to_string(lastX) + " " + std::to_string(lastY) +
                          "), beyond the engine's range, " + dbuRangeText());
    }
  }
  requireViaInRange(lex_.line(), ref, Point{at.x + (numX - 1) * stepX, at.y + (numY - 1) * stepY});
  requireViaInRange(lex_.line(), ref, at);
  for (int i = 0; i < numX; ++i) {
    for (int j = 0; j < numY; ++j) net.vias.push_back({ref, Point{at.x + i * stepX, at.y + j * stepY}, shape});
  }
}

void DefParser::readSpecialWiring(SpecialNet& net) {
  if (peekIs("+")) return;  // "+ ROUTED + RECT ...": the shape is a net-level option
  while (true) {
    PathCursor cur;
    cur.layer = routingLayerAt(lex_.next());
    const Dbu width = lex_.dbu();
    if (width < 0) lex_.fail(lex_.line(), "negative wire width");
    std::string shape;
    while (peekIs("+")) {
      lex_.next();
      const Token kw = lex_.next();
      lex_.upcase(kw);
      if (is(kw, "SHAPE")) {
        shape = plainWord("a shape type");
      } else if (is(kw, "STYLE") || is(kw, "MASK")) {
        const Token v = lex_.peek();
        const int64_t value = lex_.integer();
        if (is(kw, "STYLE")) {
          useStyle(v, value);
        } else {
          checkMask(v, value, false);
        }
        countSkip("SPECIALNETS." + std::string(kw.text));
      } else {
        unexpected(kw, "SHAPE, STYLE or MASK");
      }
    }
    if (!peekIs("(")) unexpected(lex_.peek(), "'(' starting the wire's points");
    while (true) {
      const Token& t = lex_.peek();
      if (is(t, "(")) {
        Dbu ext = -1;
        const int line = t.line;
        const Point p = readPathPoint(lex_, cur, ext);
        if (ext >= 0) {
          countSkip("SPECIALNETS.EXT");
          ++design_.warningCount;
        }
        if (cur.havePoint) {
          const bool diagonal = p.x != cur.at.x && p.y != cur.at.y;
          if (diagonal && std::abs(int64_t(p.x) - cur.at.x) != std::abs(int64_t(p.y) - cur.at.y)) {
            lex_.fail(line, "diagonal wire that is not at 45 degrees");
          }
          if (diagonal) {  // 45-degree special wiring (DEF 5.8 allows it): not kept, counted and warned
            countSkip("SPECIALNETS.DIAGONAL");
            warn(line, "45-degree special wire not kept");
          } else {
            net.wires.push_back({cur.layer, width, shape, cur.at, p});
          }
          cur.emitted = true;
        }
        cur.at = p;
        cur.havePoint = true;
      } else if (is(t, "MASK")) {
        lex_.next();
        const Token v = lex_.peek();
        const int64_t value = lex_.integer();
        checkMask(v, value, !peekIs("("));
        countSkip("SPECIALNETS.MASK");
      } else if (is(t, "NEW") || is(t, "+") || is(t, ";")) {
        if (cur.havePoint && !cur.emitted) net.wires.push_back({cur.layer, width, shape, cur.at, cur.at});
        if (!is(t, "NEW")) return;
        lex_.next();
        break;
      } else {
        const Token viaTok = lex_.next();
        const ViaRef ref = readPathVia(viaTok, cur.havePoint, "SPECIALNETS");
        readSpecialViaArray(net, ref, cur.at, shape);
        cur.layer = layerAfterVia(viaTok, ref, cur.layer);
        cur.emitted = true;
      }
    }
  }
}

// ---------------------------------------------------------------------------
// NETS

void DefParser::readNets() {
  const int declared = readSectionCount();
  design_.nets.reserve(design_.nets.size() + saneReserve(declared));
  design_.netIndex.reserve(design_.netIndex.size() + saneReserve(declared));
  readEntries("NETS", declared, [&] { readNet(); });
}

void DefParser::readNet() {
  const Token nameTok = entryName("a net name");
  if (is(nameTok, "MUSTJOIN")) {
    lex_.skipStatement();
    countSkip("NETS.MUSTJOIN");
    return;
  }
  const NetId id(static_cast<int32_t>(design_.nets.size()));
  if (!design_.netIndex.emplace(std::string(nameTok.text), id).second) {
    lex_.failAt(nameTok, "duplicate net " + quoteToken(nameTok.text));
  }
  Net& net = design_.nets.emplace_back();
  net.name = std::string(nameTok.text);
  while (peekIs("(")) {
    lex_.next();
    const Token compTok = lex_.next();
    const Token pinTok = lex_.next();
    if (is(compTok, ")") || is(pinTok, ")")) unexpected(is(compTok, ")") ? compTok : pinTok, "a pin reference");
    if (is(compTok, "PIN")) {
      auto it = design_.ioPinIndex.find(pinTok.text);
      if (it == design_.ioPinIndex.end()) lex_.failAt(pinTok, "unknown pin " + quoteToken(pinTok.text));
      design_.pinRefs.push_back({CompId(), *it->second});
    } else if (is(compTok, "*")) {
      countSkip("NETS.WILDCARDPIN");
      ++design_.warningCount;
    } else {
      auto it = design_.compIndex.find(compTok.text);
      if (it == design_.compIndex.end()) lex_.failAt(compTok, "unknown component " + quoteToken(compTok.text));
      const Macro& macro = tech_.macros[*design_.components[*it->second].macro];
      auto pit = macro.pinIndex.find(pinTok.text);
      if (pit == macro.pinIndex.end()) {
        lex_.failAt(pinTok, "component " + quoteToken(compTok.text) + " (macro " + macro.name + ") has no pin " +
                                quoteToken(pinTok.text));
      }
      design_.pinRefs.push_back({it->second, pit->second});
    }
    if (lex_.accept("+")) {
      lex_.expect("SYNTHESIZED");
      countSkip("NETS.SYNTHESIZED");
    }
    lex_.expect(")");
  }
  for (Token kw; nextOption(kw);) {
    const std::string_view k = kw.quoted ? std::string_view() : kw.text;
    if (k == "ROUTED" || k == "FIXED" || k == "COVER" || k == "NOSHIELD") {
      if (k != "ROUTED") countSkip("NETS." + std::string(k));
      readRegularWiring(net);
    } else if (k == "USE") {
      net.use = plainWord("a net use");
    } else if (k == "NONDEFAULTRULE") {
      net.ndr = netRule(lex_.next());
    } else if (k.empty() || k == ";") {
      unexpected(kw, "a net option");
    } else {
      skipToOptionEnd();
      countSkip("NETS." + std::string(k));
    }
  }
  if (net.ndr >= 0) {  // the rule may come after the wiring: widths are set once the net is read
    const NonDefaultRule& rule = design_.ndrs[net.ndr];
    for (RouteWire& w : net.routing.wires) {
      const NdrLayer* l = rule.find(w.layer);
      if (l != nullptr && w.width == 0) w.width = l->width;
    }
  }
  design_.netPinStart.push_back(static_cast<int32_t>(design_.pinRefs.size()));
}

void DefParser::readRegularWiring(Net& net) {
  NetRouting& r = net.routing;
  while (true) {
    PathCursor cur;
    cur.layer = routingLayerAt(lex_.next());
    // TAPER: this layer's wires of the path (up to its next via) at the layer's default width,
    // not the net's NONDEFAULTRULE width (0 = the width the net's rule implies); that via and the
    // path's RECT patches are drawn to the default rule too (RouteVia::taper, RoutePatch::taper).
    Dbu width = 0;
    while (true) {
      if (lex_.accept("TAPER")) {
        width = tech_.layer(cur.layer).width;
      } else if (lex_.accept("TAPERRULE")) {
        lex_.word("a rule name");
        countSkip("NETS.TAPERRULE");
      } else if (lex_.accept("STYLE")) {
        const Token v = lex_.peek();
        useStyle(v, lex_.integer());
        countSkip("NETS.STYLE");
      } else {
        break;
      }
    }
    if (!peekIs("(")) unexpected(lex_.peek(), "'(' starting the wire's points");
    while (true) {
      const Token& t = lex_.peek();
      if (is(t, "(")) {
        Dbu ext = -1;
        const int line = t.line;
        const Point p = readPathPoint(lex_, cur, ext);
        if (cur.havePoint) {
          if (p.x != cur.at.x && p.y != cur.at.y) lex_.fail(line, "diagonal wire");
          r.wires.push_back({cur.layer, cur.at, p, width, cur.ext, ext});
          cur.emitted = true;
        }
        cur.at = p;
        cur.ext = ext;
        cur.havePoint = true;
      } else if (is(t, "MASK")) {
        lex_.next();
        const Token v = lex_.peek();
        const int64_t value = lex_.integer();
        checkMask(v, value, !peekIs("(") && !peekIs("RECT"));  // else a via's mask
        countSkip("NETS.MASK");
      } else if (is(t, "RECT")) {
        const Token rectTok = lex_.next();
        if (!cur.havePoint) lex_.failAt(rectTok, "RECT before any point");
        lex_.expect("(");
        const Dbu x1 = lex_.dbu(), y1 = lex_.dbu(), x2 = lex_.dbu(), y2 = lex_.dbu();
        lex_.expect(")");
        const Point a{cur.at.x + x1, cur.at.y + y1}, b{cur.at.x + x2, cur.at.y + y2};  // each term within kMaxDbu
        checkCorners(rectTok.line, {x1, y1}, {x2, y2}, "RECT");
        r.patches.push_back({cur.layer, Rect::fromCorners(a, b), width != 0});
        requireInRange(rectTok.line, r.patches.back().rect, "RECT");
        cur.emitted = true;
      } else if (is(t, "VIRTUAL")) {
        lex_.next();
        cur.at = readPoint();
        cur.ext = -1;
        cur.havePoint = true;
        countSkip("NETS.VIRTUAL");
      } else if (is(t, "NEW") || is(t, "+") || is(t, ";")) {
        if (cur.havePoint && !cur.emitted) r.wires.push_back({cur.layer, cur.at, cur.at, width, cur.ext, cur.ext});
        if (!is(t, "NEW")) return;
        lex_.next();
        break;
      } else {
        const Token viaTok = lex_.next();
        const ViaRef ref = readPathVia(viaTok, cur.havePoint, "NETS");
        requireViaInRange(viaTok.line, ref, cur.at);
        r.vias.push_back({ref, cur.at, width != 0});
        cur.layer = layerAfterVia(viaTok, ref, cur.layer);
        width = 0;
        cur.emitted = true;
      }
    }
  }
}

}  // namespace xroute
