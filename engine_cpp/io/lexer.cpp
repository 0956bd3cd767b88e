#include "io/lexer.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/gzip_text.hpp"

namespace xroute {

namespace {
bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// Offset of the first byte of `s` that is not part of valid UTF-8 (s.size() if none).
// Names end up as Python str objects: a token that is not UTF-8 is an input error.
size_t invalidUtf8At(std::string_view s) {
  size_t i = 0;
  const size_t n = s.size();
  while (i < n) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    size_t len = 0;
    uint32_t cp = 0;
    if (c >= 0xC2 && c <= 0xDF) {
      len = 2;
      cp = c & 0x1F;
    } else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
      cp = c & 0x0F;
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
      cp = c & 0x07;
    } else {
      return i;
    }
    if (i + len > n) return i;
    for (size_t k = 1; k < len; ++k) {
      const unsigned char cc = static_cast<unsigned char>(s[i + k]);
      if ((cc & 0xC0) != 0x80) return i;
      cp = (cp << 6) | (cc & 0x3F);
    }
    if ((len == 3 && (cp < 0x800 || (cp >= 0xD800 && cp <= 0xDFFF))) || (len == 4 && (cp < 0x10000 || cp > 0x10FFFF))) {
      return i;
    }
    i += len;
  }
  return n;
}

void checkUtf8(const Lexer& lex, const Token& t) {
  for (unsigned char c : t.text) {
    if (c >= 0x80 || c == 0) {
      const size_t at = invalidUtf8At(t.text);
      bool nul = false;
      for (unsigned char d : t.text) nul = nul || d == 0;
      if (at < t.text.size()) lex.failAt(t, "invalid UTF-8 in " + quoteToken(t.text));
      if (nul) lex.failAt(t, "NUL byte in " + quoteToken(t.text));
      return;
    }
  }
}
}  // namespace

bool isKeyword(std::string_view text, std::string_view word) {
  if (text.size() != word.size()) return false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const char u = c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
    if (u != word[i]) return false;
  }
  return true;
}

std::string quoteToken(std::string_view text) {
  std::string s(text.substr(0, 40));
  for (char& c : s) {
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  }
  if (text.size() > 40) s += "...";
  return "'" + s + "'";
}

Lexer::Lexer(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}

Lexer Lexer::fromFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open file");
  std::string text;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path, 0, "cannot read file");
  text.resize(static_cast<size_t>(size));
  in.seekg(0, std::ios::beg);
  if (size > 0 && !in.read(text.data(), size)) throw InputError(path, 0, "cannot read file");
  if (isGzip(text)) text = gunzip(path, text);
  return Lexer(path, std::move(text));
}

