#pragma once
// Per-element attributes ("properties"): named, typed arrays that grow, shrink and compact
// together with the elements they describe, so algorithms can attach data to a mesh without
// the mesh knowing about them.
#include <algorithm>
#include <cassert>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "mesh/handles.h"

namespace adasculpt::mesh {

class BasePropertyArray {
 public:
  explicit BasePropertyArray(std::string name) : name_(std::move(name)) {}
  virtual ~BasePropertyArray() = default;
  virtual void resize(size_t n) = 0;
  virtual void reserve(size_t n) = 0;
  virtual void push_back() = 0;
  // new[i] = old[kept[i]]: used by garbage collection.
  virtual void compact(const std::vector<Index>& kept) = 0;
  virtual std::unique_ptr<BasePropertyArray> clone() const = 0;
  // Element i occupies bytes [i * element_bytes(), (i + 1) * element_bytes()) of raw(): the undo
  // log (sculpt/undo_log.h) records and restores slots byte for byte. Every property type is
  // trivially copyable (checked in PropertyArray).
  virtual size_t element_bytes() const = 0;
  virtual std::uint8_t* raw() = 0;
  const std::string& name() const { return name_; }

 private:
  std::string name_;
};

template <class T>
class PropertyArray : public BasePropertyArray {
  // std::vector<bool> has no element references; flags are stored as uint8_t instead.
  static_assert(!std::is_same_v<T, bool>, "use std::uint8_t for flag properties");
  static_assert(std::is_trivially_copyable_v<T>, "properties are copied byte for byte (undo log)");

 public:
  PropertyArray(std::string name, T default_value)
      : BasePropertyArray(std::move(name)), default_(std::move(default_value)) {}
  void resize(size_t n) override { data_.resize(n, default_); }
  void reserve(size_t n) override { data_.reserve(n); }
  void push_back() override { data_.push_back(default_); }
  // kept[i]: the old slot of new element i. In increasing order (a garbage collection) in place;
  // in any other order (SurfaceMesh::sort_in_space) through a new array of the same capacity.
  void compact(const std::vector<Index>& kept) override {
    bool increasing = true;
    for (size_t i = 1; i < kept.size() && increasing; ++i) increasing = kept[i - 1] < kept[i];
    if (increasing) {
      for (size_t i = 0; i < kept.size(); ++i)
        if (kept[i] != i) data_[i] = std::move(data_[kept[i]]);
      data_.resize(kept.size());
      return;
    }
    std::vector<T> moved;
    moved.reserve(std::max(data_.capacity(), kept.size()));
    for (Index k : kept) moved.push_back(std::move(data_[k]));
    data_.swap(moved);
  }
  std::unique_ptr<BasePropertyArray> clone() const override {
    return std::make_unique<PropertyArray<T>>(*this);
  }
  size_t element_bytes() const override { return sizeof(T); }
  std::uint8_t* raw() override { return reinterpret_cast<std::uint8_t*>(data_.data()); }
  std::vector<T>& vector() { return data_; }
  const std::vector<T>& vector() const { return data_; }
  const T& default_value() const { return default_; }

 private:
  std::vector<T> data_;
  T default_;
};

// A set of property arrays that all have the same number of elements.
class PropertyContainer {
 public:
  PropertyContainer() = default;
  PropertyContainer(const PropertyContainer& o) : size_(o.size_), capacity_(o.size_) {
    for (const auto& a : o.arrays_) arrays_.push_back(a->clone());
  }
  PropertyContainer& operator=(const PropertyContainer& o) {
    if (this != &o) {
      PropertyContainer copy(o);
      *this = std::move(copy);
    }
    return *this;
  }
  PropertyContainer(PropertyContainer&&) = default;
  PropertyContainer& operator=(PropertyContainer&&) = default;

