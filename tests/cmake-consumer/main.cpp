// Loads an icosphere, remeshes it adaptively through the session API and checks the result, using
// only the installed headers and library.
#include <cstdio>

#include "geometry/quality.h"
#include "mesh/primitives.h"
#include "sculpt/session.h"

int main() {
  adasculpt::sculpt::Session session;
  session.load(adasculpt::mesh::make_icosphere(3));
  session.set_settings({{"max_length", "2%"}});
  session.remesh(3);
  const adasculpt::geometry::QualityReport q = session.quality();
  std::printf("consumer: %zu vertices, min angle %.1f\n", q.vertices, q.min_angle_deg);
  return q.vertices > 642 && q.min_angle_deg > 20 ? 0 : 1;
}
