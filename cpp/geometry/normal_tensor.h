#pragma once
// How the face normals of a fan spread: the tensor sum of n n^T over its faces' unit normals,
// weighted by area. Its eigenvalues l0 <= l1 <= l2 tell a flat fan or two sheets facing opposite
// ways (normals along one axis: l1 small), a crease (normals turning about one axis: l0 small)
// and a tip (normals every way).
#include "mesh/types.h"

namespace adasculpt::geometry {

class NormalTensor {
 public:
  // n: a face's normal scaled by twice its area (a cross product of two of its edges).
  void add(const Vec3& n);
  // Whether the normals lie along one axis: l1 below `share` times l2.
  bool along_one_axis(double share) const;

 private:
  double m_[6] = {0, 0, 0, 0, 0, 0};  // xx yy zz xy xz yz
};

}  // namespace adasculpt::geometry