void Lexer::scan() {
  if (hasLookahead_ || eof_) return;
  if (pendingSemicolons_ > 0) {
    --pendingSemicolons_;
    lookahead_ = Token{std::string_view(";"), pendingSemicolonLine_, false};
    hasLookahead_ = true;
    return;
  }
  const size_t n = text_.size();
  while (pos_ < n) {
    const char c = text_[pos_];
    if (c == '\n') {
      ++curLine_;
      ++pos_;
    } else if (isSpace(c)) {
      ++pos_;
    } else if (c == '#') {
      while (pos_ < n && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
  if (pos_ >= n) {
    eof_ = true;
    return;
  }
  const int startLine = curLine_;
  if (text_[pos_] == '"') {
    const size_t start = ++pos_;
    while (pos_ < n && text_[pos_] != '"') {
      if (text_[pos_] == '\\' && pos_ + 1 < n) ++pos_;
      if (text_[pos_] == '\n') ++curLine_;
      ++pos_;
    }
    if (pos_ >= n) fail(startLine, "unterminated string");
    lookahead_ = Token{std::string_view(text_).substr(start, pos_ - start), startLine, true};
    ++pos_;  // closing quote
    hasLookahead_ = true;
    checkUtf8(*this, lookahead_);
    return;
  }
  const size_t start = pos_;
  while (pos_ < n && !isSpace(text_[pos_])) ++pos_;
  std::string_view tok = std::string_view(text_).substr(start, pos_ - start);
  // Every ';' at the end of a word is a token of its own (a name never ends in ';', so what
  // the DEF writer writes reads back the same).
  while (tok.size() > 1 && tok.back() == ';') {
    tok.remove_suffix(1);
    ++pendingSemicolons_;
    pendingSemicolonLine_ = startLine;
  }
  lookahead_ = Token{tok, startLine, false};
  hasLookahead_ = true;
  checkUtf8(*this, lookahead_);
}

bool Lexer::atEnd() {
  scan();
  return !hasLookahead_;
}

const Token& Lexer::peek() {
  scan();
  if (!hasLookahead_) fail(curLine_, "unexpected end of file");
  return lookahead_;
}

Token Lexer::next() {
  scan();
  if (!hasLookahead_) fail(curLine_, "unexpected end of file");
  hasLookahead_ = false;
  lastLine_ = lookahead_.line;
  return lookahead_;
}

bool Lexer::accept(std::string_view w) {
  scan();
  if (!hasLookahead_ || lookahead_.quoted || !isKeyword(lookahead_.text, w)) return false;
  noteKeyword(next());
  return true;
}

void Lexer::expect(std::string_view w) {
  scan();
  if (!hasLookahead_) fail(curLine_, "unexpected end of file, expected '" + std::string(w) + "'");
  if (lookahead_.quoted || !isKeyword(lookahead_.text, w)) {
    failAt(lookahead_, "expected '" + std::string(w) + "', found " + quoteToken(lookahead_.text));
  }
  noteKeyword(next());
}

void WarningTally::add(std::string_view kind, int line, std::string message) {
  for (Entry& e : entries_) {
    if (e.kind == kind) {
      ++e.count;
      return;
    }
  }
  entries_.push_back({std::string(kind), line, std::move(message), 1});
}

std::string WarningTally::text(const Entry& e) {
  if (e.count < 2) return e.message;
  return e.message + " (the first of " + std::to_string(e.count) + " in the file)";
}

void Lexer::noteKeyword(const Token& t) {
  if (t.quoted || t.text.data() == lastNoted_) return;
  bool lower = false;
  for (char c : t.text) lower = lower || (c >= 'a' && c <= 'z');
  if (!lower) return;
  lastNoted_ = t.text.data();
  tally_.add("keyword case", t.line,
             "keyword " + quoteToken(t.text) + " not in upper case (LEF and DEF keywords are; read all the same)");
}

void Lexer::upcase(const Token& t) {
  const char* base = text_.data();
  const char* p = t.text.data();
  if (t.quoted || p < base || p + t.text.size() > base + text_.size()) return;  // a split-off ';'
  noteKeyword(t);
  for (size_t i = static_cast<size_t>(p - base), e = i + t.text.size(); i < e; ++i) {
    if (text_[i] >= 'a' && text_[i] <= 'z') text_[i] = static_cast<char>(text_[i] - 'a' + 'A');
  }
}

std::string_view Lexer::word() { return next().text; }

std::string Lexer::word(std::string_view what) {
  scan();
  if (!hasLookahead_) fail(curLine_, "unexpected end of file, expected " + std::string(what));
  const Token t = next();
  if (!t.quoted && t.text == ";") failAt(t, "expected " + std::string(what) + ", found ';'");
  return std::string(t.text);
}

int64_t Lexer::integer() {
  const Token t = next();
  int64_t v = 0;
  const char* b = t.text.data();
  const char* e = b + t.text.size();
  if (b != e && *b == '+') ++b;
  auto [p, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || p != e || b == e) failAt(t, "expected an integer, found " + quoteToken(t.text));
  return v;
}

double Lexer::number() {
  const Token t = next();
  double v = 0;
  const char* b = t.text.data();
  const char* e = b + t.text.size();
  if (b != e && *b == '+') ++b;
  auto [p, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || p != e || b == e || !std::isfinite(v)) {
    failAt(t, "expected a number, found " + quoteToken(t.text));
  }
  return v;
}

std::string dbuRangeText() { return "|v| <= " + std::to_string(kMaxDbu) + " DBU"; }

Dbu Lexer::microns(int dbuPerMicron) {
  const Token copy = peek();
  const double v = number() * dbuPerMicron;
  if (!(std::fabs(v) < 2.0e9)) failAt(copy, "length out of range: " + quoteToken(copy.text));
  const int64_t d = std::llround(v);
  if (!withinDbuRange(d)) {
    failAt(copy, "length " + quoteToken(copy.text) + " (" + std::to_string(d) + " DBU) is beyond the engine's range, " +
                     dbuRangeText());
  }
  return static_cast<Dbu>(d);
}

Dbu Lexer::dbu() {
  const Token copy = peek();
  int64_t v = integer();
  if (scaleDiv_ != 1 && v % scaleDiv_ != 0) {
    failAt(copy, "coordinate " + quoteToken(copy.text) + " is not a multiple of " + std::to_string(scaleDiv_) +
                     ": it has no exact value in the LEF's database units");
  }
  // Bounded before rescaling, so that the product cannot overflow either.
  const bool inRange = withinDbuRange(v) && withinDbuRange(v / scaleDiv_ * scaleMul_);
  if (!inRange) {
    failAt(copy, "coordinate " + quoteToken(copy.text) + " is beyond the engine's range, " + dbuRangeText());
  }
  return static_cast<Dbu>(v / scaleDiv_ * scaleMul_);
}

int Lexer::skipStatement() {
  int count = 0;
  while (true) {
    const Token t = next();
    ++count;
    if (!t.quoted && t.text == ";") return count;
  }
}

void Lexer::fail(int line, const std::string& message) const { throw InputError(path_, line, message); }

void Lexer::failAt(const Token& t, const std::string& message) const { throw InputError(path_, t.line, message); }

}  // namespace xroute
