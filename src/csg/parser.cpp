// The lexer and a recursive-descent parser for OpenSCAD's grammar (parser.y of
// OpenSCAD 2021.01): statements, module and function definitions, expressions with
// OpenSCAD's precedence (ternary, ||, &&, == !=, < <= > >=, + -, * / %, unary, ^,
// call/index/member), ranges, vectors with list comprehensions, include<> and use<>.
#include "cellforge/csg/source.h"
#include "cellforge/csg/parser.h"

#include <charconv>
#include <cstdlib>
#include <string_view>

namespace cellforge::csg {
namespace {

enum class Tok {
  kEnd,
  kIdent,
  kNumber,
  kString,
  kPath,  // kPath: <...> after include/use
  kModule,
  kFunction,
  kIf,
  kElse,
  kFor,
  kLet,
  kAssert,
  kEcho,
  kEach,
  kTrue,
  kFalse,
  kUndef,
  kInclude,
  kUse,
  kLe,
  kGe,
  kEq,
  kNe,
  kAnd,
  kOr,
  kChar,  // a single punctuation character in `text`
};

struct Token {
  Tok kind = Tok::kEnd;
  std::string text;
  double number = 0;
  SourcePos pos;
};

struct LexError {
  SourcePos pos;
  std::string message;
};

bool ident_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' || c == '$';
}
bool ident_char(char c) { return ident_start(c) || (c >= '0' && c <= '9'); }
bool digit(char c) { return c >= '0' && c <= '9'; }

class Lexer {
 public:
  Lexer(std::string_view text, std::uint32_t file) : t_(text), file_(file) {}

  bool run(std::vector<Token>& out, LexError& err) {
    for (;;) {
      if (!skip_space(err)) return false;
      Token tok;
      tok.pos = here();
      if (i_ >= t_.size()) {
        out.push_back(tok);
        return true;
      }
      const char c = t_[i_];
      // OpenSCAD's lexer takes the longest match, and a name may start with digits
      // ("8bit_font"): a run of name characters longer than the number there is a name.
      std::size_t name_end = i_ + (c == '$' ? 1 : 0);
      while (name_end < t_.size() && ident_char(t_[name_end]) && t_[name_end] != '$') ++name_end;
      const bool digits_first = digit(c) && name_end > number_end(i_);
      if (ident_start(c) || digits_first) {
        std::size_t j = digits_first ? name_end : i_;
        if (!digits_first) {
          while (j < t_.size() && ident_char(t_[j])) ++j;
        }
        tok.text = std::string(t_.substr(i_, j - i_));
        tok.kind = keyword(tok.text);
        advance(j - i_);
        out.push_back(tok);
        if (tok.kind == Tok::kInclude || tok.kind == Tok::kUse) {
          if (!skip_space(err)) return false;
          if (i_ < t_.size() && t_[i_] == '<') {
            Token p;
            p.pos = here();
            const std::size_t close = t_.find('>', i_);
            const std::size_t nl = t_.find('\n', i_);
            if (close == std::string_view::npos || (nl != std::string_view::npos && nl < close)) {
              err = {p.pos, "the path after " + tok.text + " has no closing '>'"};
              return false;
            }
            p.kind = Tok::kPath;
            p.text = std::string(t_.substr(i_ + 1, close - i_ - 1));
            advance(close + 1 - i_);
            out.push_back(p);
          }
        }
        continue;
      }
      if (digit(c) || (c == '.' && i_ + 1 < t_.size() && digit(t_[i_ + 1]))) {
        if (!number(tok, err)) return false;
        out.push_back(tok);
        continue;
      }
      if (c == '"') {
        if (!string(tok, err)) return false;
        out.push_back(tok);
        continue;
      }
      const char n = i_ + 1 < t_.size() ? t_[i_ + 1] : '\0';
      tok.kind = Tok::kChar;
      if (c == '<' && n == '=') tok.kind = Tok::kLe;
      if (c == '>' && n == '=') tok.kind = Tok::kGe;
      if (c == '=' && n == '=') tok.kind = Tok::kEq;
      if (c == '!' && n == '=') tok.kind = Tok::kNe;
      if (c == '&' && n == '&') tok.kind = Tok::kAnd;
      if (c == '|' && n == '|') tok.kind = Tok::kOr;
      if (tok.kind != Tok::kChar) {
        tok.text = std::string(t_.substr(i_, 2));
        advance(2);
        out.push_back(tok);
        continue;
      }
      static constexpr std::string_view kPunct = "+-*/%^!<>=?:;,.()[]{}#";
      if (kPunct.find(c) == std::string_view::npos) {
        const unsigned char u = static_cast<unsigned char>(c);
        err = {tok.pos, u >= 0x20 && u < 0x7F ? std::string("unexpected character '") + c + "'"
                                              : "unexpected byte " + std::to_string(u)};
        return false;
      }
      tok.text = std::string(1, c);
      advance(1);
      out.push_back(tok);
    }
  }

