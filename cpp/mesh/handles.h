#pragma once
// Typed element handles of a SurfaceMesh. A handle is an index into the mesh's arrays; the
// distinct types keep a vertex index from ever being passed where a face is expected.
#include <cstdint>
#include <functional>
#include <limits>

namespace adasculpt::mesh {

using Index = std::uint32_t;
constexpr Index kInvalidIndex = std::numeric_limits<Index>::max();

template <class Tag>
struct Handle {
  Index idx = kInvalidIndex;
  constexpr Handle() = default;
  constexpr explicit Handle(Index i) : idx(i) {}
  constexpr bool is_valid() const { return idx != kInvalidIndex; }
  constexpr bool operator==(Handle o) const { return idx == o.idx; }
  constexpr bool operator!=(Handle o) const { return idx != o.idx; }
  constexpr bool operator<(Handle o) const { return idx < o.idx; }
};

struct VertexTag {};
struct HalfedgeTag {};
struct EdgeTag {};
struct FaceTag {};
using Vertex = Handle<VertexTag>;
using Halfedge = Handle<HalfedgeTag>;
using Edge = Handle<EdgeTag>;
using Face = Handle<FaceTag>;

}  // namespace adasculpt::mesh

template <class Tag>
struct std::hash<adasculpt::mesh::Handle<Tag>> {
  size_t operator()(adasculpt::mesh::Handle<Tag> h) const noexcept { return std::hash<std::uint32_t>()(h.idx); }
};
