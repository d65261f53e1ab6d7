#pragma once
// Trigonometry from IEEE-754 basic operations and sqrt only, which are correctly rounded on
// every platform. glibc (native build) and musl (WebAssembly build) implement atan2, sin, cos
// differently in the last bit; one differing bit in an angle can flip a remeshing decision
// and the two builds would then produce different meshes from the same input. Accuracy is
// within a few ulp, more than the geometry needs.
namespace adasculpt::portable {

double atan2(double y, double x);
double sin(double x);
double cos(double x);
double acos(double x);

}  // namespace adasculpt::portable