 private:
  SourcePos here() const { return {file_, line_, col_}; }

  void advance(std::size_t n) {
    for (std::size_t k = 0; k < n && i_ < t_.size(); ++k, ++i_) {
      if (t_[i_] == '\n') {
        ++line_;
        col_ = 1;
      } else {
        ++col_;
      }
    }
  }

  bool skip_space(LexError& err) {
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
        advance(1);
      } else if (c == '/' && i_ + 1 < t_.size() && t_[i_ + 1] == '/') {
        while (i_ < t_.size() && t_[i_] != '\n') advance(1);
      } else if (c == '/' && i_ + 1 < t_.size() && t_[i_ + 1] == '*') {
        const SourcePos start = here();
        const std::size_t end = t_.find("*/", i_ + 2);
        if (end == std::string_view::npos) {
          err = {start, "the comment is not closed ('*/' missing)"};
          return false;
        }
        advance(end + 2 - i_);
      } else {
        break;
      }
    }
    return true;
  }

  static Tok keyword(const std::string& s) {
    static const std::pair<std::string_view, Tok> kWords[] = {
        {"module", Tok::kModule},   {"function", Tok::kFunction},
        {"if", Tok::kIf},           {"else", Tok::kElse},
        {"for", Tok::kFor},         {"let", Tok::kLet},
        {"assert", Tok::kAssert},   {"echo", Tok::kEcho},
        {"each", Tok::kEach},       {"true", Tok::kTrue},
        {"false", Tok::kFalse},     {"undef", Tok::kUndef},
        {"include", Tok::kInclude}, {"use", Tok::kUse}};
    for (const auto& [w, k] : kWords) {
      if (s == w) return k;
    }
    return Tok::kIdent;
  }

  // Where a number starting at i ends.
  std::size_t number_end(std::size_t i) const {
    std::size_t j = i;
    while (j < t_.size() && digit(t_[j])) ++j;
    if (j < t_.size() && t_[j] == '.') {
      ++j;
      while (j < t_.size() && digit(t_[j])) ++j;
    }
    if (j < t_.size() && (t_[j] == 'e' || t_[j] == 'E')) {
      std::size_t k = j + 1;
      if (k < t_.size() && (t_[k] == '+' || t_[k] == '-')) ++k;
      if (k < t_.size() && digit(t_[k])) {
        j = k;
        while (j < t_.size() && digit(t_[j])) ++j;
      }
    }
    return j;
  }

  bool number(Token& tok, LexError& err) {
    const std::size_t j = number_end(i_);
    const std::string s(t_.substr(i_, j - i_));
    tok.kind = Tok::kNumber;
    tok.text = s;
    tok.number = std::strtod(s.c_str(), nullptr);
    if (j < t_.size() && ident_start(t_[j])) {
      err = {tok.pos, "a number runs into a name: '" + s + t_[j] + "'"};
      return false;
    }
    advance(j - i_);
    return true;
  }

  bool string(Token& tok, LexError& err) {
    tok.kind = Tok::kString;
    advance(1);
    for (;;) {
      if (i_ >= t_.size()) {
        err = {tok.pos, "the string is not closed ('\"' missing)"};
        return false;
      }
      const char c = t_[i_];
      if (c == '"') {
        advance(1);
        return true;
      }
      if (c != '\\') {
        if (c != '\n') tok.text += c;  // OpenSCAD drops a line break written in a string
        advance(1);
        continue;
      }
      const SourcePos at = here();
      if (i_ + 1 >= t_.size()) {
        err = {at, "the string ends in a backslash"};
        return false;
      }
      const char e = t_[i_ + 1];
      advance(2);
      switch (e) {
        case 'n':
          tok.text += '\n';
          break;
        case 't':
          tok.text += '\t';
          break;
        case 'r':
          tok.text += '\r';
          break;
        case '\\':
          tok.text += '\\';
          break;
        case '"':
          tok.text += '"';
          break;
        case '\'':
          tok.text += '\'';
          break;
        case 'x':
        case 'u':
        case 'U': {
          const std::size_t want = e == 'x' ? 2 : e == 'u' ? 4 : 6;
          std::uint32_t cp = 0;
          std::size_t k = 0;
          for (; k < want && i_ + k < t_.size(); ++k) {
            const char h = t_[i_ + k];
            int v = -1;
            if (digit(h)) v = h - '0';
            if (h >= 'a' && h <= 'f') v = h - 'a' + 10;
            if (h >= 'A' && h <= 'F') v = h - 'A' + 10;
            if (v < 0) break;
            cp = cp * 16 + static_cast<std::uint32_t>(v);
          }
          if (k != want || (e == 'x' && cp > 0x7F) || cp > 0x10FFFF || cp == 0) {
            // OpenSCAD leaves an escape it cannot read as it is written.
            tok.text += '\\';
            tok.text += e;
            break;
          }
          advance(want);
          append_utf8(tok.text, cp);
          break;
        }
        default:
          tok.text += '\\';
          tok.text += e;
      }
    }
  }

  std::string_view t_;
  std::uint32_t file_;
  std::size_t i_ = 0;
  std::uint32_t line_ = 1, col_ = 1;
};

