#pragma once
// Per-element scratch arrays (indexed by vertex, edge or face slot) kept by the passes that run
// every sculpting frame. The mesh grows by a few elements per frame; resizing such an array to the
// exact new size made std::vector reallocate and copy it on the next frame's growth, and a fresh
// array sized exactly at a stroke's start did so on its second stamp (3.5 ms for the brush's five
// arrays on the 35k-vertex bunny). Growing by half again leaves room for many frames' growth.
#include <cstddef>
#include <vector>

namespace adasculpt::mesh {

template <class T, class... Fill>
void resize_scratch(std::vector<T>& v, size_t n, const Fill&... fill) {
  if (n > v.capacity()) v.reserve(n + n / 2 + 16);
  v.resize(n, fill...);
}

}  // namespace adasculpt::mesh
