#pragma once
// Sculpting brushes: one stamp = a displacement of the vertices within the brush radius of a
// surface point, weighted by a smooth falloff. The stroke logic (spacing along the pointer path,
// mirror symmetry, the remeshing iteration after each stamp) lives in sculpt/brush.h.
//
// The vertices under a stamp are found by a flood from the vertex nearest to the centre through
// vertices inside the brush sphere, so the work is proportional to the brushed area and a thin
// part's far side (inside the sphere but not connected through it) is left alone.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mesh/surface_mesh.h"

namespace adasculpt::deform {

using mesh::SurfaceMesh;
using mesh::Vertex;

enum class BrushTool { Draw, Inflate, Smooth, Flatten, Pinch, Crease, Grab };

// "draw, inflate, smooth, flatten, pinch, crease, snakeHook" (for error messages); parse_brush_tool
// also reads "grab", the snake hook's deprecated name.
const char* brush_tool_list();
const char* brush_tool_name(BrushTool tool);
std::optional<BrushTool> parse_brush_tool(const std::string& name);

// How a stamp's effect fades from its centre (q = distance / radius) to its rim:
//   smooth   (1 - q^2)^3   flat centre, soft rim (the default, and every stroke before presets)
//   sphere   sqrt(1 - q^2) a dome: full strength almost to the rim, then a steep edge
//   sharp    (1 - q)^2     a pointed peak that tapers fast
//   linear   1 - q         a cone
//   constant 1             the whole disc at full strength (a stamp with a hard edge)
enum class BrushFalloff { Smooth, Sphere, Sharp, Linear, Constant };
// "smooth, sphere, sharp, linear, constant" (for error messages).
const char* brush_falloff_list();
const char* brush_falloff_name(BrushFalloff falloff);
std::optional<BrushFalloff> parse_brush_falloff(const std::string& name);

struct BrushSettings {
  BrushTool tool = BrushTool::Draw;
  double radius = 0;      // absolute length
  double strength = 0.5;  // 0..1; pressure multiplies it (grab ignores both: it follows the pointer)
  double spacing = 0.25;  // a stamp every spacing * radius of pointer travel
  bool invert = false;    // draw/inflate/crease inward, flatten/pinch push away; smooth, grab: no effect
  int symmetry_axis = -1; // 0, 1, 2: mirror across the plane x, y or z = 0; -1: none
  // > 0: this stroke remeshes to this edge length (absolute), instead of the session's detail
  // settings. The viewer's screen-pixel detail mode passes pixels x the size of a pixel at the
  // brush (Blender's relative detail).
  double detail = 0;
  BrushFalloff falloff = BrushFalloff::Smooth;
};
// Throws std::invalid_argument "brush: 'radius' must be a positive number" and the like.
void check_brush_settings(const BrushSettings& s);

// The falloff's weight in [0, 1] at `distance` from the centre; 0 at and beyond the radius.
// Without a falloff: (1 - (d/r)^2)^3, the smooth preset.
double brush_falloff(double distance, double radius, BrushFalloff falloff = BrushFalloff::Smooth);

// Walks from `start` to neighbours that are strictly closer to `target` until none is; the
// vertex reached. Cheap between successive stamps, which are a fraction of a radius apart.
Vertex walk_to_nearest_vertex(const SurfaceMesh& mesh, Vertex start, const Point& target);
// The closest point to p on the faces around v.
Point closest_point_around(const SurfaceMesh& mesh, Vertex v, const Point& p);

// One stamp as seen by the deformer: where, which vertex to flood from, how hard.
struct StampSpec {
  Point center{0.0};
  Vertex seed;             // a vertex near the centre (walk_to_nearest_vertex)
  Vec3 grab_delta{0.0};    // grab only: how far the pointer moved since the previous stamp
  double pressure = 1;
};

class BrushDeformer {
 public:
  // Applies the stamps together: every displacement is computed from the positions before any
  // of them moves, and a vertex under several stamps moves by their mean (a stamp and its mirror
  // image overlapping at the symmetry plane then stay symmetric and do not add up).
  // Returns the brushed vertices plus one ring around them (for Remesher::iterate_region).
  // With `mirror` (the image of each vertex of an exactly symmetric mesh, from the remesher) and
  // two stamps, only the first is computed and every displacement is also applied, mirrored, to
  // the vertex's image: the second stamp's result, exact to the last bit.
  std::vector<Vertex>& apply(SurfaceMesh& mesh, const BrushSettings& settings, const StampSpec* stamps, int n,
                             const std::vector<Vertex>* mirror = nullptr);
  // Vertices moved by the last apply() (without the ring).
  size_t moved() const { return moved_; }
  // Sizes the per-vertex-slot arrays for n slots (zero-filled). Called with each new mesh, so a
  // stroke's first stamp touches only its region (sizing them there cost a session's first stroke
  // on 1.1M triangles several milliseconds); apply() still grows them when the mesh outgrows n.
  void grow(size_t n);

 private:
  void gather(const SurfaceMesh& mesh, const StampSpec& s, double radius, BrushFalloff falloff);
  void displace(const SurfaceMesh& mesh, const BrushSettings& settings, const StampSpec& s);
  void add(Vertex v, const Vec3& d);  // one stamp's displacement of v
  // Inflate: vertex normals of inside_ smoothed over about `displacement` into smooth_normal_.
  void smooth_normals(const SurfaceMesh& mesh, double displacement);
  bool marked(Vertex v) const { return v.idx < mark_.size() && mark_[v.idx] == run_; }

  // Per vertex slot, valid when mark_ == run_ / in_stamp_ == stamp_run_ (never cleared in full).
  std::vector<std::uint32_t> mark_, in_stamp_;
  std::vector<Vec3> sum_;         // accumulated displacement
  std::vector<std::uint8_t> count_;  // stamps contributing
  std::uint32_t run_ = 0, stamp_run_ = 0;
  std::vector<Vertex> inside_;     // of the current stamp
  std::vector<double> weight_;     // falloff per inside_ entry
  std::vector<Vec3> smooth_normal_, next_normal_;  // inflate: per inside_ entry
  std::vector<Vec3> image_displacement_;  // apply() with a mirror map: the first stamp's, mirrored
  std::vector<std::uint32_t> slot_;  // per vertex slot: its index in inside_ (valid while in_stamp_)
  std::vector<Vertex> touched_;    // union over the stamps
  std::vector<Vertex> region_;     // touched_ + ring
  size_t moved_ = 0;
};

}  // namespace adasculpt::deform
