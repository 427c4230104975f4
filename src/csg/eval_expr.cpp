// Expressions: OpenSCAD's operators on numbers, vectors (element-wise, dot and matrix
// products) and strings; calls of built-in functions, function definitions and
// function literals, with calls in tail position run in the same loop iteration
// (no stack growth); list comprehensions.
#include <cmath>

#include "interp.h"

namespace cellforge::csg {
namespace {

bool is_number_vector(const Vector& v) {
  for (const Value& x : v) {
    if (!x.is_number()) return false;
  }
  return true;
}

bool is_matrix(const Vector& v) {
  if (v.empty()) return false;
  for (const Value& row : v) {
    if (!row.is_vector() || !is_number_vector(row.as_vector())) return false;
  }
  return true;
}

double dot(const Vector& a, const Vector& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i].as_number() * b[i].as_number();
  return s;
}

}  // namespace

Value Interp::make_vector(Vector v, SourcePos pos) {
  if (v.size() > options_.max_list_size) {
    fail(pos, "a list of " + std::to_string(v.size()) + " elements is longer than the limit (" +
                  std::to_string(options_.max_list_size) + ")");
  }
  Value out = Value::vector(std::move(v));
  if (out.nesting() > options_.max_nesting) {
    fail(pos, "vectors nest deeper than the limit (" + std::to_string(options_.max_nesting) + ")");
  }
  return out;
}

namespace {

// Element-wise + and - (to the shorter length, as OpenSCAD does); undef elsewhere.
Value add_sub(Interp& in, const Value& a, const Value& b, bool add, SourcePos pos, bool& ok) {
  if (a.is_number() && b.is_number()) {
    return Value::number(add ? a.as_number() + b.as_number() : a.as_number() - b.as_number());
  }
  if (a.is_vector() && b.is_vector()) {
    const Vector& x = a.as_vector();
    const Vector& y = b.as_vector();
    Vector out;
    out.reserve(std::min(x.size(), y.size()));
    for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
      bool inner = true;
      out.push_back(add_sub(in, x[i], y[i], add, pos, inner));
      if (!inner) out.back() = Value();
    }
    return in.make_vector(std::move(out), pos);
  }
  ok = false;
  return Value();
}

Value scale_value(Interp& in, const Value& v, double s, bool divide, bool scalar_first,
                  SourcePos pos, bool& ok) {
  if (v.is_number()) {
    const double x = v.as_number();
    return Value::number(divide ? (scalar_first ? s / x : x / s) : x * s);
  }
  if (v.is_vector()) {
    Vector out;
    out.reserve(v.as_vector().size());
    for (const Value& e : v.as_vector()) {
      bool inner = true;
      out.push_back(scale_value(in, e, s, divide, scalar_first, pos, inner));
      if (!inner) out.back() = Value();
    }
    return in.make_vector(std::move(out), pos);
  }
  ok = false;
  return Value();
}

Value multiply(Interp& in, const Value& a, const Value& b, SourcePos pos, bool& ok) {
  if (a.is_number() && b.is_number()) return Value::number(a.as_number() * b.as_number());
  if (a.is_number() && b.is_vector())
    return scale_value(in, b, a.as_number(), false, true, pos, ok);
  if (a.is_vector() && b.is_number())
    return scale_value(in, a, b.as_number(), false, false, pos, ok);
  if (a.is_vector() && b.is_vector()) {
    const Vector& x = a.as_vector();
    const Vector& y = b.as_vector();
    if (is_number_vector(x) && is_number_vector(y)) {
      if (x.size() == y.size() && !x.empty()) return Value::number(dot(x, y));
    } else if (is_matrix(x) && is_number_vector(y)) {
      Vector out;
      for (const Value& row : x) {
        if (row.as_vector().size() != y.size()) {
          ok = false;
          return Value();
        }
        out.push_back(Value::number(dot(row.as_vector(), y)));
      }
      return in.make_vector(std::move(out), pos);
    } else if (is_number_vector(x) && is_matrix(y)) {
      if (x.size() != y.size()) {
        ok = false;
        return Value();
      }
      const std::size_t cols = y[0].as_vector().size();
      Vector out;
      for (std::size_t c = 0; c < cols; ++c) {
        double s = 0;
        for (std::size_t r = 0; r < y.size(); ++r) {
          const Vector& row = y[r].as_vector();
          if (row.size() != cols) {
            ok = false;
            return Value();
          }
          s += x[r].as_number() * row[c].as_number();
        }
        out.push_back(Value::number(s));
      }
      return in.make_vector(std::move(out), pos);
    } else if (is_matrix(x) && is_matrix(y)) {
      Vector out;
      for (const Value& row : x) {
        bool inner = true;
        out.push_back(multiply(in, row, b, pos, inner));
        if (!inner) {
          ok = false;
          return Value();
        }
      }
      return in.make_vector(std::move(out), pos);
    }
  }
  ok = false;
  return Value();
}

