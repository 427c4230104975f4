// Statements: a scope takes its module and function definitions, then its
// assignments (the last assignment of a name wins, evaluated at the place of the
// first, as OpenSCAD does), then instantiates its modules in order. User modules run
// their body in a scope whose parent is the scope they were defined in and whose
// caller is the scope they were called from; children() instantiates the caller's
// child statements in the caller's scope, below the module's $ variables.
#include <algorithm>
#include <cmath>

#include "interp.h"

namespace cellforge::csg {

NodePtr Interp::group(NodeKind kind, std::vector<NodePtr> children, SourcePos pos) {
  auto n = std::make_shared<Node>();
  n->kind = kind;
  n->pos = pos;
  n->children = std::move(children);
  return n;
}

void Interp::define(const std::vector<const Stmt*>& stmts, const EnvPtr& env) {
  for (const Stmt* s : stmts) {
    if (s->kind == StmtKind::kFunction) env->functions.emplace_back(s->name, s);
    if (s->kind == StmtKind::kModule) env->modules.emplace_back(s->name, s);
  }
}

std::vector<NodePtr> Interp::run_scope(const std::vector<const Stmt*>& stmts, const EnvPtr& env,
                                       const std::vector<const Stmt*>* extra_assignments) {
  define(stmts, env);
  // Assignments in order of first appearance, each with the last value expression given.
  std::vector<const Stmt*> order;
  std::vector<const Stmt*> last;
  auto add = [&](const Stmt* s) {
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (order[i]->name == s->name) {
        last[i] = s;
        return;
      }
    }
    order.push_back(s);
    last.push_back(s);
  };
  for (const Stmt* s : stmts) {
    if (s->kind == StmtKind::kAssign) add(s);
  }
  if (extra_assignments != nullptr) {
    for (const Stmt* s : *extra_assignments) add(s);
  }
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (last[i] != order[i] && last[i]->pos.file == order[i]->pos.file &&
        (extra_assignments == nullptr ||
         std::find(extra_assignments->begin(), extra_assignments->end(), last[i]) ==
             extra_assignments->end())) {
      warn(last[i]->pos, "'" + order[i]->name + "' was assigned on line " +
                             std::to_string(order[i]->pos.line) + " and is overwritten here");
    }
    env->set(order[i]->name, eval(*last[i]->value, env));
  }
  std::vector<NodePtr> nodes;
  for (const Stmt* s : stmts) {
    if (s->kind == StmtKind::kAssign || s->kind == StmtKind::kModule ||
        s->kind == StmtKind::kFunction)
      continue;
    std::vector<NodePtr> made = instantiate(*s, env);
    for (NodePtr& n : made) nodes.push_back(std::move(n));
  }
  return nodes;
}

// The statements under an instantiation, run in a scope of their own below env.
std::vector<NodePtr> Interp::children_of(const Stmt& s, const EnvPtr& env) {
  std::vector<const Stmt*> stmts;
  for (const StmtPtr& c : s.children) stmts.push_back(c.get());
  auto scope = std::make_shared<Env>();
  scope->parent = env;
  return run_scope(stmts, scope);
}

namespace {

std::vector<const Stmt*> raw(const std::vector<StmtPtr>& v) {
  std::vector<const Stmt*> out;
  for (const StmtPtr& s : v) out.push_back(s.get());
  return out;
}

// The node a modifier makes of what an instantiation made.
std::vector<NodePtr> apply_modifier(char modifier, std::vector<NodePtr> made, SourcePos pos) {
  if (modifier != '%' && modifier != '#') return made;
  auto g = std::make_shared<Node>();
  g->kind = NodeKind::kGroup;
  g->pos = pos;
  g->children = std::move(made);
  g->background = modifier == '%';
  g->highlight = modifier == '#';
  return {g};
}

}  // namespace

