// Chains of Booleans that stay exact: a result remembers how it was made, and a
// Boolean on it evaluates that inside its own expression, over the same inputs, in one
// arrangement, so that a chain is rounded once, at its end (DESIGN.md: the CSG
// expression above the B-rep; issue 16, "exact chains").
//
//   auto r1 = boolean::chain({Operand::of(a), Operand::of(b)}, Expr::over(Op::kDifference, 2));
//   auto r2 = boolean::chain({Operand::of(*r1), Operand::of(c)}, Expr::over(Op::kUnion, 2));
//   // r2 is (a - b) u c evaluated at once from a, b and c: nothing was rounded between.
//
// The exact form is the input models, with their doubles as they were, and the
// expression over them. write_exact and read_exact store it losslessly (each input in
// the native JSON, which keeps every double bit for bit), so that a chain saved and
// reloaded between steps gives the result it gives in one run, bit for bit.
#pragma once
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cellforge/boolean/boolean.h"

namespace cellforge::boolean {

struct ExactForm {
  std::vector<std::shared_ptr<const Model>> inputs;
  Expr expr;  // over inputs 0..n-1
};

// An operand of a chain: a model (copied into the exact form), or an earlier result
// with its exact form (a result without one counts as its rounded model).
struct Operand {
  std::shared_ptr<const Model> model;
  std::shared_ptr<const ExactForm> exact;
  static Operand of(const Model& m);
  static Operand of(const BooleanResult& r);
  static Operand of(std::shared_ptr<const ExactForm> form);
};

// evaluate() over operands that may be earlier results; the result carries its exact
// form (BooleanResult::exact). Inputs shared by several operands are one input.
Result<BooleanResult> chain(std::span<const Operand> operands, const Expr& expr,
                            const Options& options = {});

// The exact form as text: a header, the expression as an s-expression
// ("(difference (union 0 1) 2)"), and each input as native JSON with its byte length.
std::string exact_to_string(const ExactForm& form);
// Errors name the line or the byte offset and what was expected.
Result<std::shared_ptr<const ExactForm>> exact_from_string(std::string_view text);
Status write_exact(const ExactForm& form, const std::string& path);
Result<std::shared_ptr<const ExactForm>> read_exact(const std::string& path);

// Re-evaluates an exact form (what reading a saved chain gives back).
Result<BooleanResult> evaluate(const ExactForm& form, const Options& options = {});

}  // namespace cellforge::boolean
