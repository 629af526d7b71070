#pragma once
/// \file
/// \brief Orientation bins of a reachability map: approach directions in equal-area regions of
/// the sphere, times roll bins about the approach.

#include <Eigen/Geometry>
#include <vector>

namespace mcws {

/// \brief Leopardi's recursive zonal equal-area partition of the unit sphere into N regions
/// (P. Leopardi, "A partition of the unit sphere into regions of equal area and small diameter",
/// Electronic Transactions on Numerical Analysis 25, 2006), the EQ partition of S^2.
///
/// Two polar caps of area 4 pi / N and, between them, collars of latitude, each cut into equal
/// longitude sectors; the collar boundaries are placed so that every region has area exactly
/// 4 pi / N, and their number keeps the regions close to square (diameter about
/// 3.5 / sqrt(N) rad). Finding a direction's region costs one pass over the zones (about
/// 0.89 sqrt(N) collars and the two caps: 13 zones for N = 200), no search.
class SpherePartition {
 public:
  /// \param regions N >= 1. \throws mcws::Error for N < 1.
  explicit SpherePartition(int regions);

  int regions() const { return regions_; }
  /// \brief Number of collars, polar caps included (1 for N = 1, 2 for N = 2).
  int zones() const { return static_cast<int>(zone_first_.size()) - 1; }

  /// \brief The region of a direction, 0 .. regions()-1, numbered from the north pole (+z) down,
  /// each collar eastwards from longitude 0 (+x).
  /// \param direction any non-zero vector (need not be unit).
  int region(const Eigen::Vector3d& direction) const;

  /// \brief region() of `lanes` unit directions at once, laid out d[a * lanes + k]: the
  /// regions of regionsByAtan2(), found without atan2 where the longitude is clearly inside a
  /// sector (nearly always).
  /// \param lanes any number (eight at a time).
  void regions(const double* d, int lanes, int* out) const;
  /// \brief The reference of regions(): region() of up to 8 unit directions, laid out
  /// d[a * stride + k], with the longitudes from glibc's vector atan2 (equal to region() except,
  /// at most, for a direction within about 1e-16 rad of a sector edge).
  void regionsByAtan2(const double* d, int stride, int lanes, int* out) const;

  /// \brief A region's centre: the direction at its mid colatitude and mid longitude (a pole for
  /// a polar cap). region(centre(i)) == i.
  Eigen::Vector3d centre(int region) const;

  /// \brief The colatitude range [rad] and longitude range [rad] of a region.
  void bounds(int region, double& colatitude_min, double& colatitude_max, double& longitude_min,
              double& longitude_max) const;

 private:
  int zoneOf(int region) const;
  int zoneOfZ(double z) const;
  int regions_;
  std::vector<double> zone_top_z_;  ///< z = cos(colatitude) of each zone's upper edge; last -1
  std::vector<int> zone_first_;     ///< first region of each zone; last entry regions_
  std::vector<int> zone_of_area_;   ///< [a]: the zone of a direction with a regions' area above it
  /// A zone's sectors as regions() reads them.
  struct ZoneSectors {
    double scale;   ///< sectors per radian of longitude: count / (2 pi)
    double margin;  ///< the distance from an edge [sectors] below which atan2 decides
    int count;      ///< sectors
  };
  std::vector<ZoneSectors> zone_sectors_;
};

/// \brief The tool orientation as a bin: the approach direction (the tool's z axis, as in
/// Zacharias et al. 2007 and ROS Reuleaux) in a SpherePartition region, times `rolls` equal bins
/// of the rotation about it.
///
/// The roll is the angle of the tool's x axis about the approach, measured from the reference
/// direction: the world x axis projected onto the plane normal to the approach, or the world y
/// axis where the approach is within 30 deg of +-x. With rolls = 1 (the default of mcws_reach) a
/// bin is reached by any roll, as in the reachability index of Zacharias et al.
class OrientationBins {
 public:
  /// \throws mcws::Error for directions < 1 or rolls < 1.
  OrientationBins(int directions, int rolls);

  int directions() const { return sphere_.regions(); }
  int rolls() const { return rolls_; }
  /// \brief directions() * rolls().
  int size() const { return sphere_.regions() * rolls_; }
  const SpherePartition& sphere() const { return sphere_; }

  /// \brief Bin of a tool orientation: direction region * rolls() + roll bin.
  /// \param approach the tool's z axis, x_axis the tool's x axis (unit, orthogonal).
  int bin(const Eigen::Vector3d& approach, const Eigen::Vector3d& x_axis) const;
  /// \brief bin() of `lanes` orientations at once, laid out as SpherePartition::regions() reads
  /// them.
  void bins(const double* approach, const double* x_axis, int lanes, int* out) const;
  /// \brief A rotation at the centre of a bin: approach = the region's centre, roll at the bin's
  /// middle angle.
  Eigen::Matrix3d centre(int bin) const;

  /// \brief The reference of the roll angle for an approach direction (unit, normal to it).
  static Eigen::Vector3d rollReference(const Eigen::Vector3d& approach);

 private:
  int rollSector(const Eigen::Vector3d& approach, const Eigen::Vector3d& x_axis) const;
  SpherePartition sphere_;
  int rolls_;
};

}  // namespace mcws
