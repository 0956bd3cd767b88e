// LEF MACRO blocks: CLASS, ORIGIN, SIZE, SYMMETRY, SITE, PIN (DIRECTION, USE,
// PORT geometry) and OBS. Shapes are stored shifted by the ORIGIN, so that
// the macro's lower-left corner is (0,0) (see MacroShape).
#include <cctype>

#include "io/lef_parser.hpp"

namespace xroute {

namespace {

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

Rect boundingBox(const std::vector<Point>& pts) {
  Rect r{pts.front().x, pts.front().y, pts.front().x, pts.front().y};
  for (const Point& p : pts) r.expandToInclude({p.x, p.y, p.x, p.y});
  return r;
}

void shift(std::vector<MacroShape>& shapes, Point by) {
  if (by.x == 0 && by.y == 0) return;
  for (MacroShape& s : shapes) {
    s.rect = s.rect.translated(by);
    for (Point& p : s.polygon) p = {p.x + by.x, p.y + by.y};
  }
}

bool sameShapes(const std::vector<MacroShape>& a, const std::vector<MacroShape>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].layer != b[i].layer || !(a[i].rect == b[i].rect) || a[i].polygon != b[i].polygon) return false;
  }
  return true;
}

// Same geometry and pins: a MACRO defined twice like this is read once, with a warning.
bool sameMacro(const Macro& a, const Macro& b) {
  if (a.macroClass != b.macroClass || !(a.origin == b.origin) || a.width != b.width || a.height != b.height ||
      a.site != b.site || a.symmetry != b.symmetry || a.pins.size() != b.pins.size() ||
      !sameShapes(a.obstructions, b.obstructions)) {
    return false;
  }
  for (size_t i = 0; i < a.pins.size(); ++i) {
    const MacroPin& p = a.pins[i];
    const MacroPin& q = b.pins[i];
    if (p.name != q.name || p.direction != q.direction || p.use != q.use || !sameShapes(p.shapes, q.shapes)) {
      return false;
    }
  }
  return true;
}

}  // namespace

void LefParser::parseMacro(const Token& opener) {
  const Token n = name("a macro name");
  const MacroId earlier = tech_.findMacro(n.text);
  Scope scope(*this, "MACRO", n.text, opener.line);
  Macro macro;
  macro.name = std::string(n.text);
  while (true) {
    const Token kw = keyword("MACRO");
    const std::string_view k = kw.text;
    if (k == "END") {
      endBlock(macro.name);
      break;
    } else if (k == "PIN") {
      parsePin(macro, kw);
    } else if (k == "OBS") {
      Scope obs(*this, "OBS", "", kw.line);
      parseGeometry("OBS", macro.obstructions);
    } else if (k == "CLASS") {
      macro.macroClass = restOfStatement();
    } else if (k == "ORIGIN") {
      macro.origin = point();
      endStatement();
    } else if (k == "SIZE") {
      // A negative size would mirror the placed geometry: refused.
      macro.width = nonNegativeDist("MACRO SIZE width");
      expect("BY");
      macro.height = nonNegativeDist("MACRO SIZE height");
      endStatement();
    } else if (k == "SYMMETRY") {
      macro.symmetry = restOfStatement();
    } else if (k == "SITE") {
      const Token s = name("a site name");
      if (!tech_.siteIndex.count(s.text)) failAt(s, "unknown site " + quoteToken(s.text));
      if (macro.site.empty()) macro.site = std::string(s.text);
      if (!accept(";")) skipStatement("MACRO", Token{"SITE.PATTERN", s.line, false});  // x y orient [DO..STEP]
    } else if (k == "TIMING") {  // LEF 5.3 timing tables: "TIMING ... END TIMING"
      skipBlock("MACRO", kw, "TIMING");
    } else if (k == "DENSITY") {  // DENSITY LAYER l ; RECT ... ; ... END
      Scope density(*this, "DENSITY", "", kw.line);
      while (true) {
        const Token t = next();
        if (!t.quoted && isKeyword(t.text, "END")) break;
      }
      count("MACRO", k);
    } else {
      skipStatement("MACRO", kw);  // FOREIGN, SOURCE, EEQ, LEQ, POWER, PROPERTY, FIXEDMASK, ...
    }
  }
  // Shapes were read relative to the LEF origin; move them so that the
  // macro's lower-left corner is (0,0), whichever order the statements came in.
  for (MacroPin& p : macro.pins) shift(p.shapes, macro.origin);
  shift(macro.obstructions, macro.origin);
  if (earlier.valid()) {
    // A repeated identical MACRO (Nangate45.lef then Nangate45_stdcell.lef in OpenROAD's tests) is
    // read once, with a warning. Two different ones conflict: OpenROAD would merge them into one
    // master (gf180's IO LEF); a router cannot know which pins are meant, so that is an error.
    if (!sameMacro(tech_.macros[*earlier], macro)) {
      failAt(n, "MACRO " + quoteToken(n.text) + " defined again with different pins, geometry or size: conflicting definitions");
    }
    warn(n.line, "MACRO " + quoteToken(n.text) + " defined again, identically: read once");
    return;
  }
  tech_.macroIndex.emplace(macro.name, MacroId(static_cast<int32_t>(tech_.macros.size())));
  tech_.macros.push_back(std::move(macro));
}

