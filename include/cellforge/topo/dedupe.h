// dedupe_stable: removes repeated elements from a query answer, keeping first
// occurrences in order: a quadratic scan for small answers (no allocation), a sort
// for large ones. The 9 queries use it (F->E and F->V only for a face marked as
// repeating an element, model.h), and so do the comparison baselines.
#pragma once

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace cellforge::inline topo {

template <class T>
void dedupe_stable(std::vector<T>& v) {
  if (v.size() <= 2) {  // most answers around an edge: no scan
    if (v.size() == 2 && v[0] == v[1]) v.pop_back();
    return;
  }
  std::size_t n = 0;
  if (v.size() <= 32) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      const auto kept_end = v.begin() + static_cast<std::ptrdiff_t>(n);
      if (std::find(v.begin(), kept_end, v[i]) == kept_end) v[n++] = v[i];
    }
    v.resize(n);
    return;
  }
  std::vector<std::pair<T, std::size_t>> keyed;
  keyed.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) keyed.emplace_back(v[i], i);
  std::sort(keyed.begin(), keyed.end());
  std::vector<char> keep(v.size(), 0);
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first) keep[keyed[i].second] = 1;
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (keep[i]) v[n++] = v[i];
  }
  v.resize(n);
}

// A value that `v` holds twice, or nullptr: a quadratic scan for up to 16
// elements, a sort (which reorders v) for more. The face marks use it (a face's
// edges and vertices, model.h).
template <class T>
const T* find_repeat(std::vector<T>& v) {
  if (v.size() <= 16) {
    for (std::size_t i = 1; i < v.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (v[i] == v[j]) return &v[i];
      }
    }
    return nullptr;
  }
  std::sort(v.begin(), v.end());
  const auto it = std::adjacent_find(v.begin(), v.end());
  return it == v.end() ? nullptr : &*it;
}

}  // namespace cellforge::inline topo
