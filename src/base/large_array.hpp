// LargeArray<T>: the one type for the mesh's big arrays (tens of MiB, written once in scattered
// order). It owns the page policy (base/memory.hpp): a buffer it allocates is advised for huge
// pages before its elements are written, and the advice is taken back before the buffer is freed,
// so that no algorithm calls the OS's memory interfaces itself.
#pragma once
#include <cstddef>
#include <initializer_list>
#include <iterator>
#include <utility>
#include <vector>
#include "base/memory.hpp"

namespace fdr {

template <class T>
class LargeArray {
 public:
  using value_type = T;
  using iterator = typename std::vector<T>::iterator;
  using const_iterator = typename std::vector<T>::const_iterator;

  LargeArray() = default;
  explicit LargeArray(std::size_t n, const T& x = T()) { assign(n, x); }
  LargeArray(std::initializer_list<T> xs) : v_(xs) {}
  // Adopts a vector's buffer (no advice: its pages may be written already).
  explicit LargeArray(std::vector<T>&& v) : v_(std::move(v)) {}
  LargeArray(LargeArray&&) noexcept = default;
  LargeArray& operator=(LargeArray&& o) noexcept {
    if (this != &o) {
      release();
      v_ = std::move(o.v_);
    }
    return *this;
  }
  LargeArray(const LargeArray& o) { *this = o; }
  LargeArray& operator=(const LargeArray& o) {
    if (this != &o) {
      reserve(o.size());
      v_.assign(o.v_.begin(), o.v_.end());
    }
    return *this;
  }
  ~LargeArray() { unadvise_huge_pages(v_); }

  // A new buffer of n elements, advised before it is written (a buffer that holds n stays).
  void assign(std::size_t n, const T& x) { assign_huge(v_, n, x); }
  template <std::input_iterator It>
  void assign(It first, It last) {
    reserve(static_cast<std::size_t>(std::distance(first, last)));
    v_.assign(first, last);
  }
  void reserve(std::size_t n) { reserve_huge(v_, n); }
  void resize(std::size_t n) { resize_huge(v_, n); }
  void resize(std::size_t n, const T& x) {
    reserve_huge(v_, n);
    v_.resize(n, x);
  }
  // Growth by doubling through reserve(), so that every buffer it moves to is advised.
  void push_back(const T& x) {
    grow_for_one();
    v_.push_back(x);
  }
  template <class... A>
  T& emplace_back(A&&... a) {
    grow_for_one();
    return v_.emplace_back(std::forward<A>(a)...);
  }
  void pop_back() { v_.pop_back(); }
  void clear() { v_.clear(); }
  // Frees the buffer, its advice taken back first.
  void release() { release_huge(v_); }
  // Hands the buffer over as a plain vector (its advice stays with the pages until freed).
  std::vector<T> take() && { return std::move(v_); }
  void swap(LargeArray& o) noexcept { v_.swap(o.v_); }

  T& operator[](std::size_t i) { return v_[i]; }
  const T& operator[](std::size_t i) const { return v_[i]; }
  T* data() { return v_.data(); }
  const T* data() const { return v_.data(); }
  T& back() { return v_.back(); }
  const T& back() const { return v_.back(); }
  std::size_t size() const { return v_.size(); }
  std::size_t capacity() const { return v_.capacity(); }
  bool empty() const { return v_.empty(); }
  iterator begin() { return v_.begin(); }
  iterator end() { return v_.end(); }
  const_iterator begin() const { return v_.begin(); }
  const_iterator end() const { return v_.end(); }
  friend bool operator==(const LargeArray& a, const LargeArray& b) { return a.v_ == b.v_; }

 private:
  void grow_for_one() {
    if (v_.size() == v_.capacity()) reserve(v_.capacity() < 8 ? 16 : 2 * v_.capacity());
  }
  std::vector<T> v_;
};

}  // namespace fdr
