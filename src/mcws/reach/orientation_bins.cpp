#include "mcws/reach/orientation_bins.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "mcws/core/error.h"
#include "mcws/core/libmvec.h"  // vector sin, cos, atan2 for the simd loops

namespace mcws {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

/// Longitude in [0, 2 pi).
double longitude(const Eigen::Vector3d& v) {
  const double phi = std::atan2(v.y(), v.x());
  return phi < 0.0 ? phi + kTwoPi : phi;
}

/// Index of `angle` (in [0, 2 pi)) among `count` equal sectors, clamped against rounding.
int sectorOf(double angle, int count) {
  return std::min(count - 1, static_cast<int>(angle * count / kTwoPi));
}

/// Two doubles (GCC and Clang vectors: SSE2 registers on x86-64).
using Pair = double __attribute__((vector_size(16)));
using PairMask = decltype(Pair{} > Pair{});

Pair choose(PairMask mask, Pair a, Pair b) {
  PairMask ia, ib;
  std::memcpy(&ia, &a, sizeof a);
  std::memcpy(&ib, &b, sizeof b);
  const PairMask bits = (mask & ia) | (~mask & ib);
  Pair out;
  std::memcpy(&out, &bits, sizeof out);
  return out;
}

/// The longitudes of two points (x, y) in [0, 2 pi] within 8.2e-7 rad, without atan2: the angle
/// of the smaller of |x|, |y| over the larger, r = min / max in [0, 1], brought within
/// tan(pi / 8) by atan r = pi / 4 + atan(u), u = (r - 1) / (r + 1) = (min - max) / (min + max)
/// (one division either way), where the Taylor series to u^11 leaves at most |u|^13 / 13 <
/// 8.2e-7 (alternating, decreasing terms), then moved to its octant. -1 where the longitude is
/// not defined here: x or y not finite or beyond a quarter of the largest double (min + max
/// must not overflow), or both below the smallest normal double (both 0, or where tan(pi / 8)
/// max would round).
Pair roughLongitudes(Pair x, Pair y) {
  const Pair zero = {0.0, 0.0};
  const Pair ax = choose(x < zero, -x, x), ay = choose(y < zero, -y, y);
  const PairMask y_larger = ay > ax;
  const Pair low = choose(y_larger, ax, ay), high = choose(y_larger, ay, ax);
  constexpr double kSmallest = std::numeric_limits<double>::min();
  constexpr double kLargest = 0.25 * std::numeric_limits<double>::max();
  const PairMask defined =
      (high >= Pair{kSmallest, kSmallest}) & (high <= Pair{kLargest, kLargest}) & (low <= high);
  const PairMask far = low > Pair{0.41421356237309503, 0.41421356237309503} * high;  // tan(pi/8)
  const Pair u = choose(far, low - high, low) / choose(far, low + high, high), u2 = u * u;
  Pair series = Pair{-1.0 / 11, -1.0 / 11};
  for (const double c : {1.0 / 9, -1.0 / 7, 1.0 / 5, -1.0 / 3, 1.0}) {
    series = Pair{c, c} + u2 * series;
  }
  series = u * series;
  const Pair quarter = {0.25 * M_PI, 0.25 * M_PI}, half = {0.5 * M_PI, 0.5 * M_PI},
             pi = {M_PI, M_PI}, two_pi = {kTwoPi, kTwoPi};
  Pair a = choose(far, quarter, zero) + series;  // atan(min / max), 0 .. pi / 4
  a = choose(y_larger, half - a, a);
  a = choose(x < zero, pi - a, a);
  a = choose(y < zero, two_pi - a, a);
  return choose(defined, a, Pair{-1.0, -1.0});
}

}  // namespace

