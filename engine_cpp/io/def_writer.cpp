// DEF writer: the whole design as standard DEF 5.8, nets with their routing
// as ROUTED/NEW paths (one straight piece per path, vias as "NEW layer ( x y )
// VIA", patches as "NEW layer ( x y ) RECT ( 0 0 w h )"). A net of a
// NONDEFAULTRULE is written "+ NONDEFAULTRULE name": its wires have the rule's
// width by DEF's reading; one drawn at the default width is written "TAPER". The output depends
// only on the database, so the same design gives the same bytes.
#include <charconv>

#include "io/atomic_file.hpp"
#include "io/readers.hpp"

namespace xroute {

namespace {

class DefOut {
 public:
  std::string text;

  DefOut& operator<<(std::string_view s) {
    text.append(s);
    return *this;
  }
  DefOut& operator<<(char c) {
    text.push_back(c);
    return *this;
  }
  DefOut& operator<<(int64_t v) {
    char buf[24];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    text.append(buf, end);
    return *this;
  }
  DefOut& operator<<(int32_t v) { return *this << static_cast<int64_t>(v); }
  DefOut& operator<<(Point p) { return *this << "( " << p.x << ' ' << p.y << " )"; }
};

const char* statusKeyword(PlaceStatus s) {
  switch (s) {
    case PlaceStatus::Placed: return "PLACED";
    case PlaceStatus::Fixed: return "FIXED";
    case PlaceStatus::Cover: return "COVER";
    case PlaceStatus::Unplaced: return "UNPLACED";
  }
  return "UNPLACED";
}

// The layer a path that places this via starts on: its bottom layer.
LayerId viaPathLayer(const Via& v) {
  if (v.bottom.valid()) return v.bottom;
  if (v.top.valid()) return v.top;
  return v.shapes.empty() ? LayerId() : v.shapes.front().layer;
}

std::string_view layerName(const Tech& tech, LayerId id) {
  return id.valid() && *id < static_cast<int32_t>(tech.layers.size()) ? std::string_view(tech.layer(id).name)
                                                                       : std::string_view("?");
}

class DefWriter {
 public:
  DefWriter(const Tech& tech, const Design& design) : tech_(tech), d_(design) {}

  std::string write() {
    out_.text.reserve(1 << 16);
    writeHeader();
    writeRowsTracksGrid();
    writeVias();
    writeNonDefaultRules();
    writeComponents();
    writePins();
    writeBlockages();
    writeSpecialNets();
    writeNets();
    out_ << "END DESIGN\n";
    return std::move(out_.text);
  }

 private:
  std::string_view layer(LayerId id) const { return layerName(tech_, id); }

  void writeHeader() {
    out_ << "VERSION 5.8 ;\n";
    out_ << "DIVIDERCHAR \"" << d_.dividerChar << "\" ;\n";
    out_ << "BUSBITCHARS \"" << d_.busBitChars << "\" ;\n";
    out_ << "DESIGN " << d_.name << " ;\n";
    // UNITS and DIEAREA only when the design has them (a DEF may lack them).
    if (d_.dbuPerMicron != 0) out_ << "UNITS DISTANCE MICRONS " << d_.dbuPerMicron << " ;\n";
    out_ << '\n';
    if (d_.diePolygon.size() >= 2) {
      out_ << "DIEAREA";
      for (const Point& p : d_.diePolygon) out_ << ' ' << p;
      out_ << " ;\n\n";
    } else if (d_.dieArea.width() > 0 || d_.dieArea.height() > 0) {
      out_ << "DIEAREA " << Point{d_.dieArea.xlo, d_.dieArea.ylo} << ' ' << Point{d_.dieArea.xhi, d_.dieArea.yhi}
           << " ;\n\n";
    }
  }

  void writeRowsTracksGrid() {
    for (const Row& r : d_.rows) {
      out_ << "ROW " << r.name << ' ' << r.site << ' ' << r.origin.x << ' ' << r.origin.y << ' '
           << orientName(r.orient) << " DO " << r.numX << " BY " << r.numY << " STEP " << r.stepX << ' ' << r.stepY
           << " ;\n";
    }
    if (!d_.rows.empty()) out_ << '\n';
    for (const TrackPattern& t : d_.tracks) {
      out_ << "TRACKS " << (t.isX ? "X " : "Y ") << t.start << " DO " << t.count << " STEP " << t.step << " LAYER "
           << layer(t.layer) << " ;\n";
    }
    if (!d_.tracks.empty()) out_ << '\n';
    for (const GCellPattern& g : d_.gcellGrid) {
      out_ << "GCELLGRID " << (g.isX ? "X " : "Y ") << g.start << " DO " << g.count << " STEP " << g.step << " ;\n";
    }
    if (!d_.gcellGrid.empty()) out_ << '\n';
  }

