// An immutable array shared by its copies: the read-only face of a std::vector whose buffer is
// owned by a shared pointer, so that models built from the same description hold one copy (a
// pile's identical spheres read one sample set, which stays in cache across the contact sweep).
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace superdex {

template <typename T>
class SharedArray {
 public:
  SharedArray() = default;
  /// Takes the elements; they cannot change afterwards.
  explicit SharedArray(std::vector<T> elements)
      : owner_(std::make_shared<const std::vector<T>>(std::move(elements))),
        data_(owner_->data()),
        size_(owner_->size()) {}

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  const T& front() const { return data_[0]; }
  const T* data() const { return data_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }

  /// Whether both refer to the same buffer (not merely equal elements).
  bool SharesBufferWith(const SharedArray& other) const { return owner_ == other.owner_; }

 private:
  std::shared_ptr<const std::vector<T>> owner_;
  const T* data_ = nullptr;  // owner_'s elements, cached: one indirection in the sample loops
  std::size_t size_ = 0;
};

/// Element-wise equality (not buffer identity).
template <typename T, typename Equal>
bool SameElements(const SharedArray<T>& a, const SharedArray<T>& b, Equal equal) {
  if (a.size() != b.size()) return false;
  if (a.SharesBufferWith(b)) return true;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!equal(a[i], b[i])) return false;
  return true;
}

}  // namespace superdex