struct ParseError {
  SourcePos pos;
  std::string message;
};

class Parser {
 public:
  Parser(std::vector<Token> tokens, const ParseOptions& options)
      : toks_(std::move(tokens)), options_(options) {}

  File file(std::uint32_t index) {
    File f;
    f.source = index;
    while (!at(Tok::kEnd)) {
      if (at(Tok::kInclude) || at(Tok::kUse)) {
        Include inc;
        inc.use = at(Tok::kUse);
        inc.pos = peek().pos;
        next();
        if (!at(Tok::kPath)) fail(peek().pos, "expected <path> after include or use");
        inc.path = next().text;
        inc.before = f.statements.size();
        f.includes.push_back(inc);
        continue;
      }
      statement(f.statements);
    }
    return f;
  }

 private:
  // ---- tokens
  const Token& peek(std::size_t ahead = 0) const {
    const std::size_t k = std::min(pos_ + ahead, toks_.size() - 1);
    return toks_[k];
  }
  bool at(Tok k) const { return peek().kind == k; }
  bool at_char(char c, std::size_t ahead = 0) const {
    const Token& t = peek(ahead);
    return t.kind == Tok::kChar && t.text[0] == c;
  }
  const Token& next() {
    const Token& t = toks_[pos_];
    if (pos_ + 1 < toks_.size()) ++pos_;
    return t;
  }
  [[noreturn]] void fail(SourcePos p, std::string message) {
    throw ParseError{p, std::move(message)};
  }
  std::string describe(const Token& t) const {
    switch (t.kind) {
      case Tok::kEnd:
        return "the end of the file";
      case Tok::kNumber:
        return "number " + t.text;
      case Tok::kString:
        return "a string";
      case Tok::kIdent:
        return "'" + t.text + "'";
      default:
        return "'" + t.text + "'";
    }
  }
  void expect_char(char c, const char* context) {
    if (!at_char(c)) {
      fail(peek().pos,
           std::string("expected '") + c + "' " + context + ", found " + describe(peek()));
    }
    next();
  }
  std::string expect_ident(const char* what) {
    if (!at(Tok::kIdent))
      fail(peek().pos, std::string("expected ") + what + ", found " + describe(peek()));
    return next().text;
  }

