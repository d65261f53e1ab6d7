#include "sculpt/undo_log.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "mesh/vertex_mask.h"
#include "sculpt/byte_io.h"

namespace adasculpt::sculpt {

using mesh::BasePropertyArray;
using mesh::PropertyContainer;
using mesh::SurfaceMesh;
using mesh::Vertex;
using byte_io::put;
using byte_io::put_bytes;
using byte_io::put_name;
using Reader = byte_io::Reader;
using byte_io::fail;

namespace {

enum Kind { kVertex = 0, kHalfedge = 1, kEdge = 2, kFace = 3 };
// Rings around the touched vertices that are compared (see the header).
constexpr int kRings = 2;

// The mesh's own arrays (positions, connectivity, deletion marks: names "v:...", "h:...", "e:...",
// "f:..."). Only these are logged: the arrays algorithms attach (the remesher's sizing, classes,
// hints) are caches they rebuild, and get their default values in slots a redo brings back.
bool builtin(const std::string& name) { return name.size() > 2 && name[1] == ':'; }

// The containers are only read through a const mesh; raw() is non-const because the same arrays
// are written when a step is undone.
PropertyContainer& container(const SurfaceMesh& m, int k) {
  auto& mm = const_cast<SurfaceMesh&>(m);
  switch (k) {
    case kVertex: return mm.vertex_properties();
    case kHalfedge: return mm.halfedge_properties();
    case kEdge: return mm.edge_properties();
    default: return mm.face_properties();
  }
}

BasePropertyArray* find_array(const PropertyContainer& c, const std::string& name, size_t bytes) {
  BasePropertyArray* a = c.find(name);
  return a && a->element_bytes() == bytes ? a : nullptr;
}

size_t slot_bytes(const PropertyContainer& c) {
  size_t b = 0;
  for (size_t i = 0; i < c.n_arrays(); ++i) b += c.array(i)->element_bytes();
  return b;
}

size_t mesh_heap_bytes(const SurfaceMesh& m) {
  size_t b = 0;
  for (int k = 0; k < UndoLog::kKinds; ++k) b += container(m, k).size() * slot_bytes(container(m, k));
  return b;
}

// The arrays of the mesh and of the shadow with the same name, side by side.
struct ArrayPair {
  BasePropertyArray* mesh;
  BasePropertyArray* shadow;
  size_t bytes;
};
std::vector<ArrayPair> pairs_of(const PropertyContainer& m, const PropertyContainer& s) {
  std::vector<ArrayPair> out;
  for (size_t i = 0; i < m.n_arrays(); ++i) {
    BasePropertyArray* a = m.array(i);
    if (!builtin(a->name())) continue;
    if (BasePropertyArray* b = find_array(s, a->name(), a->element_bytes())) out.push_back({a, b, a->element_bytes()});
  }
  return out;
}

// Copies slots [lo, hi) and the listed slots of every array from the mesh to the shadow.
void copy_to_shadow(const PropertyContainer& m, PropertyContainer& s, const std::vector<std::uint32_t>& slots,
                    size_t lo, size_t hi) {
  if (m.size() > s.capacity()) s.reserve(2 * m.size());  // grows like the mesh: not a copy per step
  if (s.size() != m.size()) s.resize(m.size());
  for (const ArrayPair& p : pairs_of(m, s)) {
    const std::uint8_t* from = p.mesh->raw();
    std::uint8_t* to = p.shadow->raw();
    for (std::uint32_t i : slots) std::memcpy(to + i * p.bytes, from + i * p.bytes, p.bytes);
    if (hi > lo) std::memcpy(to + lo * p.bytes, from + lo * p.bytes, (hi - lo) * p.bytes);
  }
}

bool deleted_flag(const SurfaceMesh& m, int k, std::uint32_t i) {
  switch (k) {
    case kVertex: return m.is_deleted(Vertex(i));
    case kEdge: return m.is_deleted(mesh::Edge(i));
    case kFace: return m.is_deleted(mesh::Face(i));
    default: return false;
  }
}
size_t deleted_count(const SurfaceMesh::DeletedCounts& c, int k) {
  return k == kVertex ? c.vertices : k == kEdge ? c.edges : k == kFace ? c.faces : 0;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
struct UndoLog::Step {
  struct Values {
    std::string name;
    std::uint32_t bytes = 0;
    std::vector<std::uint8_t> data;
  };
  // One kind of element. The step holds one of its two states (before it while on the undo list,
  // after it while on the redo list); the mesh is in the other.
  struct Block {
    std::uint32_t size_held = 0;         // slot count in the held state
    std::vector<std::uint32_t> slots;    // changed slots below both states' slot counts
    std::vector<Values> values;          // per array: the held state's bytes of `slots`
    std::vector<Values> tail;            // per array: slots [current count, size_held) when the held state has more
  };
  Block blocks[kKinds];
  SurfaceMesh::DeletedCounts deleted_held;
  std::unique_ptr<SurfaceMesh> whole;  // a whole-mesh step: the held mesh

  size_t bytes() const {
    if (whole) return mesh_heap_bytes(*whole);
    size_t b = sizeof(Step);
    for (const Block& k : blocks) {
      b += k.slots.size() * 4;
      for (const Values& v : k.values) b += v.data.size() + v.name.size() + sizeof(Values);
      for (const Values& v : k.tail) b += v.data.size() + v.name.size() + sizeof(Values);
    }
    return b;
  }
};

UndoLog::UndoLog() = default;
UndoLog::~UndoLog() = default;
UndoLog::UndoLog(UndoLog&&) noexcept = default;
UndoLog& UndoLog::operator=(UndoLog&&) noexcept = default;

void UndoLog::reset(const SurfaceMesh& m) {
  changed_known_ = false;
  shadow_ = std::make_unique<SurfaceMesh>(m);
  sync_arrays(*shadow_);
  // Room for the first strokes and the stamps of commit_local, now (with the copy) rather than in
  // the first stroke.
  shadow_->reserve_room_for_edits();
  for (int k = 0; k < kKinds; ++k) {
    const size_t n = container(m, k).size();
    stamp_[k].assign(n + n / 4, 0u);
  }
  epoch_ = 0;
  undo_.clear();
  redo_.clear();
  undo_bytes_ = 0;
}

void UndoLog::set_limits(size_t max_steps, size_t max_bytes) {
  max_steps_ = max_steps;
  max_bytes_ = max_bytes;
  enforce_limits();
}

void UndoLog::enforce_limits() {
  while (undo_.size() > max_steps_ || (undo_.size() > 1 && undo_bytes_ > max_bytes_)) {
    undo_bytes_ -= undo_.front()->bytes();
    undo_.pop_front();
  }
}

size_t UndoLog::history_bytes() const {
  size_t b = undo_bytes_;
  for (const auto& s : redo_) b += s->bytes();
  return b;
}
size_t UndoLog::shadow_bytes() const { return shadow_ ? mesh_heap_bytes(*shadow_) : 0; }

// The shadow holds the mesh's built-in arrays only (see builtin()).
void UndoLog::sync_arrays(SurfaceMesh& m) {
  for (int k = 0; k < kKinds; ++k) {
    PropertyContainer& sc = container(*shadow_, k);
    for (size_t i = sc.n_arrays(); i-- > 0;)
      if (!builtin(sc.array(i)->name()) || !container(m, k).find(sc.array(i)->name())) sc.remove(sc.array(i));
  }
}

bool UndoLog::commit_local(const SurfaceMesh& m, const std::vector<Vertex>& touched) {
  SurfaceMesh& S = *shadow_;
  sync_arrays(const_cast<SurfaceMesh&>(m));
  for (int k = 0; k < kKinds; ++k)
    if (container(m, k).size() < container(S, k).size()) {  // slots went away: only a whole step can say how
      commit_whole(m);
      return true;
    }
  if (++epoch_ == 0) {
    for (auto& s : stamp_) std::fill(s.begin(), s.end(), 0u);
    epoch_ = 1;
  }
  for (int k = 0; k < kKinds; ++k) {
    candidates_[k].clear();
    if (stamp_[k].size() < container(m, k).size()) stamp_[k].resize(container(m, k).size() + container(m, k).size() / 4, 0u);
  }
  auto add = [&](int k, std::uint32_t i) {
    if (i < stamp_[k].size() && stamp_[k][i] != epoch_) {
      stamp_[k][i] = epoch_;
      candidates_[k].push_back(i);
    }
  };
  auto alive = [](const SurfaceMesh& x, Vertex v) {
    return v.idx < x.vertices_size() && !x.is_deleted(v) && !x.is_isolated(v);
  };
  auto newly_deleted = [&](Vertex v) {
    return v.idx < S.vertices_size() && !S.is_deleted(v) && (v.idx >= m.vertices_size() || m.is_deleted(v));
  };
  // Vertices: the touched ones, their rings before and after, and chains of deleted vertices.
  for (Vertex v : touched) add(kVertex, v.idx);
  size_t ring_end = candidates_[kVertex].size();
  for (int ring = 0; ring < kRings; ++ring) {
    const size_t ring_begin = ring == 0 ? 0 : ring_end;
    ring_end = candidates_[kVertex].size();
    for (size_t i = ring_begin; i < ring_end; ++i) {
      const Vertex v(candidates_[kVertex][i]);
      if (alive(m, v))
        for (Vertex w : m.vertices(v)) add(kVertex, w.idx);
      if (alive(S, v))
        for (Vertex w : S.vertices(v)) add(kVertex, w.idx);
    }
  }
  for (size_t i = 0; i < candidates_[kVertex].size(); ++i) {
    const Vertex v(candidates_[kVertex][i]);
    if (newly_deleted(v) && alive(S, v))
      for (Vertex w : S.vertices(v)) add(kVertex, w.idx);
  }
  // Edges, halfedges and faces around them, before and after.
  for (std::uint32_t vi : candidates_[kVertex]) {
    for (const SurfaceMesh* x : {&m, static_cast<const SurfaceMesh*>(&S)}) {
      const Vertex v(vi);
      if (!alive(*x, v)) continue;
      for (mesh::Halfedge h : x->halfedges(v)) {
        add(kEdge, SurfaceMesh::edge(h).idx);
        add(kEdge, SurfaceMesh::edge(x->next(h)).idx);
        add(kEdge, SurfaceMesh::edge(x->prev(h)).idx);
        if (x->face(h).is_valid()) add(kFace, x->face(h).idx);
        const mesh::Face g = x->face(SurfaceMesh::opposite(h));
        if (g.is_valid()) add(kFace, g.idx);
      }
    }
  }
  for (std::uint32_t e : candidates_[kEdge]) {
    add(kHalfedge, 2 * e);
    add(kHalfedge, 2 * e + 1);
  }

  auto step = std::make_unique<Step>();
  std::vector<std::uint32_t> changed[kKinds];
  std::vector<ArrayPair> pairs[kKinds];
  auto diff = [&](int k, bool everything) {
    const size_t before = container(S, k).size();
    changed[k].clear();
    auto differs = [&](std::uint32_t i) {
      for (const ArrayPair& p : pairs[k])
        if (std::memcmp(p.mesh->raw() + i * p.bytes, p.shadow->raw() + i * p.bytes, p.bytes) != 0) return true;
      return false;
    };
    if (everything) {
      for (std::uint32_t i = 0; i < before; ++i)
        if (differs(i)) changed[k].push_back(i);
    } else {
      for (std::uint32_t i : candidates_[k])
        if (i < before && differs(i)) changed[k].push_back(i);
    }
  };
  // Deletions found (net, appended slots included) against the counters: a miss means a change
  // outside the neighbourhood, and then everything is compared.
  auto deletions_found = [&](int k) {
    long found = 0;
    for (std::uint32_t i : changed[k]) found += long(deleted_flag(m, k, i)) - long(deleted_flag(S, k, i));
    for (std::uint32_t i = std::uint32_t(container(S, k).size()); i < container(m, k).size(); ++i)
      found += deleted_flag(m, k, i);
    return found;
  };
  bool complete = true;
  for (int k = 0; k < kKinds; ++k) {
    pairs[k] = pairs_of(container(m, k), container(S, k));
    diff(k, false);
    if (k != kHalfedge && deletions_found(k) != long(deleted_count(m.deleted_counts(), k)) -
                                                    long(deleted_count(S.deleted_counts(), k)))
      complete = false;
  }
  if (!complete) {
    ++full_diffs_;
    for (int k = 0; k < kKinds; ++k) diff(k, true);
  }

  bool any = false;
  for (int k = 0; k < kKinds; ++k) {
    Step::Block& b = step->blocks[k];
    const PropertyContainer& sc = container(S, k);
    b.size_held = std::uint32_t(sc.size());
    any = any || !changed[k].empty() || container(m, k).size() != sc.size();
    b.slots = changed[k];
    for (const ArrayPair& p : pairs[k]) {
      Step::Values v{p.mesh->name(), std::uint32_t(p.bytes), {}};
      v.data.resize(b.slots.size() * p.bytes);
      for (size_t j = 0; j < b.slots.size(); ++j)
        std::memcpy(v.data.data() + j * p.bytes, p.shadow->raw() + size_t(b.slots[j]) * p.bytes, p.bytes);
      b.values.push_back(std::move(v));
    }
  }
  (void)any;  // a stroke that changed nothing is still a step: undo takes back "the stroke"
  note_changed_vertices(changed[kVertex], container(S, kVertex).size(), m.vertices_size());
  step->deleted_held = S.deleted_counts();
  for (int k = 0; k < kKinds; ++k)
    copy_to_shadow(container(m, k), container(S, k), changed[k], container(S, k).size(), container(m, k).size());
  S.set_deleted_counts(m.deleted_counts());
  if (verify_) check_shadow(m);
  undo_bytes_ += step->bytes();
  undo_.push_back(std::move(step));
  redo_.clear();
  enforce_limits();
  return true;
}

void UndoLog::note_changed_vertices(const std::vector<std::uint32_t>& slots, size_t appended_from, size_t appended_to) {
  changed_vertices_.clear();
  for (std::uint32_t i : slots) changed_vertices_.push_back(Vertex(i));
  for (size_t i = appended_from; i < appended_to; ++i) changed_vertices_.push_back(Vertex(mesh::Index(i)));
  changed_known_ = true;
}

void UndoLog::commit_whole(const SurfaceMesh& m) {
  changed_known_ = false;
  auto step = std::make_unique<Step>();
  step->whole = std::move(shadow_);
  shadow_ = std::make_unique<SurfaceMesh>(m);
  sync_arrays(*shadow_);
  undo_bytes_ += step->bytes();
  undo_.push_back(std::move(step));
  redo_.clear();
  enforce_limits();
}

void UndoLog::adopt_new_arrays(const SurfaceMesh& m) {
  for (int k = 0; k < kKinds; ++k) {
    const PropertyContainer& mc = container(m, k);
    PropertyContainer& sc = container(*shadow_, k);
    for (size_t i = 0; i < mc.n_arrays(); ++i) {
      const BasePropertyArray* a = mc.array(i);
      if (builtin(a->name()) && !sc.find(a->name())) sc.add_clone(*a);
    }
  }
}

bool UndoLog::swap_step(Step& s, SurfaceMesh& m, std::vector<Vertex>* touched, bool* whole,
                        std::vector<mesh::Face>* faces) {
  if (s.whole) {
    changed_known_ = false;
    std::swap(m, *s.whole);
    *shadow_ = m;
    sync_arrays(*shadow_);
    if (whole) *whole = true;
    return true;
  }
  if (whole) *whole = false;
  // Check everything the step will index before changing anything (a step read from a file).
  for (int k = 0; k < kKinds; ++k) {
    const Step::Block& b = s.blocks[k];
    const size_t lo = std::min<size_t>(b.size_held, container(m, k).size());
    for (std::uint32_t i : b.slots)
      if (i >= lo) fail("a step changes a slot the mesh does not have");
    for (const Step::Values& v : b.values)
      if (v.data.size() != b.slots.size() * size_t(v.bytes)) fail("a step's values do not match its slots");
    if (b.size_held > container(m, k).size())
      for (const Step::Values& v : b.tail)
        if (v.data.size() != (b.size_held - container(m, k).size()) * size_t(v.bytes)) fail("a step's new slots are cut");
  }
  sync_arrays(m);
  std::vector<std::uint32_t> regrown[kKinds];
  for (int k = 0; k < kKinds; ++k) {
    PropertyContainer& c = container(m, k);
    Step::Block& b = s.blocks[k];
    for (Step::Values& v : b.values) {
      BasePropertyArray* a = find_array(c, v.name, v.bytes);
      if (!a) continue;  // an array the mesh no longer has
      std::uint8_t* raw = a->raw();
      for (size_t j = 0; j < b.slots.size(); ++j)
        std::swap_ranges(raw + size_t(b.slots[j]) * v.bytes, raw + size_t(b.slots[j] + 1) * v.bytes,
                         v.data.data() + j * v.bytes);
    }
    const size_t current = c.size(), target = b.size_held;
    if (current > target) {  // undo: the slots the step appended go into the step
      b.tail.clear();
      for (size_t i = 0; i < c.n_arrays(); ++i) {
        BasePropertyArray* a = c.array(i);
        if (!builtin(a->name())) continue;
        const size_t eb = a->element_bytes();
        b.tail.push_back({a->name(), std::uint32_t(eb),
                          std::vector<std::uint8_t>(a->raw() + target * eb, a->raw() + current * eb)});
      }
      c.resize(target);
    } else if (current < target) {  // redo: they come back
      c.resize(target);
      for (const Step::Values& v : b.tail)
        if (BasePropertyArray* a = find_array(c, v.name, v.bytes))
          std::memcpy(a->raw() + current * v.bytes, v.data.data(), v.data.size());
      b.tail.clear();
      b.tail.shrink_to_fit();
    }
    b.size_held = std::uint32_t(current);
    for (std::uint32_t i = std::uint32_t(current); i < target; ++i) regrown[k].push_back(i);
    copy_to_shadow(c, container(*shadow_, k), b.slots, std::min(current, target), c.size());
  }
  const SurfaceMesh::DeletedCounts d = m.deleted_counts();
  m.set_deleted_counts(s.deleted_held);
  s.deleted_held = d;
  shadow_->set_deleted_counts(m.deleted_counts());
  if (verify_) check_shadow(m);

  note_changed_vertices(s.blocks[kVertex].slots, regrown[kVertex].empty() ? 0 : regrown[kVertex].front(),
                        regrown[kVertex].empty() ? 0 : regrown[kVertex].back() + 1);
  if (faces) {
    for (int part = 0; part < 2; ++part)
      for (std::uint32_t i : part ? regrown[kFace] : s.blocks[kFace].slots) faces->push_back(mesh::Face(i));
  }
  if (touched) {
    auto add = [&](Vertex v) {
      if (v.is_valid() && v.idx < m.vertices_size() && !m.is_deleted(v)) touched->push_back(v);
    };
    for (int part = 0; part < 2; ++part) {
      const std::vector<std::uint32_t>& vs = part ? regrown[kVertex] : s.blocks[kVertex].slots;
      for (std::uint32_t i : vs) add(Vertex(i));
      const std::vector<std::uint32_t>& hs = part ? regrown[kHalfedge] : s.blocks[kHalfedge].slots;
      for (std::uint32_t i : hs)
        if (i < m.halfedges_size() && !m.is_deleted(mesh::Halfedge(i))) {
          add(m.to_vertex(mesh::Halfedge(i)));
          add(m.from_vertex(mesh::Halfedge(i)));
        }
    }
  }
  return true;
}

bool UndoLog::undo(SurfaceMesh& m, std::vector<Vertex>* touched, bool* whole, std::vector<mesh::Face>* faces) {
  if (undo_.empty()) return false;
  Step& s = *undo_.back();
  undo_bytes_ -= s.bytes();
  try {
    swap_step(s, m, touched, whole, faces);
  } catch (...) {
    undo_bytes_ += s.bytes();
    throw;
  }
  redo_.push_back(std::move(undo_.back()));
  undo_.pop_back();
  return true;
}

bool UndoLog::redo(SurfaceMesh& m, std::vector<Vertex>* touched, bool* whole, std::vector<mesh::Face>* faces) {
  if (redo_.empty()) return false;
  swap_step(*redo_.back(), m, touched, whole, faces);
  undo_bytes_ += redo_.back()->bytes();
  undo_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  return true;
}

void UndoLog::check_shadow(const SurfaceMesh& m) const {
  for (int k = 0; k < kKinds; ++k) {
    const PropertyContainer& mc = container(m, k);
    const PropertyContainer& sc = container(*shadow_, k);
    if (mc.size() != sc.size()) throw std::logic_error("undo log: the shadow has another slot count");
    for (const ArrayPair& p : pairs_of(mc, sc))
      for (size_t i = 0; i < mc.size(); ++i)
        if (std::memcmp(p.mesh->raw() + i * p.bytes, p.shadow->raw() + i * p.bytes, p.bytes) != 0)
          throw std::logic_error("undo log: the shadow differs from the mesh in '" + p.mesh->name() + "', slot " +
                                 std::to_string(i));
  }
  const auto a = m.deleted_counts(), b = shadow_->deleted_counts();
  if (a.vertices != b.vertices || a.edges != b.edges || a.faces != b.faces)
    throw std::logic_error("undo log: the shadow has other deletion counts");
}

// ---------------------------------------------------------------------------------------------
// Persistence. A whole mesh is written as its slots (the built-in arrays), a local step as its
// blocks.
namespace {

void write_values(std::vector<std::uint8_t>& out, const std::vector<UndoLog::Step::Values>& vs) {
  put(out, std::uint32_t(vs.size()));
  for (const auto& v : vs) {
    put_name(out, v.name);
    put(out, v.bytes);
    put_bytes(out, v.data);
  }
}
std::vector<UndoLog::Step::Values> read_values(Reader& r) {
  const std::uint32_t n = r.get<std::uint32_t>();
  if (n > 64) fail("too many arrays");
  std::vector<UndoLog::Step::Values> vs(n);
  for (auto& v : vs) {
    v.name = r.name();
    v.bytes = r.get<std::uint32_t>();
    if (v.bytes == 0 || v.bytes > 64) fail("bad element size");
    const std::uint64_t size = r.get<std::uint64_t>();
    if (size % v.bytes) fail("bad array size");
    v.data = r.bytes(size_t(size));
  }
  return vs;
}
void write_counts(std::vector<std::uint8_t>& out, const SurfaceMesh::DeletedCounts& c) {
  put(out, std::uint64_t(c.vertices));
  put(out, std::uint64_t(c.edges));
  put(out, std::uint64_t(c.faces));
}
SurfaceMesh::DeletedCounts read_counts(Reader& r) {
  SurfaceMesh::DeletedCounts c;
  c.vertices = size_t(r.get<std::uint64_t>());
  c.edges = size_t(r.get<std::uint64_t>());
  c.faces = size_t(r.get<std::uint64_t>());
  return c;
}
// Mask values outside [0, 1] (NaN included) would let a brush push a vertex the wrong way.
void check_mask_values(const SurfaceMesh& m, const char* where) {
  const mesh::VertexProperty<float> mask = mesh::find_mask(m);
  if (!mask.is_valid()) return;
  for (Vertex v : m.vertices())
    if (!(mask[v] >= 0.0f && mask[v] <= 1.0f)) fail(std::string(where) + "a mask value outside [0, 1]");
}
}  // namespace

void write_mesh_slots(const SurfaceMesh& m, std::vector<std::uint8_t>& out) {
  for (int k = 0; k < UndoLog::kKinds; ++k) {
    const PropertyContainer& c = container(m, k);
    put(out, std::uint32_t(c.size()));
    std::vector<UndoLog::Step::Values> vs;
    for (size_t i = 0; i < c.n_arrays(); ++i) {
      BasePropertyArray* a = c.array(i);
      if (!builtin(a->name())) continue;
      const size_t eb = a->element_bytes();
      vs.push_back({a->name(), std::uint32_t(eb), std::vector<std::uint8_t>(a->raw(), a->raw() + c.size() * eb)});
    }
    write_values(out, vs);
  }
  write_counts(out, m.deleted_counts());
}

size_t mesh_slots_serialized_size(const SurfaceMesh& m) {
  size_t b = 24;
  for (int k = 0; k < UndoLog::kKinds; ++k) {
    const PropertyContainer& c = container(m, k);
    b += 8;
    for (size_t i = 0; i < c.n_arrays(); ++i)
      if (builtin(c.array(i)->name())) b += 2 + c.array(i)->name().size() + 12 + c.size() * c.array(i)->element_bytes();
  }
  return b;
}

// Builds a mesh from write_mesh_slots bytes, validated (connectivity, counters, finite positions).
SurfaceMesh read_mesh_slots(const std::uint8_t*& p, size_t& left) {
  Reader r{p, left};
  SurfaceMesh m;
  for (int k = 0; k < UndoLog::kKinds; ++k) {
    const std::uint32_t n = r.get<std::uint32_t>();
    std::vector<UndoLog::Step::Values> vs = read_values(r);
    PropertyContainer& c = container(m, k);
    c.resize(n);
    for (const auto& v : vs) {
      BasePropertyArray* a = find_array(c, v.name, v.bytes);
      // The mask is the one logged array a mesh gets later (mesh/vertex_mask.h).
      if (!a && k == kVertex && v.name == mesh::kMaskProperty && v.bytes == sizeof(float))
        a = m.add_vertex_property<float>(mesh::kMaskProperty, 0.0f).array();
      if (!a) fail("unknown mesh array '" + v.name + "'");
      if (v.data.size() != size_t(n) * v.bytes) fail("mesh array '" + v.name + "' is cut");
      if (n) std::memcpy(a->raw(), v.data.data(), v.data.size());
    }
  }
  if (container(m, kHalfedge).size() != 2 * container(m, kEdge).size()) fail("halfedges and edges disagree");
  m.set_deleted_counts(read_counts(r));
  try {
    m.validate();
  } catch (const std::logic_error& e) {
    fail(e.what());
  }
  for (Vertex v : m.vertices()) {
    const Point& q = m.position(v);
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) fail("non-finite position");
  }
  if (m.n_faces() == 0) fail("a mesh without faces");
  check_mask_values(m, "");
  return m;
}

void UndoLog::write_step(const Step& s, std::vector<std::uint8_t>& out) {
  put(out, std::uint8_t(s.whole ? 1 : 0));
  if (s.whole) {
    write_mesh_slots(*s.whole, out);
    return;
  }
  for (const Step::Block& b : s.blocks) {
    put(out, b.size_held);
    put(out, std::uint64_t(b.slots.size()));
    const auto* raw = reinterpret_cast<const std::uint8_t*>(b.slots.data());
    out.insert(out.end(), raw, raw + b.slots.size() * 4);
    write_values(out, b.values);
    write_values(out, b.tail);
  }
  write_counts(out, s.deleted_held);
}

size_t UndoLog::step_serialized_size(const Step& s) {
  if (s.whole) return 1 + mesh_slots_serialized_size(*s.whole);
  size_t b = 1 + 24;
  for (const Step::Block& k : s.blocks) {
    b += 12 + k.slots.size() * 4 + 8;
    for (const auto* vs : {&k.values, &k.tail})
      for (const auto& v : *vs) b += 2 + v.name.size() + 12 + v.data.size();
  }
  return b;
}

std::unique_ptr<UndoLog::Step> UndoLog::read_step(const std::uint8_t*& p, size_t& left) {
  Reader r{p, left};
  auto s = std::make_unique<Step>();
  const std::uint8_t type = r.get<std::uint8_t>();
  if (type > 1) fail("unknown step type");
  if (type == 1) {
    s->whole = std::make_unique<SurfaceMesh>(read_mesh_slots(p, left));
    return s;
  }
  for (Step::Block& b : s->blocks) {
    b.size_held = r.get<std::uint32_t>();
    const std::uint64_t n = r.get<std::uint64_t>();
    if (n > left / 4) fail("truncated step");
    b.slots.resize(size_t(n));
    const std::vector<std::uint8_t> raw = r.bytes(size_t(n) * 4);
    if (n) std::memcpy(b.slots.data(), raw.data(), raw.size());
    b.values = read_values(r);
    b.tail = read_values(r);
  }
  s->deleted_held = read_counts(r);
  return s;
}

void UndoLog::read_history(SurfaceMesh& m, const std::uint8_t*& p, size_t& left, std::uint32_t n_undo_steps,
                           std::uint32_t n_redo_steps) {
  std::deque<std::unique_ptr<Step>> undo, redo;
  for (std::uint32_t i = 0; i < n_undo_steps; ++i) undo.push_back(read_step(p, left));
  for (std::uint32_t i = 0; i < n_redo_steps; ++i) redo.push_back(read_step(p, left));
  UndoLog trial;
  trial.max_steps_ = max_steps_;
  trial.max_bytes_ = max_bytes_;
  trial.verify_ = verify_;
  SurfaceMesh work(m);
  trial.reset(work);
  trial.undo_ = std::move(undo);
  trial.redo_ = std::move(redo);
  for (const auto& s : trial.undo_) trial.undo_bytes_ += s->bytes();
  auto check = [&] {
    try {
      work.validate();
    } catch (const std::logic_error& e) {
      fail(std::string("a history step: ") + e.what());
    }
    for (Vertex v : work.vertices()) {
      const Point& q = work.position(v);
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) fail("a history step: non-finite position");
    }
    check_mask_values(work, "a history step: ");
  };
  const size_t n_undo = trial.undo_.size(), n_redo = trial.redo_.size();
  for (size_t i = 0; i < n_undo; ++i) {
    trial.undo(work, nullptr, nullptr);
    check();
  }
  for (size_t i = 0; i < n_undo + n_redo; ++i) {
    trial.redo(work, nullptr, nullptr);
    check();
  }
  for (size_t i = 0; i < n_redo; ++i) trial.undo(work, nullptr, nullptr);
  trial.enforce_limits();
  trial.full_diffs_ = full_diffs_;
  m = std::move(work);
  *this = std::move(trial);
}

bool UndoLog::write_newest_for_replay(const SurfaceMesh& m, std::vector<std::uint8_t>& out) const {
  if (undo_.empty() || undo_.back()->whole) return false;
  const Step& s = *undo_.back();
  put(out, std::uint8_t(0));
  for (int k = 0; k < kKinds; ++k) {
    const Step::Block& b = s.blocks[k];
    const PropertyContainer& c = container(m, k);
    // Same slots and arrays as the held (before) form, with the mesh's values: what redo swaps in.
    put(out, std::uint32_t(c.size()));
    put(out, std::uint64_t(b.slots.size()));
    const auto* raw = reinterpret_cast<const std::uint8_t*>(b.slots.data());
    out.insert(out.end(), raw, raw + b.slots.size() * 4);
    std::vector<Step::Values> values, tail;
    for (const Step::Values& v : b.values) {
      BasePropertyArray* a = find_array(c, v.name, v.bytes);  // raw() is non-const (see container())
      if (!a) throw std::logic_error("undo log: the mesh lost the array '" + v.name + "' of its newest step");
      Step::Values w{v.name, v.bytes, std::vector<std::uint8_t>(b.slots.size() * v.bytes)};
      for (size_t j = 0; j < b.slots.size(); ++j)
        std::memcpy(w.data.data() + j * v.bytes, a->raw() + size_t(b.slots[j]) * v.bytes, v.bytes);
      values.push_back(std::move(w));
    }
    // The slots the step appended, as undo would have put them into its tail.
    if (c.size() > b.size_held)
      for (size_t i = 0; i < c.n_arrays(); ++i) {
        BasePropertyArray* a = c.array(i);
        if (!builtin(a->name())) continue;
        const size_t eb = a->element_bytes();
        tail.push_back({a->name(), std::uint32_t(eb),
                        std::vector<std::uint8_t>(a->raw() + b.size_held * eb, a->raw() + c.size() * eb)});
      }
    write_values(out, values);
    write_values(out, tail);
  }
  write_counts(out, m.deleted_counts());
  return true;
}

void UndoLog::replay_commit(SurfaceMesh& m, const std::uint8_t*& p, size_t& left, size_t keep_undo) {
  std::unique_ptr<Step> s = read_step(p, left);
  if (s->whole) fail("a change record holds a whole mesh");
  // A commit starts a new branch: the redo steps go, as commit_local drops them. swap_step checks
  // the step against the mesh before it changes anything; only then is the redo list touched.
  std::deque<std::unique_ptr<Step>> dropped;
  dropped.swap(redo_);
  redo_.push_back(std::move(s));
  try {
    redo(m, nullptr, nullptr);
  } catch (...) {
    redo_.swap(dropped);
    throw;
  }
  while (undo_.size() > keep_undo && undo_.size() > 1) {
    undo_bytes_ -= undo_.front()->bytes();
    undo_.pop_front();
  }
}

}  // namespace adasculpt::sculpt
