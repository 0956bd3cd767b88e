// The LEF parser: one object per file read, filling a Tech that may already
// hold an earlier file (technology LEF, then cell LEFs). Split by block over
// lef_reader.cpp (file header, UNITS, SITE, skipped blocks), lef_layer.cpp,
// lef58.cpp (LEF58_* property strings), lef_via.cpp (VIA, VIARULE) and
// lef_macro.cpp (MACRO, PIN, OBS).
//
// Policies every block follows:
// - Lengths are read in microns and converted with Tech::dbuPerMicron; a
//   length before any UNITS DATABASE MICRONS (in a Tech that has none yet)
//   assumes 1000 per micron (OpenROAD's default), with a warning; a later
//   UNITS in that file that differs is an error. A cell LEF whose UNITS
//   differ from the technology LEF's is read in the technology's units
//   (LEF lengths are microns either way), with a warning.
// - A statement the reader does not store is skipped to its ';' and counted
//   in Tech::skippedStatements under "<BLOCK>.<KEYWORD>" (plus warningCount).
//   A statement that starts with something that is not a keyword (a number,
//   a quoted string, a lone ';') is an error, not a skip.
// - Unknown layer / via / site names, END-name mismatches, duplicate
//   definitions and a file that ends inside a block throw InputError at the
//   line of the offending token (for an early end of file: its last token).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "db/tech.hpp"
#include "io/lexer.hpp"

namespace xroute {

class LefParser {
 public:
  LefParser(Lexer& lex, Tech& tech);
  void parse();

 private:
  // --- tokens (every read goes through these: a clean end-of-file error) ---
  Token next();
  const Token& peek();
  bool peekIs(std::string_view word);  // next token is this unquoted word
  bool accept(std::string_view word);
  void expect(std::string_view word);
  void endStatement();  // expects ';'
  // A length that must be > 0 (positive) or >= 0; `what` names it in the error.
  Dbu positiveDist(const std::string& what);
  Dbu nonNegativeDist(const std::string& what);
  // A name being defined or referenced: not ';', not a number.
  Token name(std::string_view what);
  // The first token of a statement: must look like a keyword.
  Token keyword(std::string_view where);
  Dbu dist();           // microns -> DBU
  Area area();          // microns^2 -> DBU^2
  double number();
  int64_t integer();
  Point point();        // two distances
  Rect rect();          // RECT body: [MASK n] x1 y1 x2 y2 (any two opposite corners, as the LEF reference says)
  // After MASK: the mask number (not kept), warned in the tally unless it is one (`via`: three digits).
  void maskNumber(bool via);
  // POLYGON body: [MASK n] x y x y ... ; (consumes the ';'); at least 3 points.
  std::vector<Point> polygon();
  LayerId layerRef();   // a defined layer name
  std::string restOfStatement();  // words up to ';' joined by ' ' (consumes ';')
  [[noreturn]] void failAt(const Token& t, const std::string& message) const;
  [[noreturn]] void failEof() const;

  // A warning "file:line: message" in Tech::warnings (and warningCount).
  void warn(int line, const std::string& message);
  // Applies the LEF default units (with a warning) when a length comes before any UNITS.
  void defaultUnits(const Token& t);

  // --- skipping and counting ---
  void count(std::string_view block, std::string_view keyword);
  void skipStatement(std::string_view block, const Token& keyword);
  // Records a rule of `layer` that the checker does not judge (Layer::unjudged), once.
  static void noteUnjudged(Layer& layer, std::string rule);
  // Skips tokens until "END <name>" (name empty: until a lone "END").
  void skipBlock(std::string_view block, const Token& opener, std::string_view endName);
  void endBlock(std::string_view name);  // expects END name

  // --- blocks ---
  void parseUnits(const Token& opener);
  void parsePropertyDefinitions(const Token& opener);
  void parseSite(const Token& opener);
  void parseLayer(const Token& opener);
  void parseLayerDirection(Layer& layer);
  void parseLayerPitchOrOffset(Layer& layer, bool pitch);
  void skipCurrentDensity(std::string_view keyword);
  void parseRoutingSpacing(Layer& layer, const Token& kw);
  void parseCutSpacing(Layer& layer, const Token& kw);
  void parseSpacingTable(Layer& layer, const Token& kw);
  void parseLayerProperty(Layer& layer, const Token& kw);
  // LEF58 property strings (lef58.cpp); `valueTok` is the quoted value.
  void parseLef58CornerSpacing(Layer& layer, const Token& valueTok);
  void parseVia(const Token& opener);
  void parseViaRule(const Token& opener);
  void parseNonDefaultRule(const Token& opener);  // lef_ndr.cpp
  void parseNdrLayer(NonDefaultRule& rule, const Token& opener);
  void parseMacro(const Token& opener);
  void parsePin(Macro& macro, const Token& opener);
  // LAYER/RECT/POLYGON/VIA/... statements up to a lone END (PORT and OBS).
  void parseGeometry(std::string_view block, std::vector<MacroShape>& shapes);

  struct OpenBlock {
    std::string_view kind;  // "LAYER", "MACRO", ...
    std::string name;
    int line;
  };
  // Pushes on construction, pops on destruction: names the innermost open
  // block in an end-of-file error.
  class Scope {
   public:
    Scope(LefParser& p, std::string_view kind, std::string_view name, int line) : p_(p) {
      p_.open_.push_back({kind, std::string(name), line});
    }
    ~Scope() { p_.open_.pop_back(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    LefParser& p_;
  };

  // DATABASE MICRONS assumed when a length comes before any UNITS: OpenROAD's database default
  // (the Si2 parser keeps microns and converts nothing; asap7's ifp test LEF has no UNITS).
  static constexpr int kDefaultDbuPerMicron = 1000;

  Lexer& lex_;
  Tech& tech_;
  int defaultUnitsLine_ = 0;  // line where the default units were applied (0: not applied)
  std::vector<OpenBlock> open_;
  StringMap<size_t> skippedIndex_;  // keyword -> index into tech_.skippedStatements
};

// True when `text` is a complete decimal number ("12", "-0.5", "1e3").
bool isNumberText(std::string_view text);

}  // namespace xroute