int compare_values(const Value& a, const Value& b, bool& ok) {
  if (a.is_number() && b.is_number()) {
    return a.as_number() < b.as_number() ? -1 : a.as_number() > b.as_number() ? 1 : 0;
  }
  if (a.is_string() && b.is_string()) {
    const int c = a.as_string().compare(b.as_string());
    return c < 0 ? -1 : c > 0 ? 1 : 0;
  }
  if (a.is_bool() && b.is_bool())
    return static_cast<int>(a.as_bool()) - static_cast<int>(b.as_bool());
  ok = false;
  return 0;
}

// The UTF-8 characters of a string (a byte that starts no valid sequence is one).
std::vector<std::string> utf8_chars(const std::string& s) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    std::size_t n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 1;
    if (i + n > s.size()) n = 1;
    for (std::size_t k = 1; k < n; ++k) {
      if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) n = 1;
    }
    out.push_back(s.substr(i, n));
    i += n;
  }
  return out;
}

}  // namespace

Value Interp::lookup(const std::string& name, const EnvPtr& env, SourcePos pos) {
  if (!name.empty() && name[0] == '$') {
    if (name == "$parent_modules") {
      return Value::number(static_cast<double>(module_stack_.size()));
    }
    for (const Env* s = env.get(); s != nullptr;
         s = s->caller ? s->caller.get() : s->parent.get()) {
      if (const Value* v = s->find_local(name)) return *v;
    }
    if (name == "$fn") return Value::number(0);
    if (name == "$fa") return Value::number(12);
    if (name == "$fs") return Value::number(2);
    if (name == "$t") return Value::number(options_.t);
    if (name == "$preview") return Value::boolean(options_.preview);
    if (name == "$children") return Value::number(0);
    if (name == "$vpr" || name == "$vpt") {
      return Value::vector({Value::number(0), Value::number(0), Value::number(0)});
    }
    if (name == "$vpd") return Value::number(500);
    if (name == "$vpf") return Value::number(22.5);
    warn(pos, "unknown variable '" + name + "' (undef)");
    return Value();
  }
  for (const Env* s = env.get(); s != nullptr; s = s->parent.get()) {
    if (const Value* v = s->find_local(name)) return *v;
  }
  if (name == "PI") return Value::number(M_PI);
  warn(pos, "unknown variable '" + name + "' (undef)");
  return Value();
}

Value Interp::dollar(const std::string& name, const EnvPtr& env) { return lookup(name, env, {}); }

Args Interp::eval_args(const std::vector<Binding>& args, const EnvPtr& env) {
  Args out;
  out.reserve(args.size());
  for (const Binding& b : args) out.push_back(Arg{b.name, eval(*b.value, env), b.pos});
  return out;
}

EnvPtr Interp::bind_let(const std::vector<Binding>& bindings, const EnvPtr& env) {
  auto e = std::make_shared<Env>();
  e->parent = env;
  for (const Binding& b : bindings) {
    if (b.name.empty()) {
      warn(b.pos, "let() takes name = value; a value without a name is ignored");
      continue;
    }
    e->set(b.name, eval(*b.value, e));
  }
  return e;
}

void Interp::iterate(const Value& v, SourcePos pos, const std::function<void(const Value&)>& each) {
  switch (v.type()) {
    case Value::Type::kVector:
      for (const Value& x : v.as_vector()) each(x);
      return;
    case Value::Type::kRange: {
      const Range& r = v.as_range();
      const double n = r.count();
      if (n > static_cast<double>(options_.max_list_size)) {
        fail(pos, "the range " + v.to_echo() + " has more elements than the limit (" +
                      std::to_string(options_.max_list_size) + ")");
      }
      for (double i = 0; i < n; ++i) each(Value::number(r.at(i)));
      return;
    }
    case Value::Type::kString:
      for (const std::string& c : utf8_chars(v.as_string())) each(Value::string(c));
      return;
    case Value::Type::kUndef:
      return;
    default:
      each(v);
  }
}

