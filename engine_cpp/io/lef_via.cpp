// LEF VIA (fixed vias: LAYER + RECT/POLYGON shapes) and VIARULE blocks.
#include "io/lef_parser.hpp"

namespace xroute {

namespace {

// bottom / cut / top from the shapes' layers: the cut is the CUT layer; the
// bottom and top are the nearest other layers below and above it in LEF
// order. A via without a cut shape gets its lowest and highest layers.
void deriveViaLayers(const Tech& tech, Via& via) {
  for (const ViaShape& s : via.shapes) {
    if (tech.layer(s.layer).type == LayerType::Cut) {
      via.cut = s.layer;
      break;
    }
  }
  for (const ViaShape& s : via.shapes) {
    if (tech.layer(s.layer).type == LayerType::Cut) continue;
    if (via.cut.valid()) {
      if (s.layer < via.cut && (!via.bottom.valid() || s.layer > via.bottom)) via.bottom = s.layer;
      if (s.layer > via.cut && (!via.top.valid() || s.layer < via.top)) via.top = s.layer;
    } else {
      if (!via.bottom.valid() || s.layer < via.bottom) via.bottom = s.layer;
      if (!via.top.valid() || s.layer > via.top) via.top = s.layer;
    }
  }
}

Rect boundingBox(const std::vector<Point>& pts) {
  Rect r{pts.front().x, pts.front().y, pts.front().x, pts.front().y};
  for (const Point& p : pts) r.expandToInclude({p.x, p.y, p.x, p.y});
  return r;
}

}  // namespace

void LefParser::parseVia(const Token& opener) {
  const Token n = name("a via name");
  if (tech_.findVia(n.text).valid()) failAt(n, "duplicate VIA " + quoteToken(n.text));
  Scope scope(*this, "VIA", n.text, opener.line);
  Via via;
  via.name = std::string(n.text);
  while (true) {  // header words on the VIA line
    if (accept("DEFAULT")) {
      via.isDefault = true;
    } else if (peekIs("GENERATED") || peekIs("TOPOFSTACKONLY")) {
      count("VIA", next().text);
    } else {
      break;
    }
  }
  LayerId current;
  while (true) {
    const Token kw = keyword("VIA");
    const std::string_view k = kw.text;
    if (k == "END") {
      endBlock(via.name);
      break;
    } else if (k == "LAYER") {
      current = layerRef();
      if (!accept(";")) skipStatement("VIA.LAYER", keyword("a VIA LAYER statement"));
    } else if (k == "RECT" || k == "POLYGON") {
      if (!current.valid()) failAt(kw, std::string(k) + " before LAYER in VIA " + quoteToken(via.name));
      Rect r;
      if (k == "RECT") {
        r = rect();
        endStatement();
      } else {
        r = boundingBox(polygon());
      }
      via.shapes.push_back({current, r});
    } else {
      skipStatement("VIA", kw);  // RESISTANCE, PROPERTY, VIARULE-style via parameters, ...
    }
  }
  deriveViaLayers(tech_, via);
  tech_.viaIndex.emplace(via.name, ViaId(static_cast<int32_t>(tech_.vias.size())));
  tech_.vias.push_back(std::move(via));
}

// VIARULE name [GENERATE [DEFAULT]]
//   LAYER l ; [ENCLOSURE a b ;] [WIDTH lo TO hi ;] [RECT ... ;] [SPACING x BY y ;]
//   ... (non-GENERATE rules: VIA name ; lines, skipped and counted)
// END name
void LefParser::parseViaRule(const Token& opener) {
  const Token n = name("a via rule name");
  if (tech_.findViaRule(n.text).valid()) failAt(n, "duplicate VIARULE " + quoteToken(n.text));
  Scope scope(*this, "VIARULE", n.text, opener.line);
  ViaRule rule;
  rule.name = std::string(n.text);
  if (accept("GENERATE")) {
    rule.generate = true;
    rule.isDefault = accept("DEFAULT");
  }
  while (true) {
    const Token kw = keyword("VIARULE");
    const std::string_view k = kw.text;
    if (k == "END") {
      endBlock(rule.name);
      break;
    }
    if (k == "LAYER") {
      ViaRuleLayer l;
      l.layer = layerRef();
      endStatement();
      rule.layers.push_back(l);
      continue;
    }
    const bool layerStatement = k == "ENCLOSURE" || k == "WIDTH" || k == "RECT" || k == "SPACING";
    if (!layerStatement) {
      skipStatement("VIARULE", kw);  // VIA (non-GENERATE lists), RESISTANCE, DIRECTION, OVERHANG, PROPERTY...
      continue;
    }
    if (rule.layers.empty()) failAt(kw, std::string(k) + " before LAYER in VIARULE " + quoteToken(rule.name));
    ViaRuleLayer& l = rule.layers.back();
    if (k == "ENCLOSURE") {
      l.enclosure1 = dist();
      l.enclosure2 = dist();
    } else if (k == "WIDTH") {
      l.hasWidth = true;
      l.widthLo = dist();
      expect("TO");
      l.widthHi = dist();
    } else if (k == "RECT") {
      l.cutRect = rect();
    } else {
      l.spacingX = dist();
      expect("BY");
      l.spacingY = dist();
    }
    endStatement();
  }
  tech_.viaRuleIndex.emplace(rule.name, ViaRuleId(static_cast<int32_t>(tech_.viaRules.size())));
  tech_.viaRules.push_back(std::move(rule));
}

}  // namespace xroute
