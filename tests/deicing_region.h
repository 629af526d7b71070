#pragma once
// The de-icing arm's planar workspace (Yin, Wang & Yu 2010, eq. (1), theta3 = 0) in closed form, as
// an independent oracle for the sampler, boundary and measure stages.
//
// A point P = (x, z) is reached when some shoulder angle theta1 in [-45, 45] deg puts the elbow
// E = a1 (cos theta1, sin theta1) so that the forearm P - E has length a2 in [25, 70] and makes an
// angle within +-90 deg with the upper arm. With beta the polar angle of P and u = theta1 - beta:
//   |P - E|^2 = |P|^2 + a1^2 - 2 a1 |P| cos u   (length condition on cos u), and
//   (P - E) . (cos theta1, sin theta1) = |P| cos u - a1 >= 0   (elbow limit: cos u >= a1 / |P|).
// Both are bounds on cos u, so the valid u form [acos H, acos L] and its mirror, and P is reached
// when beta + u meets [-45, 45] deg for one of them.

#include <algorithm>
#include <cmath>

namespace mcws::test {

struct DeicingArm {
  double a1 = 50.0, a2_min = 25.0, a2_max = 70.0;  // [cm]
  double theta1_limit = M_PI / 4;                  // |theta1| <= 45 deg

  bool reaches(double x, double z) const {
    const double rho = std::hypot(x, z);
    if (rho == 0.0) return false;
    const double low = std::max(a1 / rho, (rho * rho + a1 * a1 - a2_max * a2_max) / (2 * a1 * rho));
    const double high = std::min(1.0, (rho * rho + a1 * a1 - a2_min * a2_min) / (2 * a1 * rho));
    if (low > high || low > 1.0) return false;
    const double u_small = std::acos(high), u_large = std::acos(std::max(-1.0, low));
    const double beta = std::atan2(z, x);
    auto meets = [&](double from, double to) {  // [from, to] against [-limit, limit] (mod 2 pi)
      for (int k = -1; k <= 1; ++k) {
        const double shift = 2 * M_PI * k;
        if (from + shift <= theta1_limit && to + shift >= -theta1_limit) return true;
      }
      return false;
    };
    return meets(beta + u_small, beta + u_large) || meets(beta - u_large, beta - u_small);
  }
};

/// Area [cm^2] of the X-Z workspace and volume [cm^3] of the 3-D one (the X-Z region swept by
/// theta3 in [-60, 60] deg: Pappus, V = (2 pi / 3) integral of |x| dA), integrated on a grid of
/// cells `step` cm wide with the closed-form membership at cell centres.
struct DeicingMeasures {
  double area, volume;
};
inline DeicingMeasures integrateDeicing(double step) {
  const DeicingArm arm;
  double area = 0.0, moment = 0.0;
  const double reach = arm.a1 + arm.a2_max;
  const long cells = static_cast<long>(std::ceil(2 * reach / step));
#pragma omp parallel for reduction(+ : area, moment) schedule(static)
  for (long i = 0; i < cells; ++i) {
    const double x = -reach + (i + 0.5) * step;
    for (long j = 0; j < cells; ++j) {
      const double z = -reach + (j + 0.5) * step;
      if (arm.reaches(x, z)) {
        area += step * step;
        moment += std::abs(x) * step * step;
      }
    }
  }
  return {area, 2.0 * M_PI / 3.0 * moment};
}

}  // namespace mcws::test
