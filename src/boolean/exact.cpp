// Exact chains (exact.h): the exact form of a result, its splicing into the next
// expression, and its text form.
#include "cellforge/boolean/exact.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <unordered_map>

#include "cellforge/io/mesh_io.h"

namespace cellforge::boolean {

Operand Operand::of(const Model& m) { return {std::make_shared<const Model>(m), nullptr}; }

Operand Operand::of(const BooleanResult& r) {
  if (r.exact) return {nullptr, r.exact};
  return of(r.model);
}

Operand Operand::of(std::shared_ptr<const ExactForm> form) { return {nullptr, std::move(form)}; }

namespace {

// e with every operand i renamed map[i].
Expr renamed(const Expr& e, const std::vector<int>& map) {
  if (e.kind == Expr::Kind::kOperand) return Expr::of(map[static_cast<std::size_t>(e.operand)]);
  Expr out{e.kind, 0, {}};
  for (const Expr& c : e.children) out.children.push_back(renamed(c, map));
  return out;
}

// e with operand i replaced by parts[i].
Expr substituted(const Expr& e, const std::vector<Expr>& parts) {
  if (e.kind == Expr::Kind::kOperand) return parts[static_cast<std::size_t>(e.operand)];
  Expr out{e.kind, 0, {}};
  for (const Expr& c : e.children) out.children.push_back(substituted(c, parts));
  return out;
}

const char* op_name(Expr::Kind k) {
  switch (k) {
    case Expr::Kind::kUnion:
      return "union";
    case Expr::Kind::kIntersection:
      return "intersection";
    case Expr::Kind::kDifference:
      return "difference";
    case Expr::Kind::kOperand:
      break;
  }
  return "";
}

void write_expr(const Expr& e, std::string& out) {
  if (e.kind == Expr::Kind::kOperand) {
    out += std::to_string(e.operand);
    return;
  }
  out += '(';
  out += op_name(e.kind);
  for (const Expr& c : e.children) {
    out += ' ';
    write_expr(c, out);
  }
  out += ')';
}

int depth_of(const Expr& e) {
  int d = 0;
  for (const Expr& c : e.children) d = std::max(d, depth_of(c));
  return e.kind == Expr::Kind::kOperand ? 0 : d + 1;
}

Error bad(std::string_view what, std::size_t offset) {
  return Error{ErrorCode::kParse,
               "exact form: byte " + std::to_string(offset) + ": " + std::string(what)};
}

struct ExprParser {
  std::string_view s;
  std::size_t i = 0, base = 0;  // base: the offset of s in the file
  int depth = 0;