void Interp::for_each_binding(const std::vector<Binding>& bindings, std::size_t i,
                              const EnvPtr& env, const std::function<void(const EnvPtr&)>& body) {
  if (i == bindings.size()) {
    body(env);
    return;
  }
  const Binding& b = bindings[i];
  if (b.name.empty()) fail(b.pos, "for() takes name = values");
  const Value values = eval(*b.value, env);
  iterate(values, b.pos, [&](const Value& x) {
    auto e = std::make_shared<Env>();
    e->parent = env;
    e->set(b.name, x);
    for_each_binding(bindings, i + 1, e, body);
  });
}

namespace {

struct Comprehension {
  Interp& in;
  Vector& out;

  void element(const Expr& e, const EnvPtr& env) {
    in.check_stack(e.pos);
    in.step(e.pos);
    switch (e.kind) {
      case ExprKind::kLcFor:
        in.for_each_binding(e.args, 0, env,
                            [&](const EnvPtr& inner) { element(*e.items[0], inner); });
        return;
      case ExprKind::kLcForC: {
        auto loop = std::make_shared<Env>();
        loop->parent = env;
        for (const Binding& b : e.args) loop->set(b.name, in.eval(*b.value, loop));
        while (in.eval(*e.items[0], loop).truthy()) {
          element(*e.items[1], loop);
          auto next = std::make_shared<Env>();
          next->parent = env;
          for (const Binding& b : e.params) next->set(b.name, in.eval(*b.value, loop));
          for (const auto& [name, value] : loop->vars) {
            if (!next->find_local(name)) next->set(name, value);
          }
          loop = next;
          check_size(e.pos);
        }
        return;
      }
      case ExprKind::kLcIf:
        if (in.eval(*e.items[0], env).truthy()) {
          element(*e.items[1], env);
        } else if (e.items.size() > 2) {
          element(*e.items[2], env);
        }
        return;
      case ExprKind::kLcLet:
        element(*e.items[0], in.bind_let(e.args, env));
        return;
      case ExprKind::kLcEach: {
        const Value v = value_of(*e.items[0], env);
        if (v.is_vector() || v.is_range() || v.is_string()) {
          in.iterate(v, e.pos, [&](const Value& x) {
            out.push_back(x);
            check_size(e.pos);
          });
        } else {
          out.push_back(v);
        }
        return;
      }
      default:
        out.push_back(in.eval(e, env));
        check_size(e.pos);
    }
  }

  // `each` of a comprehension element collects that element's values first.
  Value value_of(const Expr& e, const EnvPtr& env) {
    switch (e.kind) {
      case ExprKind::kLcFor:
      case ExprKind::kLcForC:
      case ExprKind::kLcIf:
      case ExprKind::kLcLet:
      case ExprKind::kLcEach: {
        Vector inner;
        Comprehension c{in, inner};
        c.element(e, env);
        return in.make_vector(std::move(inner), e.pos);
      }
      default:
        return in.eval(e, env);
    }
  }

  void check_size(SourcePos pos) {
    if (out.size() > in.options_.max_list_size) {
      in.fail(pos, "the list comprehension makes more elements than the limit (" +
                       std::to_string(in.options_.max_list_size) + ")");
    }
  }
};

}  // namespace

