#pragma once
/// \file
/// \brief glibc's libmvec vector sin, cos and atan2 for `#pragma omp simd` loops.
///
/// <bits/math-vector.h> declares them only under -ffast-math. Declared here as glibc does, so a
/// file compiled with -fopenmp-simd -fno-math-errno calls the vector versions from its simd
/// loops while the rest of its arithmetic keeps IEEE semantics. atan2 needs glibc 2.35 or later
/// (Debian 12 has 2.36). Include it only in such files, before any other header that declares
/// these functions' use. GCC only: clang (the fuzz build) knows no __simd__ attribute and calls
/// the scalar functions.

#if defined(__x86_64__) && defined(__GLIBC__) && !defined(__FAST_MATH__) && !defined(__clang__)
extern "C" {
__attribute__((__simd__("notinbranch"))) double sin(double) noexcept;
__attribute__((__simd__("notinbranch"))) double cos(double) noexcept;
__attribute__((__simd__("notinbranch"))) double atan2(double, double) noexcept;
}
#endif
