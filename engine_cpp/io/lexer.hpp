// Tokenizer shared by the LEF, DEF and guide readers. Tokens are separated by
// white space; "#" starts a comment to the end of the line; double-quoted
// strings may hold spaces and span lines; ';'s glued to the end of a word are
// split off as tokens of their own ("x;;" is "x" ";" ";"). Tokens are views into the file text held by the
// lexer, so they live as long as the lexer. A gzip-compressed file (magic bytes 1f 8b) is
// decompressed when read. LEF and DEF keywords are case-insensitive ("Via", "layer", "by"), names
// are not: accept() and expect() match a keyword in any case, and a parser that takes a token in a
// keyword position calls upcase() on it before comparing. A keyword read that is not written in
// upper case (the specification's spelling) is noted in the lexer's WarningTally.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "geom/geom.hpp"
#include "io/input_error.hpp"

namespace xroute {

struct Token {
  std::string_view text;
  int line = 0;         // 1-based line where the token starts
  bool quoted = false;  // was a "string" (text excludes the quotes)
};

// Odd but readable things of one kind, added up over a file: the first one's line and message and
// how many there were (a file that repeats an oddity a million times gets one warning).
class WarningTally {
 public:
  struct Entry {
    std::string kind;
    int line = 0;         // of the first one
    std::string message;  // of the first one
    int64_t count = 0;
  };
  void add(std::string_view kind, int line, std::string message);
  const std::vector<Entry>& entries() const { return entries_; }
  // The warning of `e`: its first message, and how many there were when more than one.
  static std::string text(const Entry& e);

 private:
  std::vector<Entry> entries_;
};

class Lexer {
 public:
  Lexer(std::string path, std::string text);
  // Reads the whole file; throws InputError when it cannot be read.
  static Lexer fromFile(const std::string& path);

  bool atEnd();
  const Token& peek();
  Token next();                        // throws at end of file
  bool accept(std::string_view word);  // consume the next token if it is `word` (any case)
  void expect(std::string_view word);  // throws unless the next token is `word` (any case)
  // Rewrites a token of this lexer's text in upper case, in place (for a keyword position); a
  // token that was not in upper case is noted (noteKeyword).
  void upcase(const Token& t);
  // Notes `t`, read as a keyword, in tally() when it is not written in upper case.
  void noteKeyword(const Token& t);
  WarningTally& tally() { return tally_; }
  std::string_view word();             // any token (the name of something)
  std::string word(std::string_view what);  // a token, naming `what` in the error
  int64_t integer();                   // throws unless an integer
  double number();                     // throws unless a number
  // A length in microns converted to DBU (rounded to nearest); throws if it
  // does not fit a Dbu.
  Dbu microns(int dbuPerMicron);
  // A DEF integer coordinate that must fit a Dbu, rescaled by setScale().
  Dbu dbu();
  // DEF coordinates read by dbu() are multiplied by `mul` and divided by `div` from now on (DEF
  // units to the LEF's); a coordinate that `div` does not divide is an error.
  void setScale(int mul, int div) {
    scaleMul_ = mul;
    scaleDiv_ = div;
  }
  int scaleMul() const { return scaleMul_; }
  int scaleDiv() const { return scaleDiv_; }
  // Skips tokens up to and including the next ';'. Returns the number skipped.
  int skipStatement();

  [[noreturn]] void fail(int line, const std::string& message) const;
  [[noreturn]] void failAt(const Token& t, const std::string& message) const;
  const std::string& path() const { return path_; }
  int line() const { return lastLine_; }  // line of the last token taken

 private:
  void scan();  // fills lookahead_ if empty

  std::string path_;
  std::string text_;
  size_t pos_ = 0;
  int curLine_ = 1;
  int lastLine_ = 1;
  bool hasLookahead_ = false;
  int pendingSemicolons_ = 0;  // ';' split off the end of the last word, still to hand out
  int pendingSemicolonLine_ = 0;
  Token lookahead_;
  bool eof_ = false;
  int scaleMul_ = 1;  // dbu(): v * scaleMul_ / scaleDiv_
  int scaleDiv_ = 1;
  WarningTally tally_;
  const char* lastNoted_ = nullptr;  // the token noteKeyword() saw last (a peeked token is matched twice)
};

// True when `text` is the keyword `word` (upper case) written in any case.
bool isKeyword(std::string_view text, std::string_view word);

// "|v| <= 268435455 DBU": the engine's range (kMaxDbu), for error messages.
std::string dbuRangeText();

// Quotes a token for an error message, shortened if long.
std::string quoteToken(std::string_view text);

}  // namespace xroute