  struct Depth {
    Depth(Parser& p, SourcePos pos) : p_(p) {
      if (++p_.depth_ > p_.options_.max_depth) {
        p_.fail(pos, "nested too deeply (more than " + std::to_string(p_.options_.max_depth) +
                         " levels)");
      }
    }
    ~Depth() { --p_.depth_; }
    Parser& p_;
  };

  // ---- statements
  void statement(std::vector<StmtPtr>& out) {
    Depth d(*this, peek().pos);
    const Token& t = peek();
    if (at_char(';')) {
      next();
      return;
    }
    if (at_char('{')) {
      auto s = std::make_unique<Stmt>();
      s->kind = StmtKind::kBlock;
      s->pos = t.pos;
      next();
      while (!at_char('}')) {
        if (at(Tok::kEnd)) fail(s->pos, "the block is not closed ('}' missing)");
        statement(s->children);
      }
      next();
      out.push_back(std::move(s));
      return;
    }
    if (at(Tok::kModule)) {
      auto s = std::make_unique<Stmt>();
      s->kind = StmtKind::kModule;
      s->pos = next().pos;
      s->name = expect_ident("a module name");
      expect_char('(', "after the module name");
      s->params = bindings(')', "parameters");
      statement(s->children);
      out.push_back(std::move(s));
      return;
    }
    if (at(Tok::kFunction)) {
      auto s = std::make_unique<Stmt>();
      s->kind = StmtKind::kFunction;
      s->pos = next().pos;
      s->name = expect_ident("a function name");
      expect_char('(', "after the function name");
      s->params = bindings(')', "parameters");
      expect_char('=', "after the function's parameters");
      s->value = expr();
      expect_char(';', "after the function definition");
      out.push_back(std::move(s));
      return;
    }
    if (at(Tok::kIdent) && at_char('=', 1)) {
      out.push_back(assignment());
      return;
    }
    out.push_back(instantiation());
  }

  StmtPtr assignment() {
    auto s = std::make_unique<Stmt>();
    s->kind = StmtKind::kAssign;
    s->pos = peek().pos;
    s->name = next().text;
    next();  // '='
    s->value = expr();
    expect_char(';', "after the assignment");
    return s;
  }

  // child_statement: ';' | '{' (child_statement | assignment)* '}' | module_instantiation
  void child_statement(std::vector<StmtPtr>& out) {
    Depth d(*this, peek().pos);
    if (at_char(';')) {
      next();
      return;
    }
    if (at_char('{')) {
      const SourcePos open = next().pos;
      while (!at_char('}')) {
        if (at(Tok::kEnd)) fail(open, "the block is not closed ('}' missing)");
        if (at(Tok::kIdent) && at_char('=', 1)) {
          out.push_back(assignment());
        } else if (at(Tok::kModule) || at(Tok::kFunction)) {
          fail(peek().pos, "a module or function cannot be defined among a module's children");
        } else {
          child_statement(out);
        }
      }
      next();
      return;
    }
    out.push_back(instantiation());
  }