void LefParser::parsePin(Macro& macro, const Token& opener) {
  const Token n = next();
  if (n.quoted || n.text == ";") failAt(n, "expected a pin name, found " + quoteToken(n.text));
  Scope scope(*this, "PIN", n.text, opener.line);
  MacroPin pin;
  pin.name = std::string(n.text);
  const auto earlier = macro.pinIndex.find(n.text);
  while (true) {
    const Token kw = keyword("PIN");
    const std::string_view k = kw.text;
    if (k == "END") {
      endBlock(pin.name);
      break;
    } else if (k == "PORT") {
      Scope port(*this, "PORT", "", kw.line);
      parseGeometry("PORT", pin.shapes);
      ++pin.portCount;
    } else if (k == "DIRECTION") {
      const Token d = name("a pin direction");
      pin.direction = upper(d.text);
      if (pin.direction != "INPUT" && pin.direction != "OUTPUT" && pin.direction != "INOUT" &&
          pin.direction != "FEEDTHRU") {
        failAt(d, "unknown pin DIRECTION " + quoteToken(d.text));
      }
      if (pin.direction == "OUTPUT") accept("TRISTATE");
      endStatement();
    } else if (k == "USE") {
      const Token u = name("a pin use");
      pin.use = upper(u.text);
      if (pin.use != "SIGNAL" && pin.use != "ANALOG" && pin.use != "POWER" && pin.use != "GROUND" &&
          pin.use != "CLOCK") {
        failAt(u, "unknown pin USE " + quoteToken(u.text));
      }
      endStatement();
    } else {
      skipStatement("PIN", kw);  // SHAPE, NETEXPR, ANTENNA*, MUSTJOIN, TAPERRULE, PROPERTY, ...
    }
  }
  if (earlier != macro.pinIndex.end()) {  // a pin written twice: its ports join the first one's
    MacroPin& first = macro.pins[earlier->second];
    first.shapes.insert(first.shapes.end(), pin.shapes.begin(), pin.shapes.end());
    first.portCount += pin.portCount;
    warn(n.line, "PIN " + quoteToken(n.text) + " defined again in MACRO " + quoteToken(macro.name) +
                     ": its ports are added to the first definition");
    return;
  }
  macro.pinIndex.emplace(pin.name, static_cast<int>(macro.pins.size()));
  macro.pins.push_back(std::move(pin));
}

// The body of a PORT or OBS, up to its lone END. LAYER options (SPACING,
// DESIGNRULEWIDTH, EXCEPTPGNET, MASK), PATH, WIDTH, CLASS and ITERATE forms
// are skipped and counted under "<block>.<KEYWORD>" / "<block>.LAYER.<WORD>".
void LefParser::parseGeometry(std::string_view block, std::vector<MacroShape>& shapes) {
  LayerId current;
  const std::string layerBlock = std::string(block) + ".LAYER";
  while (true) {
    const Token kw = keyword(block);
    const std::string_view k = kw.text;
    if (k == "END") return;
    if (k == "LAYER") {
      current = layerRef();
      if (!accept(";")) skipStatement(layerBlock, keyword("a LAYER statement"));
      continue;
    }
    if (k != "RECT" && k != "POLYGON" && k != "VIA") {
      skipStatement(block, kw);
      continue;
    }
    if (accept("MASK")) maskNumber(k == "VIA");  // the mask comes before ITERATE: "RECT MASK 2 ITERATE ..."
    if (peekIs("ITERATE")) {
      skipStatement(block, kw);
      continue;
    }
    if (k == "VIA") {
      if (accept("MASK")) maskNumber(true);
      const Point at = point();
      const Token v = name("a via name");
      const ViaId via = tech_.findVia(v.text);
      if (!via.valid()) failAt(v, "unknown via " + quoteToken(v.text));
      endStatement();
      for (const ViaShape& s : tech_.vias[*via].shapes) shapes.push_back({s.layer, s.rect.translated(at), {}});
      continue;
    }
    if (!current.valid()) failAt(kw, std::string(k) + " before LAYER in " + std::string(block));
    if (k == "RECT") {
      const Rect r = rect();
      endStatement();
      shapes.push_back({current, r, {}});
    } else {
      std::vector<Point> pts = polygon();
      const Rect r = boundingBox(pts);
      shapes.push_back({current, r, std::move(pts)});
    }
  }
}

}  // namespace xroute