std::vector<NodePtr> Interp::instantiate(const Stmt& s, const EnvPtr& env) {
  check_stack(s.pos);
  step(s.pos);
  if (s.modifier == '*') return {};
  std::vector<NodePtr> made;
  switch (s.kind) {
    case StmtKind::kIf: {
      const bool c = eval(*s.value, env).truthy();
      auto scope = std::make_shared<Env>();
      scope->parent = env;
      made = run_scope(raw(c ? s.children : s.else_children), scope);
      break;
    }
    case StmtKind::kBlock: {
      auto scope = std::make_shared<Env>();
      scope->parent = env;
      made = run_scope(raw(s.children), scope);
      break;
    }
    case StmtKind::kInstance: {
      // A user module (innermost definition first, then use<>d files), else a built-in.
      const Stmt* def = nullptr;
      EnvPtr def_env;
      for (EnvPtr e = env; e && !def; e = e->parent) {
        for (auto it = e->modules.rbegin(); it != e->modules.rend(); ++it) {
          if (it->first == s.name) {
            def = it->second;
            def_env = e;
            break;
          }
        }
        for (const EnvPtr& u : e->uses) {
          if (def) break;
          for (auto it = u->modules.rbegin(); it != u->modules.rend(); ++it) {
            if (it->first == s.name) {
              def = it->second;
              def_env = u;
              break;
            }
          }
        }
      }
      if (def == nullptr) {
        if (s.name == "for" || s.name == "intersection_for") {
          std::vector<NodePtr> all;
          for_each_binding(s.args, 0, env, [&](const EnvPtr& inner) {
            auto nodes = children_of(s, inner);
            if (s.name == "for") {
              for (NodePtr& n : nodes) all.push_back(std::move(n));
            } else {
              all.push_back(group(NodeKind::kGroup, std::move(nodes), s.pos));
            }
          });
          made.push_back(group(s.name == "for" ? NodeKind::kGroup : NodeKind::kIntersection,
                               std::move(all), s.pos));
          break;
        }
        if (s.name == "let" || s.name == "assign") {  // assign(): OpenSCAD's deprecated let
          made = children_of(s, bind_let(s.args, env));
          break;
        }
        if (s.name == "each") fail(s.pos, "'each' is a list-comprehension element, not a module");
        const Args args = eval_args(s.args, env);
        if (s.name == "echo" || s.name == "assert") {
          if (s.name == "echo") {
            std::string line = "ECHO: ";
            for (std::size_t i = 0; i < args.size(); ++i) {
              if (i) line += ", ";
              if (!args[i].name.empty()) line += args[i].name + " = ";
              line += args[i].value.to_echo();
            }
            echo(line);
          } else if (args.empty() || !args[0].value.truthy()) {
            std::string msg =
                "assertion '" +
                (s.args.empty() ? std::string("undef") : expr_text(*s.args[0].value)) + "' failed";
            if (args.size() > 1) msg += ": " + args[1].value.to_echo();
            fail(s.pos, msg);
          }
          made = children_of(s, env);
          break;
        }
        if (s.name == "children") {
          // The children of the module call this scope belongs to.
          const Env* frame = env.get();
          while (frame != nullptr && !frame->children) frame = frame->parent.get();
          if (frame == nullptr) break;  // children() outside a module: nothing
          const ChildList& kids = *frame->children;
          std::vector<std::size_t> which;
          const double n = static_cast<double>(kids.instances.size());
          auto pick = [&](const Value& v) {
            if (!v.is_number()) {
              warn(s.pos, std::string("children() takes numbers, not a ") + type_name(v.type()));
              return;
            }
            const double i = v.as_number();
            if (i >= 0 && i < n && i == std::floor(i)) {
              which.push_back(static_cast<std::size_t>(i));
            } else {
              warn(s.pos, "children(" + format_number(i) + "): out of range (there are " +
                              format_number(n) + ")");
            }
          };
          if (args.empty()) {
            for (std::size_t i = 0; i < kids.instances.size(); ++i) which.push_back(i);
          } else if (args[0].value.is_number()) {
            pick(args[0].value);
          } else {
            iterate(args[0].value, s.pos, pick);
          }
          auto scope = std::make_shared<Env>();
          scope->parent = kids.env;
          scope->caller = env;
          std::vector<NodePtr> nodes;
          // The braces' assignments first, then the chosen instantiations.
          std::vector<const Stmt*> stmts = kids.assignments;
          run_scope(stmts, scope);
          for (std::size_t i : which) {
            for (NodePtr& m : instantiate(*kids.instances[i], scope)) nodes.push_back(std::move(m));
          }
          made.push_back(group(NodeKind::kGroup, std::move(nodes), s.pos));
          break;
        }
        if (!call_builtin_module(s, args, env, made)) {
          warn(s.pos, "unknown module '" + s.name + "' (ignored)");
        }
        break;
      }
      // A user module call.
      const Args args = eval_args(s.args, env);
      auto frame = std::make_shared<Env>();
      frame->parent = def_env;
      frame->caller = env;
      frame->module_name = s.name;
      auto kids = std::make_shared<ChildList>();
      kids->env = env;
      for (const StmtPtr& c : s.children) {
        (c->kind == StmtKind::kAssign ? kids->assignments : kids->instances).push_back(c.get());
      }
      frame->children = kids;
      std::size_t positional = 0;
      for (const Arg& a : args) {
        if (!a.name.empty()) continue;
        if (positional < def->params.size()) {
          frame->set(def->params[positional].name, a.value);
        } else if (positional == def->params.size()) {
          warn(a.pos, "too many unnamed arguments for module '" + s.name + "'");
        }
        ++positional;
      }
      for (const Arg& a : args) {
        if (a.name.empty()) continue;
        bool known = a.name[0] == '$';
        for (const Binding& p : def->params) known |= p.name == a.name;
        if (known) {
          frame->set(a.name, a.value);
        } else {
          warn(a.pos, "'" + a.name + "' is not a parameter of module '" + s.name + "'");
        }
      }
      for (const Binding& p : def->params) {
        if (!frame->find_local(p.name))
          frame->set(p.name, p.value ? eval(*p.value, frame) : Value());
      }
      frame->set("$children", Value::number(static_cast<double>(kids->instances.size())));
      if (module_stack_.size() >= 100000) fail(s.pos, "modules nested deeper than 100000 calls");
      module_stack_.push_back(s.name);
      std::vector<NodePtr> body = run_scope(raw(def->children), frame);
      module_stack_.pop_back();
      made.push_back(group(NodeKind::kGroup, std::move(body), s.pos));
      break;
    }
    default:
      break;
  }
  if (s.modifier == '!' && !root_override_) {
    root_override_ = group(NodeKind::kGroup, made, s.pos);
  }
  return apply_modifier(s.modifier, std::move(made), s.pos);
}

}  // namespace cellforge::csg