  StmtPtr instantiation() {
    Depth d(*this, peek().pos);
    const Token& t = peek();
    if (at_char('!') || at_char('#') || at_char('%') || at_char('*')) {
      const char m = next().text[0];
      StmtPtr s = instantiation();
      if (s->modifier == 0 || m == '*' || m == '!') s->modifier = m;
      return s;
    }
    auto s = std::make_unique<Stmt>();
    s->pos = t.pos;
    if (at(Tok::kIf)) {
      next();
      s->kind = StmtKind::kIf;
      expect_char('(', "after 'if'");
      s->value = expr();
      expect_char(')', "after the condition");
      child_statement(s->children);
      if (at(Tok::kElse)) {
        next();
        child_statement(s->else_children);
      }
      return s;
    }
    s->kind = StmtKind::kInstance;
    if (at(Tok::kIdent) || at(Tok::kFor) || at(Tok::kLet) || at(Tok::kAssert) || at(Tok::kEcho) ||
        at(Tok::kEach)) {
      s->name = next().text;
    } else {
      fail(t.pos, "expected a statement, found " + describe(t));
    }
    expect_char('(', ("after the module name '" + s->name + "'").c_str());
    s->args = bindings(')', "arguments");
    child_statement(s->children);
    return s;
  }

  // A comma-separated list of `expr`, `name = expr` or bare `name` up to `close`
  // (consumed); empty elements between commas are allowed, as OpenSCAD does.
  std::vector<Binding> bindings(char close, const char* what) {
    std::vector<Binding> out;
    for (;;) {
      while (at_char(',')) next();
      if (at_char(close)) {
        next();
        return out;
      }
      if (at(Tok::kEnd)) fail(peek().pos, std::string("the ") + what + " are not closed");
      Binding b;
      b.pos = peek().pos;
      if (at(Tok::kIdent) && at_char('=', 1)) {
        b.name = next().text;
        next();
        b.value = expr();
      } else {
        b.value = expr();
      }
      out.push_back(std::move(b));
      if (!at_char(',') && !at_char(close)) {
        fail(peek().pos, std::string("expected ',' or '") + close + "' in the " + what +
                             ", found " + describe(peek()));
      }
    }
  }

  // ---- expressions
  ExprPtr make(ExprKind k, SourcePos p) {
    auto e = std::make_unique<Expr>();
    e->kind = k;
    e->pos = p;
    return e;
  }

  ExprPtr expr() {
    Depth d(*this, peek().pos);
    const Token& t = peek();
    if (at(Tok::kFunction)) {
      next();
      auto e = make(ExprKind::kFunction, t.pos);
      expect_char('(', "after 'function'");
      e->params = bindings(')', "parameters");
      e->items.push_back(expr());
      return e;
    }
    if (at(Tok::kLet) || at(Tok::kAssert) || at(Tok::kEcho)) {
      const Tok k = next().kind;
      auto e = make(k == Tok::kLet      ? ExprKind::kLet
                    : k == Tok::kAssert ? ExprKind::kAssert
                                        : ExprKind::kEcho,
                    t.pos);
      expect_char('(', "after let, assert or echo");
      e->args = bindings(')', "arguments");
      if (k == Tok::kLet || starts_expr()) e->items.push_back(expr());
      return e;
    }
    ExprPtr c = binary(0);
    if (at_char('?')) {
      auto e = make(ExprKind::kTernary, next().pos);
      e->items.push_back(std::move(c));
      e->items.push_back(expr());
      expect_char(':', "in the ternary (a ? b : c)");
      e->items.push_back(expr());
      return e;
    }
    return c;
  }

  // Whether the next token can begin an expression (for assert/echo without a body).
  bool starts_expr() const {
    const Token& t = peek();
    switch (t.kind) {
      case Tok::kIdent:
      case Tok::kNumber:
      case Tok::kString:
      case Tok::kTrue:
      case Tok::kFalse:
      case Tok::kUndef:
      case Tok::kFunction:
      case Tok::kLet:
      case Tok::kAssert:
      case Tok::kEcho:
        return true;
      case Tok::kChar:
        return t.text[0] == '(' || t.text[0] == '[' || t.text[0] == '-' || t.text[0] == '+' ||
               t.text[0] == '!';
      default:
        return false;
    }
  }

