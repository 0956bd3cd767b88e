// DEF reader, PINS: the design's IO pins with their ports, shapes and
// placements (the parser's state is in def_parser.hpp; the other sections
// are in def_reader.cpp, def_vias.cpp and def_nets.cpp).
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "io/def_parser.hpp"

namespace xroute {

void DefParser::readPins() {
  const int declared = readSectionCount();
  design_.ioPins.reserve(design_.ioPins.size() + saneReserve(declared));
  readEntries("PINS", declared, [&] { readPin(); });
}

namespace {
// One + PORT of a pin (the part before the first + PORT counts as a port).
struct PinPort {
  std::vector<IoPinShape> shapes;
  PlaceStatus status = PlaceStatus::Unplaced;
  Point location;
  Orient orient = Orient::N;
};

// The ports' shapes into `pin`: with one placement for all ports the pin keeps
// it; otherwise the shapes are made absolute and false is returned.
bool placePorts(IoPin& pin, std::vector<PinPort>& ports) {
  bool samePlacement = true;
  for (const PinPort& p : ports) {
    samePlacement = samePlacement && p.status == ports[0].status && p.location == ports[0].location &&
                    p.orient == ports[0].orient;
  }
  if (samePlacement) {
    pin.status = ports[0].status;
    pin.location = ports[0].location;
    pin.orient = ports[0].orient;
    for (PinPort& p : ports) pin.shapes.insert(pin.shapes.end(), p.shapes.begin(), p.shapes.end());
    return true;
  }
  pin.status = PlaceStatus::Unplaced;
  for (PinPort& p : ports) {
    if (p.status != PlaceStatus::Unplaced && pin.status == PlaceStatus::Unplaced) pin.status = p.status;
    const Transform t{p.location, p.orient, 0, 0};
    for (const IoPinShape& s : p.shapes) pin.shapes.push_back({s.layer, t.apply(s.rect)});
  }
  return false;
}
}  // namespace

void DefParser::readPin() {
  const Token nameTok = entryName("a pin name");
  const IoPinId id(static_cast<int32_t>(design_.ioPins.size()));
  if (!design_.ioPinIndex.emplace(std::string(nameTok.text), id).second) {
    lex_.failAt(nameTok, "duplicate pin " + quoteToken(nameTok.text));
  }
  IoPin pin;
  pin.name = std::string(nameTok.text);
  std::vector<PinPort> ports(1);
  bool explicitPorts = false;
  for (Token kw; nextOption(kw);) {
    const std::string_view k = kw.quoted ? std::string_view() : kw.text;
    if (k == "NET") {
      pin.netName = plainWord("a net name");
    } else if (k == "DIRECTION") {
      pin.direction = plainWord("a direction");
    } else if (k == "USE") {
      pin.use = plainWord("a pin use");
    } else if (k == "PORT") {
      if (explicitPorts) ports.emplace_back();
      explicitPorts = true;
    } else if (k == "LAYER") {
      ports.back().shapes.push_back(readPinRect());
    } else if (k == "POLYGON") {
      ports.back().shapes.push_back(readPinPolygon());
    } else if (k == "VIA") {
      const Token viaTok = lex_.next();
      const ViaRef ref = findVia(viaTok.text);
      if (!ref.valid()) lex_.failAt(viaTok, "unknown via " + quoteToken(viaTok.text));
      if (lex_.accept("MASK")) {
        const Token v = lex_.peek();
        checkMask(v, lex_.integer(), true);
      }
      const Point at = readPoint();
      requireViaInRange(viaTok.line, ref, at);
      for (const ViaShape& s : design_.via(tech_, ref).shapes) {
        ports.back().shapes.push_back({s.layer, s.rect.translated(at)});
      }
    } else if (k == "PLACED" || k == "FIXED" || k == "COVER") {
      PinPort& p = ports.back();
      p.status = readPlacement(kw, p.location, p.orient);
    } else if (k.empty() || k == ";") {
      unexpected(kw, "a pin option");
    } else {
      skipToOptionEnd();
      countSkip("PINS." + std::string(k));
    }
  }
  if (!placePorts(pin, ports)) {
    countSkip("PINS.PORT.PLACEMENT");
    ++design_.warningCount;
  }
  // Placed shapes (location plus rect: each term within kMaxDbu, the sum fits) within the range too.
  const Transform t{pin.location, pin.orient, 0, 0};
  for (const IoPinShape& s : pin.shapes) requireInRange(nameTok.line, t.apply(s.rect), "pin shape");
  design_.ioPins.push_back(std::move(pin));
}

// "+ LAYER name [options] pt pt" after LAYER: the rect.
IoPinShape DefParser::readPinRect() {
  const LayerId layer = layerAt(lex_.next());
  while (!peekIs("(")) {
    const Token opt = lex_.next();
    if (is(opt, "MASK") || is(opt, "SPACING") || is(opt, "DESIGNRULEWIDTH")) {
      lex_.integer();
      countSkip("PINS.LAYER." + std::string(opt.text));
    } else {
      unexpected(opt, "'(' or MASK, SPACING, DESIGNRULEWIDTH");
    }
  }
  const int line = lex_.peek().line;
  const Point a = readPoint();
  const Point b = readPoint();
  if (a.x == b.x || a.y == b.y) warn(line, "pin RECT without area");
  checkCorners(line, a, b, "pin RECT");  // read as the rectangle between the corners, with a warning
  return {layer, Rect::fromCorners(a, b)};
}

// "+ POLYGON name [options] pt pt pt ..." after POLYGON: kept as its bounding box (counted, warned).
IoPinShape DefParser::readPinPolygon() {
  const LayerId layer = layerAt(lex_.next());
  while (!peekIs("(")) {
    const Token opt = lex_.next();
    if (is(opt, "MASK") || is(opt, "SPACING") || is(opt, "DESIGNRULEWIDTH")) {
      lex_.integer();
    } else {
      unexpected(opt, "'('");
    }
  }
  const Token first = lex_.peek();
  const std::vector<Point> pts = readPolygonPoints(first);
  Rect box{pts[0].x, pts[0].y, pts[0].x, pts[0].y};
  for (const Point& p : pts) box.expandToInclude(Rect{p.x, p.y, p.x, p.y});
  countSkip("PINS.POLYGON");
  ++design_.warningCount;
  return {layer, box};
}

void DefParser::resolveIoPinNets() {
  for (IoPin& p : design_.ioPins) p.net = design_.findNet(p.netName);
}

}  // namespace xroute