  void writeVias() {
    if (d_.vias.empty()) return;
    out_ << "VIAS " << static_cast<int64_t>(d_.vias.size()) << " ;\n";
    for (const DefVia& v : d_.vias) {
      out_ << "- " << v.via.name << '\n';
      if (v.generated) {
        const std::string_view rule =
            v.rule.valid() ? std::string_view(tech_.viaRules[*v.rule].name) : std::string_view("?");
        out_ << "  + VIARULE " << rule << '\n';
        out_ << "  + CUTSIZE " << v.cutSizeX << ' ' << v.cutSizeY << '\n';
        out_ << "  + LAYERS " << layer(v.botLayer) << ' ' << layer(v.cutLayer) << ' ' << layer(v.topLayer) << '\n';
        out_ << "  + CUTSPACING " << v.cutSpacingX << ' ' << v.cutSpacingY << '\n';
        out_ << "  + ENCLOSURE " << v.botEncX << ' ' << v.botEncY << ' ' << v.topEncX << ' ' << v.topEncY << '\n';
        out_ << "  + ROWCOL " << v.rows << ' ' << v.cols << '\n';
        if (v.originX != 0 || v.originY != 0) out_ << "  + ORIGIN " << v.originX << ' ' << v.originY << '\n';
        if (v.botOffX != 0 || v.botOffY != 0 || v.topOffX != 0 || v.topOffY != 0) {
          out_ << "  + OFFSET " << v.botOffX << ' ' << v.botOffY << ' ' << v.topOffX << ' ' << v.topOffY << '\n';
        }
        if (!v.pattern.empty()) out_ << "  + PATTERN " << v.pattern << '\n';
      } else {
        for (const ViaShape& s : v.via.shapes) {
          out_ << "  + RECT " << layer(s.layer) << ' ' << Point{s.rect.xlo, s.rect.ylo} << ' '
               << Point{s.rect.xhi, s.rect.yhi} << '\n';
        }
      }
      out_ << " ;\n";
    }
    out_ << "END VIAS\n\n";
  }

  void writeComponents() {
    out_ << "COMPONENTS " << static_cast<int64_t>(d_.components.size()) << " ;\n";
    for (const Component& c : d_.components) {
      out_ << "- " << c.name << ' ' << tech_.macros[*c.macro].name << " + " << statusKeyword(c.status);
      if (c.status != PlaceStatus::Unplaced) out_ << ' ' << c.location << ' ' << orientName(c.orient);
      out_ << " ;\n";
    }
    out_ << "END COMPONENTS\n\n";
  }

  void writePins() {
    out_ << "PINS " << static_cast<int64_t>(d_.ioPins.size()) << " ;\n";
    for (const IoPin& p : d_.ioPins) {
      out_ << "- " << p.name;
      if (!p.netName.empty()) out_ << " + NET " << p.netName;
      if (!p.direction.empty()) out_ << " + DIRECTION " << p.direction;
      if (!p.use.empty()) out_ << " + USE " << p.use;
      for (const IoPinShape& s : p.shapes) {
        out_ << "\n  + LAYER " << layer(s.layer) << ' ' << Point{s.rect.xlo, s.rect.ylo} << ' '
             << Point{s.rect.xhi, s.rect.yhi};
      }
      if (p.status != PlaceStatus::Unplaced) {
        out_ << "\n  + " << statusKeyword(p.status) << ' ' << p.location << ' ' << orientName(p.orient);
      }
      out_ << " ;\n";
    }
    out_ << "END PINS\n\n";
  }

  void writeBlockages() {
    if (d_.blockages.empty()) return;
    out_ << "BLOCKAGES " << static_cast<int64_t>(d_.blockages.size()) << " ;\n";
    for (const Blockage& b : d_.blockages) {
      if (b.placement) {
        out_ << "- PLACEMENT";
      } else {
        out_ << "- LAYER " << layer(b.layer);
      }
      for (const Rect& r : b.rects) out_ << "\n  RECT " << Point{r.xlo, r.ylo} << ' ' << Point{r.xhi, r.yhi};
      for (const auto& poly : b.polygons) {
        out_ << "\n  POLYGON";
        for (const Point& p : poly) out_ << ' ' << p;
      }
      out_ << " ;\n";
    }
    out_ << "END BLOCKAGES\n\n";
  }

  // Starts the next path of a net's wiring: "+ ROUTED " first, then "NEW ".
  void startPath(bool& first) {
    out_ << (first ? "\n  + ROUTED " : "\n    NEW ");
    first = false;
  }

