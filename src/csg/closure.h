// The evaluator's environments and function literals (private to csg/).
//
// An Env is one scope: its variables (the last assignment of a name in the scope
// wins), the modules and functions defined in it, and two links: `parent`, the
// lexical scope (where plain names are looked up), and `caller`, set on the scope of
// a module or function call, the scope it was called from (where $ variables are
// looked up after the call's own scopes: OpenSCAD's dynamic scoping).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cellforge/csg/ast.h"
#include "cellforge/csg/value.h"

namespace cellforge::csg {

struct Env;
using EnvPtr = std::shared_ptr<Env>;

// The children of a module instantiation: the statements written in its braces and
// the scope they were written in.
struct ChildList {
  std::vector<const Stmt*> assignments;
  std::vector<const Stmt*> instances;
  EnvPtr env;
};

struct Env {
  EnvPtr parent;
  EnvPtr caller;  // non-null on a call's scope
  std::vector<std::pair<std::string, Value>> vars;
  std::vector<std::pair<std::string, const Stmt*>> functions, modules;
  std::vector<EnvPtr> uses;                   // file scope: the use<>d files' scopes
  std::shared_ptr<const ChildList> children;  // a module call's scope: its children
  std::string module_name;                    // a module call's scope

  const Value* find_local(const std::string& name) const {
    for (auto it = vars.rbegin(); it != vars.rend(); ++it) {
      if (it->first == name) return &it->second;
    }
    return nullptr;
  }
  void set(const std::string& name, Value v) {
    for (auto& [n, value] : vars) {
      if (n == name) {
        value = std::move(v);
        return;
      }
    }
    vars.emplace_back(name, std::move(v));
  }
};

struct Closure {
  const Expr* literal = nullptr;  // the kFunction expression
  mutable EnvPtr env;             // reset when the evaluation ends (breaks cycles)
};

// OpenSCAD's text of an expression: "(a + b)", "f(x, y = 2)", "function(x) (x + 1)".
std::string expr_text(const Expr& e);
std::string closure_text(const Closure& c);

}  // namespace cellforge::csg
