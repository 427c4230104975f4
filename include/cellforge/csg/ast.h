// The syntax tree of an OpenSCAD script (parser.h makes it, evaluator.h runs it).
// Every node keeps the place it was written (SourcePos) for diagnostics.
//
// Expressions are one node type with a kind; list-comprehension elements (for, C-style
// for, if/else, let, each) are expression kinds that may appear only among the
// elements of a vector literal. Statements are assignments, module instantiations
// (including for, let, echo, assert and intersection_for, which OpenSCAD treats as
// modules), if/else, and module and function definitions.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cellforge/csg/source.h"

namespace cellforge::csg {

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

// `name = value` in a call's arguments, let(), for(), or a parameter with its
// default (value null: no default, or a positional argument when name is empty).
struct Binding {
  std::string name;
  ExprPtr value;
  SourcePos pos;
};

enum class ExprKind {
  kNumber,  // number
  kString,  // text
  kBool,    // number != 0
  kUndef,
  kIdent,     // text = name
  kVector,    // items = elements (expressions or list-comprehension elements)
  kRange,     // items = begin, end or begin, step, end
  kUnary,     // text = "-", "+", "!"; items[0]
  kBinary,    // text = operator; items[0], items[1]
  kTernary,   // items = condition, then, else
  kIndex,     // items = object, index
  kMember,    // items[0] . text
  kCall,      // items[0] = callee; args
  kFunction,  // function (params) items[0]
  kLet,       // let (args) items[0]
  kAssert,    // assert (args) items[0] (or no items)
  kEcho,      // echo (args) items[0] (or no items)
  // list-comprehension elements
  kLcFor,   // for (args) items[0]
  kLcForC,  // for (args; items[0]; params) items[1]  (params: the updates)
  kLcIf,    // if (items[0]) items[1] [else items[2]]
  kLcLet,   // let (args) items[0]
  kLcEach,  // each items[0]
};

struct Expr {
  ExprKind kind = ExprKind::kUndef;
  SourcePos pos;
  double number = 0;
  std::string text;
  std::vector<ExprPtr> items;
  std::vector<Binding> args;    // call arguments, let/for/assert/echo bindings
  std::vector<Binding> params;  // function literal parameters; C-style for updates
};

struct Stmt;
using StmtPtr = std::unique_ptr<Stmt>;

enum class StmtKind {
  kAssign,    // name = value
  kInstance,  // name(args) children; modifier
  kIf,        // if (condition) children else else_children
  kBlock,     // { children } with no module (a scope of its own)
  kModule,    // module name(params) body (children)
  kFunction,  // function name(params) = value
};

struct Stmt {
  StmtKind kind = StmtKind::kAssign;
  SourcePos pos;
  std::string name;
  ExprPtr value;                       // kAssign, kFunction; kIf: the condition
  std::vector<Binding> args;           // kInstance
  std::vector<Binding> params;         // kModule, kFunction
  std::vector<StmtPtr> children;       // kInstance, kIf (then), kBlock, kModule (body)
  std::vector<StmtPtr> else_children;  // kIf
  char modifier = 0;                   // '!', '#', '%', '*' or 0
};

// A parsed file: its statements and the include<> / use<> it names. include<> is
// textual in OpenSCAD; the parser records it as a statement position so that the
// evaluator splices the included file's statements in place.
struct Include {
  std::string path;  // as written between < >
  bool use = false;  // use<>: only its modules and functions are imported
  SourcePos pos;
  std::size_t before = 0;  // index into statements where an include<> goes
};

struct File {
  std::uint32_t source = 0;  // index into Sources
  std::vector<StmtPtr> statements;
  std::vector<Include> includes;
};

}  // namespace cellforge::csg