  // Binary operators by level: 0 ||, 1 &&, 2 == !=, 3 < <= > >=, 4 + -, 5 * / %.
  int level_of(const Token& t) const {
    switch (t.kind) {
      case Tok::kOr:
        return 0;
      case Tok::kAnd:
        return 1;
      case Tok::kEq:
      case Tok::kNe:
        return 2;
      case Tok::kLe:
      case Tok::kGe:
        return 3;
      case Tok::kChar:
        switch (t.text[0]) {
          case '<':
          case '>':
            return 3;
          case '+':
          case '-':
            return 4;
          case '*':
          case '/':
          case '%':
            return 5;
          default:
            return -1;
        }
      default:
        return -1;
    }
  }

  ExprPtr binary(int level) {
    if (level > 5) return unary();
    ExprPtr left = binary(level + 1);
    while (level_of(peek()) == level) {
      const Token& op = next();
      auto e = make(ExprKind::kBinary, op.pos);
      e->text = op.text;
      e->items.push_back(std::move(left));
      e->items.push_back(binary(level + 1));
      left = std::move(e);
    }
    return left;
  }

  ExprPtr unary() {
    Depth d(*this, peek().pos);
    if (at_char('-') || at_char('+') || at_char('!')) {
      const Token& op = next();
      auto e = make(ExprKind::kUnary, op.pos);
      e->text = op.text;
      e->items.push_back(unary());
      return e;
    }
    ExprPtr base = postfix();
    if (at_char('^')) {
      auto e = make(ExprKind::kBinary, next().pos);
      e->text = "^";
      e->items.push_back(std::move(base));
      e->items.push_back(unary());
      return e;
    }
    return base;
  }

  ExprPtr postfix() {
    ExprPtr e = primary();
    for (;;) {
      if (at_char('(')) {
        auto c = make(ExprKind::kCall, next().pos);
        c->items.push_back(std::move(e));
        c->args = bindings(')', "arguments");
        e = std::move(c);
      } else if (at_char('[')) {
        auto c = make(ExprKind::kIndex, next().pos);
        c->items.push_back(std::move(e));
        c->items.push_back(expr());
        expect_char(']', "after the index");
        e = std::move(c);
      } else if (at_char('.')) {
        auto c = make(ExprKind::kMember, next().pos);
        c->items.push_back(std::move(e));
        c->text = expect_ident("a member name after '.'");
        e = std::move(c);
      } else {
        return e;
      }
    }
  }

  ExprPtr primary() {
    Depth d(*this, peek().pos);
    const Token& t = peek();
    switch (t.kind) {
      case Tok::kNumber: {
        auto e = make(ExprKind::kNumber, t.pos);
        e->number = next().number;
        return e;
      }
      case Tok::kString: {
        auto e = make(ExprKind::kString, t.pos);
        e->text = next().text;
        return e;
      }
      case Tok::kTrue:
      case Tok::kFalse: {
        auto e = make(ExprKind::kBool, t.pos);
        e->number = next().kind == Tok::kTrue ? 1 : 0;
        return e;
      }
      case Tok::kUndef:
        next();
        return make(ExprKind::kUndef, t.pos);
      case Tok::kIdent: {
        auto e = make(ExprKind::kIdent, t.pos);
        e->text = next().text;
        return e;
      }
      case Tok::kChar:
        if (t.text[0] == '(') {
          next();
          ExprPtr e = expr();
          expect_char(')', "to close '('");
          return e;
        }
        if (t.text[0] == '[') return vector();
        break;
      default:
        break;
    }
    fail(t.pos, "expected an expression, found " + describe(t));
  }

