// The Expansion value class: each operation runs a kernel into scratch space, then
// compresses the result (so chains of operations stay short) and stores it inline
// when it fits.
#include "cellforge/geom/expansion.h"

#include <algorithm>
#include <cstddef>

#include "geom/expansion_kernels.h"

namespace cellforge::inline geom {

namespace {

namespace k = expansion_kernels;

// Scratch space of n doubles: on the stack when small, else on the heap.
class Scratch {
 public:
  explicit Scratch(std::size_t n)
      : heap_(n > kLocal ? std::make_unique_for_overwrite<double[]>(n) : nullptr) {}
  double* data() { return heap_ ? heap_.get() : local_; }

 private:
  static constexpr std::size_t kLocal = 128;
  std::unique_ptr<double[]> heap_;
  double local_[kLocal];
};

}  // namespace

Expansion::Expansion(double d) {
  if (d != 0) inline_[size_++] = d;
}

Expansion::Expansion(std::span<const double> components) { assign(components); }

Expansion::Expansion(const Expansion& other) { assign(other.components()); }

Expansion::Expansion(Expansion&& other) noexcept
    : heap_(std::move(other.heap_)), size_(other.size_) {
  if (!heap_) std::copy(other.inline_, other.inline_ + size_, inline_);
  other.size_ = 0;
}

Expansion& Expansion::operator=(const Expansion& other) {
  if (this != &other) assign(other.components());
  return *this;
}

Expansion& Expansion::operator=(Expansion&& other) noexcept {
  if (this == &other) return *this;
  heap_ = std::move(other.heap_);
  size_ = other.size_;
  if (!heap_) std::copy(other.inline_, other.inline_ + size_, inline_);
  other.size_ = 0;
  return *this;
}

void Expansion::assign(std::span<const double> components) {
  const auto n = static_cast<std::uint32_t>(components.size());
  heap_ = n > kInline ? std::make_unique_for_overwrite<double[]>(n) : nullptr;
  size_ = n;
  std::copy(components.begin(), components.end(), data());
}

double Expansion::estimate() const { return k::estimate(components()); }

Expansion operator+(const Expansion& a, const Expansion& b) {
  Scratch h(a.size_ + b.size_);
  const int n = k::compress(h.data(), k::sum(a.components(), b.components(), h.data()));
  return Expansion(std::span<const double>(h.data(), n));
}

Expansion operator-(const Expansion& a) {
  Expansion r(a);
  for (std::uint32_t i = 0; i < r.size_; ++i) r.data()[i] = -r.data()[i];
  return r;
}

Expansion operator-(const Expansion& a, const Expansion& b) { return a + -b; }

Expansion operator*(const Expansion& a, const Expansion& b) {
  const std::size_t out = 2 * std::size_t{a.size_} * b.size_;
  Scratch h(out);
  Scratch scratch(out + 2 * std::max(a.size_, b.size_));
  const int n =
      k::compress(h.data(), k::product(a.components(), b.components(), h.data(), scratch.data()));
  return Expansion(std::span<const double>(h.data(), n));
}

}  // namespace cellforge::inline geom