SpherePartition::SpherePartition(int regions) : regions_(regions) {
  if (regions < 1)
    throw Error("sphere partition: need at least 1 region, not " + std::to_string(regions));
  zone_first_.push_back(0);
  if (regions == 1) {
    zone_first_.push_back(1);
  } else if (regions == 2) {
    zone_first_.insert(zone_first_.end(), {1, 2});
  } else {
    // Leopardi 2006, eq_caps for S^2: caps of one region's area, collars of the fitting angle.
    const double n = regions;
    const double area = 4.0 * M_PI / n;
    const double cap = std::acos(1.0 - 2.0 / n);  // colatitude of the north cap's edge
    const double ideal_angle = std::sqrt(area);
    const int collars =
        std::max(1, static_cast<int>(std::lround((M_PI - 2.0 * cap) / ideal_angle)));
    const double fitting_angle = (M_PI - 2.0 * cap) / collars;
    const auto capArea = [](double colatitude) { return kTwoPi * (1.0 - std::cos(colatitude)); };
    zone_first_.push_back(1);
    double carry = 0.0;
    for (int i = 1; i <= collars; ++i) {
      const double ideal =
          (capArea(cap + i * fitting_angle) - capArea(cap + (i - 1) * fitting_angle)) / area;
      const int count = static_cast<int>(std::lround(ideal + carry));
      carry += ideal - count;
      zone_first_.push_back(zone_first_.back() + count);
    }
    zone_first_.push_back(zone_first_.back() + 1);  // the south cap
    if (zone_first_.back() != regions) {
      throw Error("sphere partition: collars hold " + std::to_string(zone_first_.back()) +
                  " regions, not " + std::to_string(regions));  // Leopardi's rounding prevents it
    }
  }
  // Each zone ends where the cap above it holds zone_first_[j + 1] regions' area.
  for (std::size_t j = 0; j + 1 < zone_first_.size(); ++j) {
    zone_top_z_.push_back(1.0 - 2.0 * zone_first_[j] / static_cast<double>(regions));
  }
  zone_top_z_.push_back(-1.0);
  // Per zone, the factor from a longitude to its sector and the margin regions() keeps from a
  // sector's edges, in sectors (as regions() computed them per direction).
  for (std::size_t j = 0; j + 1 < zone_first_.size(); ++j) {
    const int count = zone_first_[j + 1] - zone_first_[j];
    zone_sectors_.push_back({count / kTwoPi, 1e-6 * count, count});
  }
  // The zone of each whole number of regions' area above a direction.
  for (int above = 0, zone = 0; above <= regions_; ++above) {
    while (zone + 1 < zones() && above >= zone_first_[zone + 1]) ++zone;
    zone_of_area_.push_back(zone);
  }
}

int SpherePartition::zoneOfZ(double z) const {
  // Area above the direction in units of one region: the zone is found by its region counts.
  // The zone is the last whose first region count is <= above; the counts are whole numbers, so
  // it is that of floor(above) (in the table); below 1 (or NaN) zone 0, above all the last.
  const double above = 0.5 * regions_ * (1.0 - z);
  if (!(above >= 1.0)) return 0;
  return zone_of_area_[above < regions_ ? static_cast<int>(above) : regions_];
}

void SpherePartition::regions(const double* d, int lanes, int* out) const {
  // Eight lanes at a time. The longitude's sector from roughLongitudes() where that longitude is
  // over 2 pi 1e-6 rad from the sector's edges, 7.6 times its error: the sector of glibc's atan2
  // too then (whose longitude and its scaling are within 1e-13 rad); otherwise, for the eight,
  // regionsByAtan2().
  for (int first = 0; first < lanes; first += 8) {
    const int last = std::min(lanes, first + 8);
    double rough[8];
    for (int k = 0; k < 8; k += 2) {
      const int lane0 = first + k < last ? first + k : first;
      const int lane1 = first + k + 1 < last ? first + k + 1 : first;
      const Pair x = {d[lane0], d[lane1]}, y = {d[lanes + lane0], d[lanes + lane1]};
      const Pair a = roughLongitudes(x, y);
      rough[k] = a[0];
      rough[k + 1] = a[1];
    }
    bool certain = true;
    for (int k = first; k < last; ++k) {
      const int zone = zoneOfZ(d[2 * lanes + k]);
      const ZoneSectors& sectors = zone_sectors_[zone];
      const int count = sectors.count;
      if (count == 1) {
        out[k] = zone_first_[zone];
        continue;
      }
      const double t = rough[k - first] * sectors.scale, margin = sectors.margin;
      bool clear = t >= 0.0 && t < count;  // not where the longitude is undefined (-1)
      const int sector = clear ? static_cast<int>(t) : 0;  // floor
      clear = clear && t - sector > margin && sector + 1.0 - t > margin;
      certain = certain && clear;
      out[k] = zone_first_[zone] + sector;
    }
    if (!certain) regionsByAtan2(d + first, lanes, last - first, out + first);
  }
}

void SpherePartition::regionsByAtan2(const double* d, int stride, int lanes, int* out) const {
  double x[8], y[8], phi[8];
  for (int k = 0; k < 8; ++k) {
    const int lane = k < lanes ? k : 0;
    x[k] = d[lane];
    y[k] = d[stride + lane];
  }
#pragma omp simd
  for (int k = 0; k < 8; ++k) phi[k] = std::atan2(y[k], x[k]);
  for (int k = 0; k < lanes; ++k) {
    const int zone = zoneOfZ(d[2 * stride + k]);
    const int count = zone_first_[zone + 1] - zone_first_[zone];
    const double angle = phi[k] < 0.0 ? phi[k] + kTwoPi : phi[k];
    out[k] = zone_first_[zone] + (count == 1 ? 0 : sectorOf(angle, count));
  }
}

