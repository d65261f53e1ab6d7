#include "geometry/normal_tensor.h"

#include <cmath>

#include <Eigen/Eigenvalues>

namespace adasculpt::geometry {

void NormalTensor::add(const Vec3& n) {
  const double length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  if (!(length > 0)) return;
  const double w = 1.0 / length;  // n n^T / |n|: the unit normal's tensor times the area (x 2)
  m_[0] += w * n.x * n.x;
  m_[1] += w * n.y * n.y;
  m_[2] += w * n.z * n.z;
  m_[3] += w * n.x * n.y;
  m_[4] += w * n.x * n.z;
  m_[5] += w * n.y * n.z;
}

bool NormalTensor::along_one_axis(double share) const {
  Eigen::Matrix3d m;
  m << m_[0], m_[3], m_[4], m_[3], m_[1], m_[5], m_[4], m_[5], m_[2];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(m, Eigen::EigenvaluesOnly);  // in increasing order
  const Eigen::Vector3d& values = solver.eigenvalues();
  return values[2] > 0 && values[1] < share * values[2];
}

}  // namespace adasculpt::geometry