  ExprPtr vector() {
    const SourcePos open = next().pos;  // '['
    if (at_char(']')) {
      next();
      return make(ExprKind::kVector, open);
    }
    // A range [a : b] or [a : s : b]: a plain expression followed by ':'.
    if (!at(Tok::kFor) && !at(Tok::kEach) && !at(Tok::kIf) && !at(Tok::kLet)) {
      ExprPtr first = expr();
      if (at_char(':')) {
        auto r = make(ExprKind::kRange, open);
        r->items.push_back(std::move(first));
        next();
        r->items.push_back(expr());
        if (at_char(':')) {
          next();
          r->items.push_back(expr());
        }
        expect_char(']', "to close the range");
        return r;
      }
      auto v = make(ExprKind::kVector, open);
      v->items.push_back(std::move(first));
      return vector_rest(std::move(v));
    }
    auto v = make(ExprKind::kVector, open);
    v->items.push_back(element());
    return vector_rest(std::move(v));
  }

  ExprPtr vector_rest(ExprPtr v) {
    for (;;) {
      if (at_char(']')) {
        next();
        return v;
      }
      if (!at_char(','))
        fail(peek().pos, "expected ',' or ']' in the vector, found " + describe(peek()));
      while (at_char(',')) next();
      if (at_char(']')) {
        next();
        return v;
      }
      v->items.push_back(element());
    }
  }

  // A vector element: an expression or a list-comprehension element.
  ExprPtr element() {
    Depth d(*this, peek().pos);
    const Token& t = peek();
    if (at(Tok::kFor)) {
      next();
      expect_char('(', "after 'for'");
      std::vector<Binding> init;
      for (;;) {
        while (at_char(',')) next();
        if (at_char(')') || at_char(';')) break;
        Binding b;
        b.pos = peek().pos;
        b.name = expect_ident("a loop variable");
        expect_char('=', "after the loop variable");
        b.value = expr();
        init.push_back(std::move(b));
        if (!at_char(',') && !at_char(')') && !at_char(';'))
          fail(peek().pos, "expected ',' or ')' in for(), found " + describe(peek()));
      }
      if (at_char(';')) {
        next();
        auto e = make(ExprKind::kLcForC, t.pos);
        e->args = std::move(init);
        e->items.push_back(expr());
        expect_char(';', "after the condition of for(init; condition; update)");
        e->params = bindings(')', "updates");
        for (const Binding& b : e->params) {
          if (b.name.empty()) fail(b.pos, "an update of for(;;) must be name = value");
        }
        e->items.push_back(element());
        return e;
      }
      next();  // ')'
      auto e = make(ExprKind::kLcFor, t.pos);
      e->args = std::move(init);
      e->items.push_back(element());
      return e;
    }
    if (at(Tok::kEach)) {
      next();
      auto e = make(ExprKind::kLcEach, t.pos);
      e->items.push_back(element());
      return e;
    }
    if (at(Tok::kIf)) {
      next();
      auto e = make(ExprKind::kLcIf, t.pos);
      expect_char('(', "after 'if'");
      e->items.push_back(expr());
      expect_char(')', "after the condition");
      e->items.push_back(element());
      if (at(Tok::kElse)) {
        next();
        e->items.push_back(element());
      }
      return e;
    }
    if (at(Tok::kLet)) {
      next();
      auto e = make(ExprKind::kLcLet, t.pos);
      expect_char('(', "after 'let'");
      e->args = bindings(')', "arguments");
      e->items.push_back(element());
      return e;
    }
    if (at_char('(') && (peek(1).kind == Tok::kFor || peek(1).kind == Tok::kEach ||
                         peek(1).kind == Tok::kIf || peek(1).kind == Tok::kLet)) {
      // A parenthesised comprehension element, as parser.y allows.
      std::size_t save = pos_;
      next();
      if (peek().kind == Tok::kLet) {
        // (let(...) expr) is an ordinary expression too; let the expression parser have it.
        pos_ = save;
        return expr();
      }
      ExprPtr e = element();
      expect_char(')', "to close '('");
      return e;
    }
    return expr();
  }

 private:
  std::vector<Token> toks_;
  const ParseOptions& options_;
  std::size_t pos_ = 0;
  int depth_ = 0;
};

