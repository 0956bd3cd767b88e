// LEF LAYER blocks: TYPE, the routing-layer geometry and spacing rules, the
// cut-layer width and spacing rules, and PROPERTY pairs (LEF58 strings are
// parsed in lef58.cpp). Everything else in a layer is skipped and counted
// under "LAYER.<KEYWORD>".
#include "io/lef_parser.hpp"

namespace xroute {

namespace {

bool typeFromName(std::string_view s, LayerType& out) {
  if (s == "ROUTING") out = LayerType::Routing;
  else if (s == "CUT") out = LayerType::Cut;
  else if (s == "MASTERSLICE") out = LayerType::Masterslice;
  else if (s == "OVERLAP") out = LayerType::Overlap;
  else if (s == "IMPLANT") out = LayerType::Implant;
  else return false;
  return true;
}

// Whether a LAYER statement the reader skips states a design rule (Layer::unjudged): not the
// electrical and process descriptions (RESISTANCE, CAPACITANCE, THICKNESS, ...), not the
// parameters of another statement's rule (ANTENNAMODEL selects the oxide the ANTENNA ratios after
// it apply to; the density window and step belong to MAXIMUMDENSITY / MINIMUMDENSITY), nor the
// diagonal-routing values of a router that draws no diagonal metal, nor the track values a cut or
// other layer may carry (PITCH, OFFSET, DIRECTION describe tracks, not a rule of the layout).
bool isRuleKeyword(std::string_view k) {
  static constexpr std::string_view kNotRules[] = {
      "PITCH", "OFFSET", "DIRECTION", "RESISTANCE", "CAPACITANCE", "EDGECAPACITANCE", "CAPMULTIPLIER", "THICKNESS", "HEIGHT", "SHRINKAGE",
      "WIREEXTENSION", "ANTENNAMODEL", "DENSITYCHECKWINDOW", "DENSITYCHECKSTEP", "FILLACTIVESPACING",
      "DIAGPITCH", "DIAGWIDTH", "DIAGSPACING", "DIAGMINEDGELENGTH"};
  for (std::string_view n : kNotRules) {
    if (k == n) return false;
  }
  return true;
}

}  // namespace

// DIRECTION HORIZONTAL | VERTICAL ;  (DIAG45 / DIAG135 are counted and read as no direction)
void LefParser::parseLayerDirection(Layer& layer) {
  const Token d = name("HORIZONTAL or VERTICAL");
  if (isKeyword(d.text, "HORIZONTAL")) {
    layer.direction = Direction::Horizontal;
  } else if (isKeyword(d.text, "VERTICAL")) {
    layer.direction = Direction::Vertical;
  } else if (isKeyword(d.text, "DIAG45") || isKeyword(d.text, "DIAG135")) {
    layer.direction = Direction::None;
    count("LAYER.DIRECTION", d.text);
  } else {
    failAt(d, "unknown DIRECTION " + quoteToken(d.text));
  }
  endStatement();
}

// PITCH p [py] ;  |  OFFSET o [oy] ;  (one value: the same along x and y; an offset may be negative)
void LefParser::parseLayerPitchOrOffset(Layer& layer, bool pitch) {
  const std::string what = std::string(pitch ? "PITCH" : "OFFSET") + " of LAYER " + quoteToken(layer.name);
  // An OFFSET may be negative (asap7 writes one): it only places the first track.
  const Dbu a = pitch ? positiveDist(what) : dist();
  const Dbu b = peekIs(";") ? a : (pitch ? positiveDist(what) : dist());
  endStatement();
  if (pitch) {
    layer.pitchX = a;
    layer.pitchY = b;
  } else {
    layer.offsetX = a;
    layer.offsetY = b;
  }
}

// "{AC|DC}CURRENTDENSITY kind value ;" or a table written as several
// ';'-ended statements (FREQUENCY / WIDTH / CUTAREA ... TABLEENTRIES ... ;): skipped and counted.
void LefParser::skipCurrentDensity(std::string_view keyword) {
  next();  // PEAK / AVERAGE / RMS
  const bool table = !isNumberText(peek().text);
  bool seenEntries = !table;
  while (true) {
    const Token t = next();
    if (t.quoted) continue;
    if (isKeyword(t.text, "TABLEENTRIES")) seenEntries = true;
    if (t.text == ";" && seenEntries) break;
  }
  count("LAYER", keyword);
}

void LefParser::parseLayer(const Token& opener) {
  const Token n = name("a layer name");
  if (tech_.findLayer(n.text).valid()) failAt(n, "duplicate LAYER " + quoteToken(n.text));
  Scope scope(*this, "LAYER", n.text, opener.line);
  Layer layer;
  layer.name = std::string(n.text);
  layer.path = lex_.path();
  layer.line = n.line;
  bool hasType = false;
  while (true) {
    const Token kw = keyword("LAYER");
    const std::string_view k = kw.text;
    if (k == "END") {
      endBlock(layer.name);
      break;
    }
    if (k == "TYPE") {
      const Token t = name("a layer type");
      lex_.upcase(t);
      LayerType type = LayerType::Other;
      if (!typeFromName(t.text, type)) {
        failAt(t, "unknown layer TYPE " + quoteToken(t.text) + " (ROUTING, CUT, MASTERSLICE, OVERLAP, IMPLANT)");
      }
      if (hasType && type != layer.type) failAt(kw, "second TYPE in LAYER " + quoteToken(layer.name) + ", a different one");
      if (hasType) warn(kw.line, "TYPE repeated in LAYER " + quoteToken(layer.name));  // asap7's M7 does this
      layer.type = type;
      hasType = true;
      endStatement();
      continue;
    }
    if (k == "PROPERTY") {
      parseLayerProperty(layer, kw);
      continue;
    }
    const bool routing = layer.type == LayerType::Routing;
    const bool cut = layer.type == LayerType::Cut;
    if (!hasType && (k == "SPACING" || k == "SPACINGTABLE" || k == "WIDTH")) {
      failAt(kw, std::string(k) + " before TYPE in LAYER " + quoteToken(layer.name));
    }
    if ((routing || cut) && k == "WIDTH") {
      layer.width = positiveDist("WIDTH of LAYER " + quoteToken(layer.name));
      endStatement();
    } else if (routing && k == "DIRECTION") {
      parseLayerDirection(layer);
    } else if (routing && (k == "PITCH" || k == "OFFSET")) {
      parseLayerPitchOrOffset(layer, k == "PITCH");
    } else if (routing && k == "MINWIDTH") {
      layer.minWidth = positiveDist("MINWIDTH of LAYER " + quoteToken(layer.name));
      noteUnjudged(layer, "MINWIDTH");  // stored for the router; no marker judges it
      endStatement();
    } else if (routing && k == "AREA") {
      const Token at = peek();
      layer.minArea = area();
      if (layer.minArea < 0) failAt(at, "AREA of LAYER " + quoteToken(layer.name) + " must not be negative");
      endStatement();
    } else if (routing && k == "SPACING") {
      parseRoutingSpacing(layer, kw);
    } else if (routing && k == "SPACINGTABLE") {
      parseSpacingTable(layer, kw);
    } else if (cut && k == "SPACING") {
      parseCutSpacing(layer, kw);
    } else if (k == "ACCURRENTDENSITY" || k == "DCCURRENTDENSITY") {
      skipCurrentDensity(k);
    } else {
      if (isRuleKeyword(k)) noteUnjudged(layer, std::string(k));
      skipStatement("LAYER", kw);
    }
  }
  if (!hasType) failAt(n, "LAYER " + quoteToken(layer.name) + " has no TYPE");
  // Only metal and cut layers carry routing: the rules of implant or masterslice layers judge cells.
  if (layer.type != LayerType::Routing && layer.type != LayerType::Cut) layer.unjudged.clear();

  const LayerId id(static_cast<int32_t>(tech_.layers.size()));
  if (layer.type == LayerType::Routing) {
    layer.routingIndex = static_cast<int>(tech_.routingLayers.size());
    tech_.routingLayers.push_back(id);
  } else if (layer.type == LayerType::Cut) {
    layer.cutIndex = static_cast<int>(tech_.cutLayers.size());
    tech_.cutLayers.push_back(id);
  }
  tech_.layerIndex.emplace(layer.name, id);
  tech_.layers.push_back(std::move(layer));
}

// SPACING s ;  |  SPACING s RANGE lo hi ;  |  SPACING s SAMENET ;
// SPACING s ENDOFLINE w WITHIN d [PARALLELEDGE p WITHIN q [TWOEDGES]] ;
// Any other form is skipped whole and counted as "LAYER.SPACING.<WORD>".
void LefParser::parseRoutingSpacing(Layer& layer, const Token& kw) {
  const Dbu space = nonNegativeDist("SPACING of LAYER " + quoteToken(layer.name));
  if (accept(";")) {
    layer.spacings.push_back({space, false, 0, 0, false});
    return;
  }
  const Token t = peek();
  if (!t.quoted && isKeyword(t.text, "RANGE")) {
    next();
    SpacingRule r;
    r.space = space;
    r.hasRange = true;
    r.rangeLo = dist();
    r.rangeHi = dist();
    if (accept(";")) {
      layer.spacings.push_back(r);
      return;
    }
  } else if (!t.quoted && isKeyword(t.text, "SAMENET")) {
    next();
    if (accept(";")) {
      layer.spacings.push_back({space, false, 0, 0, true});
      noteUnjudged(layer, "SPACING SAMENET");  // kept, not judged on metal (drc/README.md)
      return;
    }
  } else if (!t.quoted && isKeyword(t.text, "ENDOFLINE")) {
    next();
    EolRule e;
    e.space = space;
    e.eolWidth = dist();
    expect("WITHIN");
    e.within = dist();
    if (accept("PARALLELEDGE")) {
      e.parallelEdge = true;
      e.parSpace = dist();
      expect("WITHIN");
      e.parWithin = dist();
      e.twoEdges = accept("TWOEDGES");
    }
    if (accept(";")) {
      layer.eolRules.push_back(e);
      return;
    }
  }
  // A form this reader does not model: drop the whole statement, say which.
  const Token stop = keyword("a LAYER SPACING statement");
  noteUnjudged(layer, "SPACING " + std::string(stop.text));
  skipStatement("LAYER.SPACING", stop);
}

// SPACING s [CENTERTOCENTER] [SAMENET] [ADJACENTCUTS n WITHIN d] ; on a cut
// layer. Other forms (LAYER, AREA, PARALLELOVERLAP, ...) are skipped and
// counted as "LAYER.SPACING.<WORD>".
void LefParser::parseCutSpacing(Layer& layer, const Token& kw) {
  CutSpacingRule r;
  r.space = nonNegativeDist("SPACING of LAYER " + quoteToken(layer.name));
  r.centerToCenter = accept("CENTERTOCENTER");
  r.sameNet = accept("SAMENET");
  if (accept("ADJACENTCUTS")) {
    const Token nTok = peek();
    const int64_t n = integer();
    if (n < 1 || n > 8) failAt(nTok, "ADJACENTCUTS must be 1..8, found " + quoteToken(nTok.text));
    r.adjacentCuts = static_cast<int>(n);
    expect("WITHIN");
    r.cutWithin = dist();
  }
  if (accept(";")) {
    layer.cutSpacings.push_back(r);
    return;
  }
  const Token stop = keyword("a cut LAYER SPACING statement");
  noteUnjudged(layer, "SPACING " + std::string(stop.text));
  skipStatement("LAYER.SPACING", stop);
}

// SPACINGTABLE PARALLELRUNLENGTH l1 .. ln  WIDTH w1 s11 .. s1n  WIDTH ... ;
// TWOWIDTHS and INFLUENCE tables are skipped and counted.
void LefParser::parseSpacingTable(Layer& layer, const Token& kw) {
  const Token form = keyword("SPACINGTABLE");
  if (!isKeyword(form.text, "PARALLELRUNLENGTH")) {
    noteUnjudged(layer, "SPACINGTABLE " + std::string(form.text));
    skipStatement("LAYER.SPACINGTABLE", form);
    return;
  }
  if (!layer.prlTable.empty()) failAt(kw, "second SPACINGTABLE PARALLELRUNLENGTH in LAYER " + quoteToken(layer.name));
  PrlSpacingTable table;
  while (!peekIs("WIDTH") && !peekIs(";")) {
    const Token t = peek();
    const Dbu v = dist();
    if (!table.prls.empty() && v < table.prls.back()) {
      failAt(t, "PARALLELRUNLENGTH values must be ascending, found " + quoteToken(t.text));
    }
    table.prls.push_back(v);
  }
  if (table.prls.empty()) failAt(peek(), "SPACINGTABLE PARALLELRUNLENGTH needs at least one length");
  while (!accept(";")) {
    const Token w = peek();
    if (w.quoted || !isKeyword(w.text, "WIDTH")) failAt(w, "expected WIDTH or ';' in SPACINGTABLE, found " + quoteToken(w.text));
    next();
    const Token wv = peek();
    const Dbu width = dist();
    // A row narrower than the one before (ISPD-2018 test4-test10's Metal9 ends with one) cannot be
    // reached by a lookup in ascending widths: it is read, then left out, with a warning.
    const bool outOfOrder = !table.widths.empty() && width < table.widths.back();
    if (outOfOrder) {
      warn(wv.line, "SPACINGTABLE row WIDTH " + std::string(wv.text) + " of LAYER " + quoteToken(layer.name) +
                        " is narrower than the row before it: left out (widths must ascend)");
    } else {
      table.widths.push_back(width);
    }
    for (size_t i = 0; i < table.prls.size(); ++i) {
      if (peekIs("WIDTH") || peekIs(";")) {
        failAt(peek(), "SPACINGTABLE row WIDTH " + std::string(wv.text) + " has " + std::to_string(i) +
                           " spacing values, expected " + std::to_string(table.prls.size()) +
                           " (one per PARALLELRUNLENGTH)");
      }
      const Dbu space = nonNegativeDist("SPACINGTABLE spacing of LAYER " + quoteToken(layer.name));
      if (!outOfOrder) table.spacing.push_back(space);
    }
  }
  if (table.widths.empty()) failAt(kw, "SPACINGTABLE PARALLELRUNLENGTH without a WIDTH row");
  layer.prlTable = std::move(table);
}

// PROPERTY name value [name value ...] ; every pair is kept as written;
// LEF58_CORNERSPACING is also parsed into rules. Other LEF58_* strings are
// kept but not interpreted, and counted as "LAYER.PROPERTY.<NAME>".
void LefParser::parseLayerProperty(Layer& layer, const Token& kw) {
  do {
    const Token pn = name("a property name");
    const Token value = next();
    if (!value.quoted && value.text == ";") failAt(value, "PROPERTY " + quoteToken(pn.text) + " has no value");
    layer.properties.emplace_back(std::string(pn.text), std::string(value.text));
    if (pn.text == "LEF58_CORNERSPACING" && value.quoted) {
      parseLef58CornerSpacing(layer, value);
    } else if (pn.text.substr(0, 6) == "LEF58_") {
      if (pn.text != "LEF58_TYPE") noteUnjudged(layer, std::string(pn.text));  // a TYPE is no rule
      count("LAYER.PROPERTY", pn.text);
    }
  } while (!accept(";"));
}

}  // namespace xroute