  template <class T>
  PropertyArray<T>* add(const std::string& name, T default_value) {
    if (find(name)) throw std::logic_error("property '" + name + "' already exists");
    auto arr = std::make_unique<PropertyArray<T>>(name, std::move(default_value));
    arr->reserve(capacity_);  // room for the elements the others have room for (see push_back)
    arr->resize(size_);
    auto* raw = arr.get();
    arrays_.push_back(std::move(arr));
    return raw;
  }
  // As add, with `data` (one element per slot; missing ones get the default) moved in as the
  // array's contents instead of a fill: an algorithm lending its own per-slot array to the mesh
  // pays nothing per slot.
  template <class T>
  PropertyArray<T>* adopt(const std::string& name, std::vector<T>&& data, T default_value) {
    if (find(name)) throw std::logic_error("property '" + name + "' already exists");
    auto arr = std::make_unique<PropertyArray<T>>(name, std::move(default_value));
    arr->vector() = std::move(data);
    arr->reserve(capacity_);
    arr->resize(size_);
    auto* raw = arr.get();
    arrays_.push_back(std::move(arr));
    return raw;
  }
  template <class T>
  PropertyArray<T>* get(const std::string& name) const {
    return dynamic_cast<PropertyArray<T>*>(find(name));
  }
  BasePropertyArray* find(const std::string& name) const {
    for (const auto& a : arrays_)
      if (a->name() == name) return a.get();
    return nullptr;
  }
  void remove(const BasePropertyArray* arr) {
    for (auto it = arrays_.begin(); it != arrays_.end(); ++it)
      if (it->get() == arr) {
        arrays_.erase(it);
        return;
      }
  }
  size_t size() const { return size_; }
  size_t capacity() const { return capacity_; }
  size_t n_arrays() const { return arrays_.size(); }
  BasePropertyArray* array(size_t i) const { return arrays_[i].get(); }
  // A copy of another container's array (same element count), e.g. one an algorithm added to the
  // mesh, into a copy of that mesh.
  void add_clone(const BasePropertyArray& a) {
    if (find(a.name())) throw std::logic_error("property '" + a.name() + "' already exists");
    arrays_.push_back(a.clone());
    arrays_.back()->reserve(capacity_);
  }
  void resize(size_t n) {
    if (n > capacity_) reserve(n);
    for (auto& a : arrays_) a->resize(n);
    size_ = n;
  }
  void reserve(size_t n) {
    if (n <= capacity_) return;
    for (auto& a : arrays_) a->reserve(n);
    capacity_ = n;
  }
  // All arrays grow together, doubling, and an array added later starts with the same room: a
  // sculpting stroke adds the remesher's arrays to a mesh, and each array growing on its own at
  // the stroke's first split copied every array of the mesh in the middle of a frame (13 ms on
  // the 35k-vertex bunny). Doubling, not growing by half: every growth is fresh memory the kernel
  // must fault in, and a whole-mesh remesh that doubles the mesh paid 50 % more of them.
  void push_back() {
    if (size_ == capacity_) reserve(2 * size_ + 16);
    for (auto& a : arrays_) a->push_back();
    ++size_;
  }
  void compact(const std::vector<Index>& kept) {
    for (auto& a : arrays_) a->compact(kept);
    size_ = kept.size();
  }

 private:
  std::vector<std::unique_ptr<BasePropertyArray>> arrays_;
  size_t size_ = 0;
  size_t capacity_ = 0;  // every array has room for this many elements
};

// Typed access to one property array through element handles of type H.
template <class H, class T>
class Property {
 public:
  Property() = default;
  explicit Property(PropertyArray<T>* a) : array_(a) {}
  bool is_valid() const { return array_ != nullptr; }
  T& operator[](H h) {
    assert(h.idx < array_->vector().size());
    return array_->vector()[h.idx];
  }
  const T& operator[](H h) const {
    assert(h.idx < array_->vector().size());
    return array_->vector()[h.idx];
  }
  std::vector<T>& vector() { return array_->vector(); }
  const std::vector<T>& vector() const { return array_->vector(); }
  PropertyArray<T>* array() const { return array_; }

 private:
  PropertyArray<T>* array_ = nullptr;
};

template <class T> using VertexProperty = Property<Vertex, T>;
template <class T> using HalfedgeProperty = Property<Halfedge, T>;
template <class T> using EdgeProperty = Property<Edge, T>;
template <class T> using FaceProperty = Property<Face, T>;

}  // namespace adasculpt::mesh