// Parameters given as bare names parse as positional arguments; make them names.
void normalise_params(std::vector<Binding>& params) {
  for (Binding& b : params) {
    if (b.name.empty() && b.value && b.value->kind == ExprKind::kIdent) {
      b.name = b.value->text;
      b.value.reset();
    }
  }
}

void normalise(std::vector<StmtPtr>& stmts);

void normalise_expr(Expr& e) {
  if (e.kind == ExprKind::kFunction) normalise_params(e.params);
  for (ExprPtr& c : e.items) {
    if (c) normalise_expr(*c);
  }
  for (Binding& b : e.args) {
    if (b.value) normalise_expr(*b.value);
  }
  for (Binding& b : e.params) {
    if (b.value) normalise_expr(*b.value);
  }
}

void normalise(std::vector<StmtPtr>& stmts) {
  for (StmtPtr& s : stmts) {
    if (s->kind == StmtKind::kModule || s->kind == StmtKind::kFunction) normalise_params(s->params);
    if (s->value) normalise_expr(*s->value);
    for (Binding& b : s->args) {
      if (b.value) normalise_expr(*b.value);
    }
    for (Binding& b : s->params) {
      if (b.value) normalise_expr(*b.value);
    }
    normalise(s->children);
    normalise(s->else_children);
  }
}

// A definition parameter must end up a name (a bare name or name = default).
const Binding* bad_param(const std::vector<Binding>& params) {
  for (const Binding& b : params) {
    if (b.name.empty()) return &b;
  }
  return nullptr;
}

const Binding* bad_param_in(const Expr& e) {
  if (e.kind == ExprKind::kFunction) {
    if (const Binding* b = bad_param(e.params)) return b;
  }
  for (const ExprPtr& c : e.items) {
    if (c) {
      if (const Binding* b = bad_param_in(*c)) return b;
    }
  }
  for (const Binding& a : e.args) {
    if (a.value) {
      if (const Binding* b = bad_param_in(*a.value)) return b;
    }
  }
  for (const Binding& a : e.params) {
    if (a.value) {
      if (const Binding* b = bad_param_in(*a.value)) return b;
    }
  }
  return nullptr;
}

const Binding* bad_param_in(const std::vector<StmtPtr>& stmts) {
  for (const StmtPtr& s : stmts) {
    if (s->kind == StmtKind::kModule || s->kind == StmtKind::kFunction) {
      if (const Binding* b = bad_param(s->params)) return b;
    }
    if (s->value) {
      if (const Binding* b = bad_param_in(*s->value)) return b;
    }
    for (const Binding& a : s->args) {
      if (a.value) {
        if (const Binding* b = bad_param_in(*a.value)) return b;
      }
    }
    for (const Binding& a : s->params) {
      if (a.value) {
        if (const Binding* b = bad_param_in(*a.value)) return b;
      }
    }
    if (const Binding* b = bad_param_in(s->children)) return b;
    if (const Binding* b = bad_param_in(s->else_children)) return b;
  }
  return nullptr;
}

}  // namespace

Result<File> parse(const Sources& sources, std::uint32_t index, const ParseOptions& options) {
  const SourceFile& src = sources.file(index);
  std::vector<Token> tokens;
  LexError lex;
  if (!Lexer(src.text, index).run(tokens, lex)) {
    return Error{ErrorCode::kParse, sources.format(lex.pos, lex.message)};
  }
  Parser p(std::move(tokens), options);
  try {
    File f = p.file(index);
    normalise(f.statements);
    if (const Binding* b = bad_param_in(f.statements)) {
      return Error{ErrorCode::kParse,
                   sources.format(b->pos, "a parameter must be a name or name = default")};
    }
    return f;
  } catch (const ParseError& e) {
    return Error{ErrorCode::kParse, sources.format(e.pos, e.message)};
  }
}

}  // namespace cellforge::csg