  void writeSpecialNets() {
    if (d_.specialNets.empty()) return;
    out_ << "SPECIALNETS " << static_cast<int64_t>(d_.specialNets.size()) << " ;\n";
    for (const SpecialNet& n : d_.specialNets) {
      out_ << "- " << n.name;
      for (const auto& [comp, pin] : n.pins) out_ << " ( " << comp << ' ' << pin << " )";
      bool first = true;
      for (const SpecialWire& w : n.wires) {
        startPath(first);
        out_ << layer(w.layer) << ' ' << w.width;
        if (!w.shape.empty()) out_ << " + SHAPE " << w.shape;
        out_ << ' ' << w.from << ' ' << w.to;
      }
      for (const SpecialVia& v : n.vias) {
        startPath(first);
        const Via& via = d_.via(tech_, v.via);
        out_ << layer(viaPathLayer(via)) << " 0";
        if (!v.shape.empty()) out_ << " + SHAPE " << v.shape;
        out_ << ' ' << v.at << ' ' << via.name;
      }
      for (const RoutePatch& r : n.rects) {
        out_ << "\n  + RECT " << layer(r.layer) << ' ' << Point{r.rect.xlo, r.rect.ylo} << ' '
             << Point{r.rect.xhi, r.rect.yhi};
      }
      if (!n.use.empty()) out_ << "\n  + USE " << n.use;
      out_ << "\n ;\n";
    }
    out_ << "END SPECIALNETS\n\n";
  }

  void writeEnd(Point p, Dbu ext) {
    out_ << "( " << p.x << ' ' << p.y;
    if (ext >= 0) out_ << ' ' << ext;
    out_ << " )";
  }

  void writeNonDefaultRules() {
    if (d_.ndrs.empty()) return;
    out_ << "NONDEFAULTRULES " << static_cast<int64_t>(d_.ndrs.size()) << " ;\n";
    for (const NonDefaultRule& r : d_.ndrs) {
      out_ << "- " << r.name;
      if (r.hardSpacing) out_ << "\n  + HARDSPACING";
      for (const NdrLayer& l : r.layers) {
        out_ << "\n  + LAYER " << layer(l.layer) << " WIDTH " << l.width;
        if (l.spacing > 0) out_ << " SPACING " << l.spacing;
        if (l.wireExt > 0) out_ << " WIREEXT " << l.wireExt;
      }
      for (const std::string& v : r.vias) out_ << "\n  + VIA " << v;
      for (const std::string& v : r.viaRules) out_ << "\n  + VIARULE " << v;
      out_ << " ;\n";
    }
    out_ << "END NONDEFAULTRULES\n\n";
  }

  void writeNets() {
    out_ << "NETS " << static_cast<int64_t>(d_.nets.size()) << " ;\n";
    for (size_t i = 0; i < d_.nets.size(); ++i) {
      const Net& n = d_.nets[i];
      out_ << "- " << n.name;
      if (i + 1 < d_.netPinStart.size()) {
        int onLine = 0;
        for (int32_t r = d_.netPinStart[i]; r < d_.netPinStart[i + 1]; ++r) {
          if (onLine++ % 8 == 0) out_ << "\n ";
          const PinRef& ref = d_.pinRefs[r];
          if (ref.isIo()) {
            out_ << " ( PIN " << d_.ioPins[ref.pin].name << " )";
          } else {
            const Component& c = d_.components[*ref.comp];
            out_ << " ( " << c.name << ' ' << tech_.macros[*c.macro].pins[ref.pin].name << " )";
          }
        }
      }
      if (!n.use.empty()) out_ << "\n  + USE " << n.use;
      if (n.ndr >= 0) out_ << "\n  + NONDEFAULTRULE " << d_.ndrs[n.ndr].name;
      bool first = true;
      for (const RouteWire& w : n.routing.wires) {
        startPath(first);
        out_ << layer(w.layer) << (taperedWire(tech_, d_, n.ndr, w) ? " TAPER " : " ");
        writeEnd(w.from, w.extFrom);
        out_ << ' ';
        writeEnd(w.to, w.extTo);
      }
      for (const RouteVia& v : n.routing.vias) {
        startPath(first);
        const Via& via = d_.via(tech_, v.via);
        out_ << layer(viaPathLayer(via)) << (n.ndr >= 0 && v.taper ? " TAPER " : " ") << v.at << ' ' << via.name;
      }
      for (const RoutePatch& p : n.routing.patches) {
        startPath(first);
        out_ << layer(p.layer) << (n.ndr >= 0 && p.taper ? " TAPER " : " ") << Point{p.rect.xlo, p.rect.ylo}
             << " RECT ( 0 0 " << p.rect.width() << ' '
             << p.rect.height() << " )";
      }
      out_ << "\n ;\n";
    }
    out_ << "END NETS\n\n";
  }

  const Tech& tech_;
  const Design& d_;
  DefOut out_;
};

}  // namespace

std::string writeDefText(const Tech& tech, const Design& design) { return DefWriter(tech, design).write(); }

void writeDef(const std::string& path, const Tech& tech, const Design& design) {
  const std::string text = writeDefText(tech, design);
  writeFileAtomically(path, text, "DEF");
}

}  // namespace xroute