  void skip() {
    while (i < s.size() && s[i] == ' ') ++i;
  }
  Result<Expr> parse() {
    skip();
    if (i >= s.size()) return bad("an expression ends early", base + i);
    if (std::isdigit(static_cast<unsigned char>(s[i]))) {
      int v = 0;
      const auto [p, ec] = std::from_chars(s.data() + i, s.data() + s.size(), v);
      if (ec != std::errc()) return bad("an operand number is out of range", base + i);
      i = static_cast<std::size_t>(p - s.data());
      return Expr::of(v);
    }
    if (s[i] != '(') return bad("expected '(' or an operand number", base + i);
    if (++depth > kMaxExactDepth)
      return bad("the expression nests deeper than " + std::to_string(kMaxExactDepth) + " levels",
                 base + i);
    ++i;
    const std::size_t start = i;
    while (i < s.size() && std::isalpha(static_cast<unsigned char>(s[i]))) ++i;
    const std::string_view name = s.substr(start, i - start);
    Expr e;
    if (name == "union") {
      e.kind = Expr::Kind::kUnion;
    } else if (name == "intersection") {
      e.kind = Expr::Kind::kIntersection;
    } else if (name == "difference") {
      e.kind = Expr::Kind::kDifference;
    } else {
      return bad("expected union, intersection or difference", base + start);
    }
    for (;;) {
      skip();
      if (i >= s.size()) return bad("a ')' is missing", base + i);
      if (s[i] == ')') {
        ++i;
        --depth;
        return e;
      }
      auto c = parse();
      if (!c) return c.error();
      e.children.push_back(std::move(*c));
    }
  }
};

constexpr std::string_view kMagic = "cellforge exact form 1\n";

}  // namespace

Result<std::shared_ptr<const ExactForm>> compose(std::span<const Operand> operands, const Expr& expr) {
  auto form = std::make_shared<ExactForm>();
  std::unordered_map<const Model*, int> index;  // an input shared by operands, once
  auto input = [&](const std::shared_ptr<const Model>& m) {
    auto [it, fresh] = index.try_emplace(m.get(), static_cast<int>(form->inputs.size()));
    if (fresh) form->inputs.push_back(m);
    return it->second;
  };
  std::vector<Expr> parts;
  for (std::size_t k = 0; k < operands.size(); ++k) {
    const Operand& o = operands[k];
    if (o.exact) {
      std::vector<int> map;
      for (const auto& m : o.exact->inputs) map.push_back(input(m));
      parts.push_back(renamed(o.exact->expr, map));
    } else if (o.model) {
      parts.push_back(Expr::of(input(o.model)));
    } else {
      return Error{ErrorCode::kInvalidInput,
                   "boolean: chain operand " + std::to_string(k) + " is empty"};
    }
  }
  if (expr.max_operand() >= static_cast<int>(parts.size()))
    return Error{ErrorCode::kInvalidInput, "boolean: the expression names operand " +
                                               std::to_string(expr.max_operand()) + " of " +
                                               std::to_string(parts.size())};
  form->expr = substituted(expr, parts);
  if (const int depth = depth_of(form->expr); depth > kMaxExactDepth)
    return Error{ErrorCode::kUnsupported,
                 "boolean: the chain's expression would nest " + std::to_string(depth) +
                     " levels; an exact form holds at most " + std::to_string(kMaxExactDepth) +
                     " (make an operand of the rounded model, Operand::of(result.model))"};
  return std::shared_ptr<const ExactForm>(std::move(form));
}

Result<BooleanResult> chain(std::span<const Operand> operands, const Expr& expr,
                            const Options& options) {
  auto form = compose(operands, expr);
  if (!form) return form.error();
  auto r = evaluate(**form, options);
  if (r) r->exact = std::move(*form);
  return r;
}

Result<BooleanResult> evaluate(const ExactForm& form, const Options& options) {
  std::vector<const Model*> ptrs;
  for (const auto& m : form.inputs) ptrs.push_back(m.get());
  return evaluate(std::span<const Model* const>(ptrs), form.expr, options);
}

std::string exact_to_string(const ExactForm& form) {
  std::string out(kMagic);
  out += "expr ";
  write_expr(form.expr, out);
  out += '\n';
  for (const auto& m : form.inputs) {
    auto json = io::write_model(*m, io::Format::kJson);
    const std::string text = json ? std::move(*json) : std::string();
    out += "input " + std::to_string(text.size()) + '\n';
    out += text;
    out += '\n';
  }
  return out;
}

Result<std::shared_ptr<const ExactForm>> exact_from_string(std::string_view text) {
  if (text.substr(0, kMagic.size()) != kMagic)
    return bad("not a cellforge exact form (no header)", 0);
  std::size_t at = kMagic.size();
  auto line_end = [&](std::size_t from) { return text.find('\n', from); };
  std::size_t e = line_end(at);
  if (e == std::string_view::npos || text.substr(at, 5) != "expr ")
    return bad("expected 'expr (...)'", at);
  ExprParser p{text.substr(at + 5, e - at - 5), 0, at + 5};
  auto expr = p.parse();
  if (!expr) return expr.error();
  p.skip();
  if (p.i != p.s.size()) return bad("unexpected text after the expression", p.base + p.i);
  auto form = std::make_shared<ExactForm>();
  form->expr = std::move(*expr);
  at = e + 1;
  while (at < text.size()) {
    e = line_end(at);
    if (e == std::string_view::npos || text.substr(at, 6) != "input ")
      return bad("expected 'input LENGTH'", at);
    std::size_t length = 0;
    const auto [ptr, ec] = std::from_chars(text.data() + at + 6, text.data() + e, length);
    if (ec != std::errc() || ptr != text.data() + e)
      return bad("expected the input's length in bytes", at + 6);
    const std::size_t body = e + 1;
    if (length > text.size() - body || body + length >= text.size() || text[body + length] != '\n')
      return bad("input " + std::to_string(form->inputs.size()) + " is shorter than its length",
                 body);
    auto m = std::make_shared<Model>();
    const std::string_view json = text.substr(body, length);
    auto r = io::read_model(*m,
                            std::span<const std::uint8_t>(
                                reinterpret_cast<const std::uint8_t*>(json.data()), json.size()),
                            io::Format::kJson);
    if (!r)
      return Error{ErrorCode::kParse, "exact form: input " + std::to_string(form->inputs.size()) +
                                          " (from byte " + std::to_string(body) +
                                          "): " + r.error().message};
    form->inputs.push_back(std::move(m));
    at = body + length + 1;
  }
  if (form->expr.max_operand() >= static_cast<int>(form->inputs.size()))
    return bad("the expression names input " + std::to_string(form->expr.max_operand()) + " of " +
                   std::to_string(form->inputs.size()),
               kMagic.size());
  return std::shared_ptr<const ExactForm>(std::move(form));
}

Status write_exact(const ExactForm& form, const std::string& path) {
  const std::string text = exact_to_string(form);
  std::ofstream f(path, std::ios::binary);
  f.write(text.data(), static_cast<std::streamsize>(text.size()));
  f.close();
  if (!f) return Error{ErrorCode::kIo, "exact form: cannot write " + path};
  return {};
}

Attachment exact_attachment(const ExactForm& form) {
  return {kExactAttachment, kExactAttachmentVersion, exact_to_string(form)};
}

Result<std::shared_ptr<const ExactForm>> exact_from_attachment(const Attachment& a) {
  const std::string what = std::string("attachment '") + a.name + "'";
  if (a.name != kExactAttachment)
    return Error{ErrorCode::kInvalidInput,
                 what + " is not an exact form ('" + kExactAttachment + "')"};
  if (a.version != kExactAttachmentVersion)
    return Error{ErrorCode::kUnsupported, what + " has version " + std::to_string(a.version) +
                                              "; this cellforge reads version " +
                                              std::to_string(kExactAttachmentVersion)};
  auto form = exact_from_string(a.data);
  if (!form) return Error{form.error().code, what + ": " + form.error().message};
  return form;
}

Result<std::shared_ptr<const ExactForm>> find_exact(const std::vector<Attachment>& attachments) {
  const Attachment* a = find_attachment(attachments, kExactAttachment);
  if (!a) return std::shared_ptr<const ExactForm>();
  return exact_from_attachment(*a);
}

Status write_result(const BooleanResult& result, const std::string& path) {
  io::WriteOptions options{.format = io::Format::kJson};
  if (result.exact) options.attachments.push_back(exact_attachment(*result.exact));
  return io::write_file(result.model, path, options);
}

Result<BooleanResult> read_result(const std::string& path) {
  BooleanResult out;
  auto r = io::read_file(out.model, path);
  if (!r) return r.error();
  auto form = find_exact(r->attachments);
  if (!form) return Error{form.error().code, path + ": " + form.error().message};
  out.exact = std::move(*form);
  return out;
}

Result<std::shared_ptr<const ExactForm>> read_exact(const std::string& path) {
  auto bytes = io::read_bytes(path);
  if (!bytes) return bytes.error();
  auto r = exact_from_string(
      std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()));
  if (!r) return Error{r.error().code, path + ": " + r.error().message};
  return r;
}

}  // namespace cellforge::boolean
