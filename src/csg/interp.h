// The evaluator's machinery (private to csg/): one Interp per evaluation.
//   eval_expr.cpp      expressions, operators, calls (with tail calls), comprehensions
//   builtin_functions.cpp  the built-in functions (math, strings, lists, search ...)
//   eval_stmt.cpp      scopes, statements, module calls, children(), control modules
//   builtin_modules.cpp    the geometry modules (cube ... projection) -> tree nodes
//   evaluator.cpp      files, include<> and use<>, the entry points and the thread
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cellforge/csg/ast.h"
#include "cellforge/csg/evaluator.h"
#include "cellforge/csg/tree.h"
#include "closure.h"

namespace cellforge::csg {

// An evaluation error: thrown inside the evaluator, returned as an Error by it.
struct EvalError {
  SourcePos pos;
  std::string message;
};

// Evaluated call arguments, in order, each with its name ("" when positional).
struct Arg {
  std::string name;
  Value value;
  SourcePos pos;
};
using Args = std::vector<Arg>;

// The arguments of a built-in module or function matched to its parameter names:
// positional ones in order, then named ones.
class Params {
 public:
  Params(const Args& args, std::vector<std::string> names, SourcePos call)
      : args_(args), names_(std::move(names)), call_(call) {}
  // The value given for the parameter (undef when absent) and where it was written.
  const Value& get(const std::string& name) const;
  SourcePos pos(const std::string& name) const;
  bool has(const std::string& name) const { return !get(name).is_undef(); }
  SourcePos call() const { return call_; }
  const Args& args() const { return args_; }

 private:
  const Arg* find(const std::string& name) const;
  const Args& args_;
  std::vector<std::string> names_;
  SourcePos call_;
};

struct FileEntry {
  std::unique_ptr<File> file;
  EnvPtr use_env;  // the file's scope when it is use<>d (made once)
};

class Interp {
 public:
  Interp(const EvalOptions& options, std::shared_ptr<Sources> sources);
  ~Interp();

  // evaluator.cpp
  EvalOutput run(std::uint32_t main_source);
  const File& load(std::uint32_t source);                          // parse (once)
  std::uint32_t resolve(const std::string& path, SourcePos from);  // find and read a file

  // eval_expr.cpp
  Value eval(const Expr& e, const EnvPtr& env);
  Args eval_args(const std::vector<Binding>& args, const EnvPtr& env);
  Value lookup(const std::string& name, const EnvPtr& env, SourcePos pos);
  Value make_vector(Vector v, SourcePos pos);
  void iterate(const Value& v, SourcePos pos, const std::function<void(const Value&)>& each);
  // Binds `for (a = ..., b = ...)` combinations, the first the outermost loop.
  void for_each_binding(const std::vector<Binding>& bindings, std::size_t i, const EnvPtr& env,
                        const std::function<void(const EnvPtr&)>& body);
  EnvPtr bind_let(const std::vector<Binding>& bindings, const EnvPtr& env);

  // builtin_functions.cpp: false when no built-in function has the name.
  bool call_builtin_function(const std::string& name, const Args& args, SourcePos pos,
                             const EnvPtr& env, Value& out);
  bool dxf_function(const std::string& name, const Args& args, SourcePos pos, Value& out);

  // eval_stmt.cpp
  std::vector<NodePtr> run_scope(const std::vector<const Stmt*>& stmts, const EnvPtr& env,
                                 const std::vector<const Stmt*>* extra_assignments = nullptr);
  std::vector<NodePtr> instantiate(const Stmt& s, const EnvPtr& env);
  void define(const std::vector<const Stmt*>& stmts, const EnvPtr& env);
  // A file's statements with its include<>s spliced in and its use<>s attached to env.
  std::vector<const Stmt*> file_statements(const File& f, const EnvPtr& env, int depth);

  // builtin_modules.cpp: false when no built-in module has the name.
  bool call_builtin_module(const Stmt& s, const Args& args, const EnvPtr& env,
                           std::vector<NodePtr>& out);

  // builtin_text.cpp: text() as one polygon per glyph; surface() as a polyhedron.
  bool text(const Stmt& s, const Args& args, const EnvPtr& env, std::vector<NodePtr>& out);
  bool surface(const Stmt& s, const Args& args, std::vector<NodePtr>& out);
  // A file named by a script (import(), surface()): resolved against the folder of the
  // script that names it, unless absolute.
  std::string script_relative(const std::string& file, SourcePos from) const;

  // Shared helpers
  void step(SourcePos pos);
  void check_stack(SourcePos pos);
  [[noreturn]] void fail(SourcePos pos, const std::string& message) const;
  void warn(SourcePos pos, const std::string& message);
  void echo(const std::string& line);
  Value dollar(const std::string& name, const EnvPtr& env);  // a $ variable in scope
  shape::Faceting faceting(const Params& p, const EnvPtr& env);
  NodePtr group(NodeKind kind, std::vector<NodePtr> children, SourcePos pos);
  std::vector<NodePtr> children_of(const Stmt& s, const EnvPtr& env);

  const EvalOptions& options_;
  std::shared_ptr<Sources> sources_;
  std::map<std::uint32_t, FileEntry> files_;      // by source index
  std::map<std::string, std::uint32_t> by_path_;  // canonical path -> source index
  std::map<std::uint32_t, std::string> source_paths_;
  std::vector<std::weak_ptr<const Closure>> closures_;
  std::vector<std::string> module_stack_;
  std::vector<std::string> echoes_, warnings_;
  std::uint64_t steps_ = 0;
  const char* stack_base_ = nullptr;
  NodePtr root_override_;  // the first '!' subtree
};

// Numbers and vectors out of values (for the built-ins).
bool to_vec3(const Value& v, Vec3& out, bool allow_2d = true);
bool to_number(const Value& v, double& out);

}  // namespace cellforge::csg