Value Interp::eval(const Expr& e0, const EnvPtr& env0) {
  check_stack(e0.pos);
  const Expr* e = &e0;
  EnvPtr env = env0;
  bool in_call = false;  // whether env belongs to a call this loop made (tail calls)
  for (;;) {
    step(e->pos);
    switch (e->kind) {
      case ExprKind::kNumber:
        return Value::number(e->number);
      case ExprKind::kString:
        return Value::string(e->text);
      case ExprKind::kBool:
        return Value::boolean(e->number != 0);
      case ExprKind::kUndef:
        return Value();
      case ExprKind::kIdent:
        return lookup(e->text, env, e->pos);
      case ExprKind::kVector: {
        Vector out;
        Comprehension c{*this, out};
        for (const ExprPtr& item : e->items) c.element(*item, env);
        return make_vector(std::move(out), e->pos);
      }
      case ExprKind::kRange: {
        double v[3];
        for (std::size_t i = 0; i < e->items.size(); ++i) {
          const Value x = eval(*e->items[i], env);
          if (!x.is_number()) {
            warn(e->items[i]->pos,
                 std::string("a range takes numbers, not a ") + type_name(x.type()));
            return Value();
          }
          v[i] = x.as_number();
        }
        Range r;
        if (e->items.size() == 2) {
          r = {v[0], 1, v[1]};
          if (r.begin > r.end) {
            warn(e->pos,
                 "a range [begin:end] with begin greater than end runs from end to begin "
                 "(deprecated in OpenSCAD)");
            std::swap(r.begin, r.end);
          }
        } else {
          r = {v[0], v[1], v[2]};
        }
        return Value::range(r);
      }
      case ExprKind::kUnary: {
        const Value x = eval(*e->items[0], env);
        if (e->text == "!") return Value::boolean(!x.truthy());
        if (e->text == "+" && (x.is_number() || x.is_vector())) return x;
        if (e->text == "-") {
          bool ok = true;
          if (x.is_number() || x.is_vector()) {
            Value r = scale_value(*this, x, -1, false, false, e->pos, ok);
            if (ok) return r;
          }
        }
        warn(e->pos, "undefined operation (" + e->text + type_name(x.type()) + ")");
        return Value();
      }
      case ExprKind::kBinary: {
        const std::string& op = e->text;
        if (op == "&&") {
          if (!eval(*e->items[0], env).truthy()) return Value::boolean(false);
          return Value::boolean(eval(*e->items[1], env).truthy());
        }
        if (op == "||") {
          if (eval(*e->items[0], env).truthy()) return Value::boolean(true);
          return Value::boolean(eval(*e->items[1], env).truthy());
        }
        const Value a = eval(*e->items[0], env);
        const Value b = eval(*e->items[1], env);
        if (op == "==") return Value::boolean(a == b);
        if (op == "!=") return Value::boolean(!(a == b));
        bool ok = true;
        Value r;
        if (op == "+" || op == "-") {
          r = add_sub(*this, a, b, op == "+", e->pos, ok);
        } else if (op == "*") {
          r = multiply(*this, a, b, e->pos, ok);
        } else if (op == "/") {
          if (a.is_number() && b.is_number()) {
            r = Value::number(a.as_number() / b.as_number());
          } else if (a.is_vector() && b.is_number()) {
            r = scale_value(*this, a, b.as_number(), true, false, e->pos, ok);
          } else if (a.is_number() && b.is_vector()) {
            r = scale_value(*this, b, a.as_number(), true, true, e->pos, ok);
          } else {
            ok = false;
          }
        } else if (op == "%") {
          if (a.is_number() && b.is_number()) {
            r = Value::number(std::fmod(a.as_number(), b.as_number()));
          } else {
            ok = false;
          }
        } else if (op == "^") {
          if (a.is_number() && b.is_number()) {
            r = Value::number(std::pow(a.as_number(), b.as_number()));
          } else {
            ok = false;
          }
        } else {
          const int c = compare_values(a, b, ok);
          if (ok) {
            if (op == "<") r = Value::boolean(c < 0);
            if (op == "<=") r = Value::boolean(c <= 0);
            if (op == ">") r = Value::boolean(c > 0);
            if (op == ">=") r = Value::boolean(c >= 0);
          }
        }
        if (!ok) {
          warn(e->pos, std::string("undefined operation (") + type_name(a.type()) + " " + op + " " +
                           type_name(b.type()) + ")");
          return Value();
        }
        return r;
      }
      case ExprKind::kTernary: {
        const bool c = eval(*e->items[0], env).truthy();
        e = c ? e->items[1].get() : e->items[2].get();
        continue;
      }
      case ExprKind::kIndex: {
        const Value obj = eval(*e->items[0], env);
        const Value idx = eval(*e->items[1], env);
        if (!idx.is_number()) {
          if (!obj.is_undef())
            warn(e->pos, std::string("an index must be a number, not a ") + type_name(idx.type()));
          return Value();
        }
        const double d = idx.as_number();
        if (!(d >= 0)) return Value();
        const double i = std::floor(d);
        if (obj.is_vector()) {
          return i < static_cast<double>(obj.as_vector().size())
                     ? obj.as_vector()[static_cast<std::size_t>(i)]
                     : Value();
        }
        if (obj.is_string()) {
          const auto chars = utf8_chars(obj.as_string());
          return i < static_cast<double>(chars.size())
                     ? Value::string(chars[static_cast<std::size_t>(i)])
                     : Value();
        }
        if (obj.is_range()) {
          const Range& r = obj.as_range();
          return i < r.count() ? Value::number(r.at(i)) : Value();
        }
        return Value();
      }
      case ExprKind::kMember: {
        const Value obj = eval(*e->items[0], env);
        const std::size_t i = e->text == "x" ? 0 : e->text == "y" ? 1 : e->text == "z" ? 2 : 99;
        if (obj.is_vector() && i < obj.as_vector().size()) return obj.as_vector()[i];
        if (obj.is_range() && i < 3) {
          const Range& r = obj.as_range();
          return Value::number(i == 0 ? r.begin : i == 1 ? r.step : r.end);
        }
        return Value();
      }
      case ExprKind::kFunction: {
        auto c = std::make_shared<Closure>();
        c->literal = e;
        c->env = env;
        if (closures_.size() > 1024 && closures_.size() == closures_.capacity()) {
          std::erase_if(closures_, [](const auto& w) { return w.expired(); });
        }
        closures_.push_back(c);
        return Value::function(std::move(c));
      }
      case ExprKind::kLet:
        env = bind_let(e->args, env);
        e = e->items[0].get();
        continue;
      case ExprKind::kAssert:
      case ExprKind::kEcho: {
        const Args args = eval_args(e->args, env);
        if (e->kind == ExprKind::kAssert) {
          if (args.empty() || !args[0].value.truthy()) {
            std::string msg =
                "assertion '" +
                (e->args.empty() ? std::string("undef") : expr_text(*e->args[0].value)) +
                "' failed";
            if (args.size() > 1) msg += ": " + args[1].value.to_echo();
            fail(e->pos, msg);
          }
        } else {
          std::string line = "ECHO: ";
          for (std::size_t i = 0; i < args.size(); ++i) {
            if (i) line += ", ";
            if (!args[i].name.empty()) line += args[i].name + " = ";
            line += args[i].value.to_echo();
          }
          echo(line);
        }
        if (e->items.empty()) return Value();
        e = e->items[0].get();
        continue;
      }
      case ExprKind::kCall: {
        const Expr& callee = *e->items[0];
        const Closure* closure = nullptr;
        Value held;  // keeps the closure alive until its frame is made
        const Stmt* def = nullptr;
        EnvPtr def_env;
        if (callee.kind == ExprKind::kIdent) {
          const std::string& name = callee.text;
          for (const Env* s = env.get(); s != nullptr && !closure; s = s->parent.get()) {
            if (const Value* v = s->find_local(name); v && v->is_function()) {
              held = *v;
              closure = held.as_function().get();
            }
          }
          if (!closure) {
            for (EnvPtr s = env; s && !def; s = s->parent) {
              for (auto it = s->functions.rbegin(); it != s->functions.rend(); ++it) {
                if (it->first == name) {
                  def = it->second;
                  def_env = s;
                  break;
                }
              }
              for (const EnvPtr& u : s->uses) {
                if (def) break;
                for (auto it = u->functions.rbegin(); it != u->functions.rend(); ++it) {
                  if (it->first == name) {
                    def = it->second;
                    def_env = u;
                    break;
                  }
                }
              }
            }
          }
          if (!closure && !def) {
            const Args args = eval_args(e->args, env);
            Value out;
            if (call_builtin_function(name, args, e->pos, env, out)) return out;
            warn(callee.pos, "unknown function '" + name + "' (undef)");
            return Value();
          }
        } else {
          held = eval(callee, env);
          if (!held.is_function()) {
            warn(e->pos, std::string("a ") + type_name(held.type()) + " is not a function (undef)");
            return Value();
          }
          closure = held.as_function().get();
        }
        const std::vector<Binding>& params = closure ? closure->literal->params : def->params;
        const Args args = eval_args(e->args, env);
        auto frame = std::make_shared<Env>();
        frame->parent = closure ? closure->env : def_env;
        // A tail call replaces the running call: its caller is the running call's
        // caller unless a $ variable was set in between.
        EnvPtr caller = env;
        if (in_call) {
          bool dollar_set = false;
          const Env* s = env.get();
          for (; s != nullptr && !s->caller; s = s->parent.get()) {
            for (const auto& [n, v] : s->vars) dollar_set |= !n.empty() && n[0] == '$';
          }
          if (s != nullptr) {
            for (const auto& [n, v] : s->vars) dollar_set |= !n.empty() && n[0] == '$';
            if (!dollar_set) caller = s->caller;
          }
        }
        frame->caller = caller;
        std::size_t positional = 0;
        for (const Arg& a : args) {
          if (!a.name.empty()) continue;
          if (positional < params.size()) {
            frame->set(params[positional].name, a.value);
          }
          ++positional;
        }
        for (const Arg& a : args) {
          if (a.name.empty()) continue;
          bool known = a.name[0] == '$';
          for (const Binding& p : params) known |= p.name == a.name;
          if (known) {
            frame->set(a.name, a.value);
          } else {
            warn(a.pos, "'" + a.name + "' is not a parameter of the function");
          }
        }
        for (const Binding& p : params) {
          if (!frame->find_local(p.name))
            frame->set(p.name, p.value ? eval(*p.value, frame) : Value());
        }
        env = std::move(frame);
        in_call = true;
        e = closure ? closure->literal->items[0].get() : def->value.get();
        continue;
      }
      default:
        fail(e->pos, "a list-comprehension element (for, if, let, each) outside [ ]");
    }
  }
}

