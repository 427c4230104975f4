// Attachments: data that a layer above topo/ keeps beside a model in the native
// JSON (io/) and the model database (store/) without those layers knowing what it
// means. boolean/'s exact form of a result (boolean/exact.h) is one: it names the
// input models and the expression a result was made from, and only boolean/ can
// read it, while io/ and store/ sit below boolean/ and must not link it.
//
// An attachment is beside the model, not in it: the operators edit a Model without
// knowing its attachments, so an attachment inside it would go stale silently
// after an edit. Whoever holds a model and its attachments writes and reads them
// together (io::WriteOptions::attachments and ReadResult::attachments,
// PutOptions::attachments and Store::get_attachments).
//
// `name` says whose it is ("cellforge.exact"), `version` which layout of the data,
// so that the layer that reads it refuses what it does not know with a clear
// message; `data` is text (valid UTF-8, any bytes but NUL) kept byte for byte.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace cellforge::inline topo {

struct Attachment {
  std::string name;
  int version = 1;
  std::string data;
  friend bool operator==(const Attachment&, const Attachment&) = default;
};

// The first attachment named `name`, or nullptr.
inline const Attachment* find_attachment(const std::vector<Attachment>& all,
                                         std::string_view name) {
  for (const Attachment& a : all)
    if (a.name == name) return &a;
  return nullptr;
}

}  // namespace cellforge::inline topo
