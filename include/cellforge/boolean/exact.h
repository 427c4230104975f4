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
//
// Beside a rounded model, the exact form travels as an attachment (topo/attachment.h,
// name "cellforge.exact", version 1, data the text of exact_to_string), which the
// native JSON and the model database keep byte for byte without knowing what it is:
// io/ and store/ sit below boolean/, so boolean/ alone writes and reads it.
//
//   io::write_file(r.model, "r.json", {.attachments = {boolean::exact_attachment(*r.exact)}});
//   store.put("part", r.model, {.attachments = {boolean::exact_attachment(*r.exact)}});
//   auto form = boolean::find_exact(store.get_attachments("part").value());  // or read_result
#pragma once
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cellforge/boolean/boolean.h"
#include "cellforge/topo/attachment.h"

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

// How deep an exact form's expression may nest (a step of a chain adds a level at
// most): deeper forms are refused by chain() and by the reader, whose recursion must
// stay well inside a thread's stack.
inline constexpr int kMaxExactDepth = 2000;

// evaluate() over operands that may be earlier results; the result carries its exact
// form (BooleanResult::exact). Inputs shared by several operands are one input.
// An error (kUnsupported) when the expression would nest deeper than kMaxExactDepth.
Result<BooleanResult> chain(std::span<const Operand> operands, const Expr& expr,
                            const Options& options = {});

// A step of a chain without evaluating it: the exact form that chain() evaluates
// (the same errors). A program that needs only the chain's last result composes the
// steps and evaluates once, one arrangement of all inputs:
//
//   auto f1 = boolean::compose({Operand::of(a), Operand::of(b)}, Expr::over(Op::kDifference, 2));
//   auto f2 = boolean::compose({Operand::of(*f1), Operand::of(c)}, Expr::over(Op::kUnion, 2));
//   auto r = boolean::evaluate(**f2);  // (a - b) u c, as chain() gives it at its last step
Result<std::shared_ptr<const ExactForm>> compose(std::span<const Operand> operands, const Expr& expr);

// The exact form as text: a header, the expression as an s-expression
// ("(difference (union 0 1) 2)"), and each input as native JSON with its byte length.
std::string exact_to_string(const ExactForm& form);
// Errors name the line or the byte offset and what was expected.
Result<std::shared_ptr<const ExactForm>> exact_from_string(std::string_view text);
Status write_exact(const ExactForm& form, const std::string& path);
Result<std::shared_ptr<const ExactForm>> read_exact(const std::string& path);

// The exact form as an attachment, and back. The name and version are checked
// (another version is refused, naming it); an error in the data names the byte
// (in the data) and what was expected.
inline constexpr const char* kExactAttachment = "cellforge.exact";
inline constexpr int kExactAttachmentVersion = 1;
Attachment exact_attachment(const ExactForm& form);
Result<std::shared_ptr<const ExactForm>> exact_from_attachment(const Attachment& attachment);
// The exact form among a model's attachments: nullptr when there is none, an
// error when the one there cannot be read.
Result<std::shared_ptr<const ExactForm>> find_exact(const std::vector<Attachment>& attachments);

// A result as a native JSON file: the rounded model, and its exact form (when it
// has one) as an attachment.
Status write_result(const BooleanResult& result, const std::string& path);
// A native JSON file (or any format io/ reads) as a chain operand: its model, and
// the exact form the file keeps, if any. An error names the file.
Result<BooleanResult> read_result(const std::string& path);

// Re-evaluates an exact form (what reading a saved chain gives back).
Result<BooleanResult> evaluate(const ExactForm& form, const Options& options = {});

}  // namespace cellforge::boolean