// ---- OpenSCAD's text of an expression

namespace {

std::string bindings_text(const std::vector<Binding>& bs) {
  std::string out;
  for (std::size_t i = 0; i < bs.size(); ++i) {
    if (i) out += ", ";
    if (!bs[i].name.empty()) out += bs[i].name + (bs[i].value ? " = " : "");
    if (bs[i].value) out += expr_text(*bs[i].value);
  }
  return out;
}

}  // namespace

std::string expr_text(const Expr& e) {
  auto item = [&](std::size_t i) { return expr_text(*e.items[i]); };
  switch (e.kind) {
    case ExprKind::kNumber:
      return format_number(e.number);
    case ExprKind::kString:
      return "\"" + e.text + "\"";
    case ExprKind::kBool:
      return e.number != 0 ? "true" : "false";
    case ExprKind::kUndef:
      return "undef";
    case ExprKind::kIdent:
      return e.text;
    case ExprKind::kVector: {
      std::string out = "[";
      for (std::size_t i = 0; i < e.items.size(); ++i) out += (i ? ", " : "") + item(i);
      return out + "]";
    }
    case ExprKind::kRange:
      return e.items.size() == 2 ? "[" + item(0) + " : " + item(1) + "]"
                                 : "[" + item(0) + " : " + item(1) + " : " + item(2) + "]";
    case ExprKind::kUnary:
      return e.text + item(0);
    case ExprKind::kBinary:
      return "(" + item(0) + " " + e.text + " " + item(1) + ")";
    case ExprKind::kTernary:
      return "(" + item(0) + " ? " + item(1) + " : " + item(2) + ")";
    case ExprKind::kIndex:
      return item(0) + "[" + item(1) + "]";
    case ExprKind::kMember:
      return item(0) + "." + e.text;
    case ExprKind::kCall:
      return item(0) + "(" + bindings_text(e.args) + ")";
    case ExprKind::kFunction:
      return "function(" + bindings_text(e.params) + ") " + item(0);
    case ExprKind::kLet:
      return "let(" + bindings_text(e.args) + ") " + item(0);
    case ExprKind::kAssert:
    case ExprKind::kEcho:
      return std::string(e.kind == ExprKind::kAssert ? "assert(" : "echo(") +
             bindings_text(e.args) + ")" + (e.items.empty() ? "" : " " + item(0));
    case ExprKind::kLcFor:
      return "for(" + bindings_text(e.args) + ") " + item(0);
    case ExprKind::kLcForC:
      return "for(" + bindings_text(e.args) + "; " + item(0) + "; " + bindings_text(e.params) +
             ") " + item(1);
    case ExprKind::kLcIf:
      return "if(" + item(0) + ") " + item(1) + (e.items.size() > 2 ? " else " + item(2) : "");
    case ExprKind::kLcLet:
      return "let(" + bindings_text(e.args) + ") " + item(0);
    case ExprKind::kLcEach:
      return "each " + item(0);
  }
  return "?";
}

std::string closure_text(const Closure& c) { return expr_text(*c.literal); }

}  // namespace cellforge::csg