int SpherePartition::region(const Eigen::Vector3d& direction) const {
  const int zone = zoneOfZ(direction.z() / direction.norm());
  const int count = zone_first_[zone + 1] - zone_first_[zone];
  return zone_first_[zone] + (count == 1 ? 0 : sectorOf(longitude(direction), count));
}

int SpherePartition::zoneOf(int region) const {
  if (region < 0 || region >= regions_) {
    throw Error("sphere partition: no region " + std::to_string(region) + " of " +
                std::to_string(regions_));
  }
  int zone = 0;
  while (region >= zone_first_[zone + 1]) ++zone;
  return zone;
}

void SpherePartition::bounds(int region, double& colatitude_min, double& colatitude_max,
                             double& longitude_min, double& longitude_max) const {
  const int zone = zoneOf(region);
  colatitude_min = std::acos(zone_top_z_[zone]);
  colatitude_max = std::acos(zone_top_z_[zone + 1]);
  const int count = zone_first_[zone + 1] - zone_first_[zone];
  const int sector = region - zone_first_[zone];
  longitude_min = kTwoPi * sector / count;
  longitude_max = sector + 1 == count ? kTwoPi : kTwoPi * (sector + 1) / count;
}

Eigen::Vector3d SpherePartition::centre(int region) const {
  double theta0, theta1, phi0, phi1;
  bounds(region, theta0, theta1, phi0, phi1);
  if (theta0 == 0.0 && regions_ > 1) return Eigen::Vector3d::UnitZ();    // north cap
  if (theta1 == M_PI && regions_ > 1) return -Eigen::Vector3d::UnitZ();  // south cap
  if (regions_ == 1) return Eigen::Vector3d::UnitZ();
  const double theta = 0.5 * (theta0 + theta1), phi = 0.5 * (phi0 + phi1);
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

OrientationBins::OrientationBins(int directions, int rolls) : sphere_(directions), rolls_(rolls) {
  if (rolls < 1)
    throw Error("orientation bins: need at least 1 roll bin, not " + std::to_string(rolls));
}

Eigen::Vector3d OrientationBins::rollReference(const Eigen::Vector3d& approach) {
  const Eigen::Vector3d axis = std::abs(approach.x()) > std::cos(M_PI / 6.0)
                                   ? Eigen::Vector3d::UnitY()
                                   : Eigen::Vector3d::UnitX();
  return (axis - axis.dot(approach) * approach).normalized();
}

int OrientationBins::rollSector(const Eigen::Vector3d& approach,
                                const Eigen::Vector3d& x_axis) const {
  if (rolls_ == 1) return 0;
  const Eigen::Vector3d reference = rollReference(approach);
  double roll = std::atan2(reference.cross(x_axis).dot(approach), reference.dot(x_axis));
  if (roll < 0.0) roll += kTwoPi;
  return sectorOf(roll, rolls_);
}

int OrientationBins::bin(const Eigen::Vector3d& approach, const Eigen::Vector3d& x_axis) const {
  return sphere_.region(approach) * rolls_ + rollSector(approach, x_axis);
}

void OrientationBins::bins(const double* approach, const double* x_axis, int lanes,
                           int* out) const {
  sphere_.regions(approach, lanes, out);
  if (rolls_ == 1) return;
  for (int k = 0; k < lanes; ++k) {
    const Eigen::Vector3d a(approach[k], approach[lanes + k], approach[2 * lanes + k]);
    const Eigen::Vector3d x(x_axis[k], x_axis[lanes + k], x_axis[2 * lanes + k]);
    out[k] = out[k] * rolls_ + rollSector(a, x);
  }
}

Eigen::Matrix3d OrientationBins::centre(int bin) const {
  if (bin < 0 || bin >= size()) {
    throw Error("orientation bins: no bin " + std::to_string(bin) + " of " +
                std::to_string(size()));
  }
  const Eigen::Vector3d approach = sphere_.centre(bin / rolls_);
  const Eigen::Vector3d reference = rollReference(approach);
  const double roll = kTwoPi * (bin % rolls_ + 0.5) / rolls_;
  const Eigen::Vector3d x = std::cos(roll) * reference + std::sin(roll) * approach.cross(reference);
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = approach.cross(x);
  R.col(2) = approach;
  return R;
}

}  // namespace mcws
