#pragma once
/// \file
/// \brief Datasheet drawings of a workspace envelope: the side view (the section in a vertical
/// plane through the first joint's axis) and the top view (the projection on the horizontal
/// plane), with the numbers industrial robot datasheets give.
///
/// The first joint's axis is the base frame's z axis through its origin: joint 1 of a D-H chain
/// turns about z0, and the seed robots' URDFs put their first joint there too.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mcws/workspace/measure.h"

namespace mcws {

/// \brief The section of a closed surface by the vertical half-planes at `azimuth` and at
/// `azimuth` + pi, i.e. by the whole vertical plane through the z axis in that direction.
struct EnvelopeSection {
  double azimuth{0.0};  ///< direction of +s, from +x towards +y [rad]
  /// Closed polygons in (s, z): s the signed horizontal distance from the axis along the azimuth
  /// (negative behind the axis). Counter-clockwise around the region, clockwise around its holes
  /// (seen with s to the right and z up), for an outward-oriented surface.
  std::vector<std::vector<Eigen::Vector2d>> loops;
  double area{0.0};         ///< enclosed by the loops, holes subtracted [length unit^2]
  double front_reach{0.0};  ///< largest s [length unit]
  double back_reach{0.0};   ///< largest -s (0 when the section stays in front) [length unit]
  double highest{0.0}, lowest{0.0};  ///< largest and smallest z [length unit]
};

/// \brief The section of `surface` (closed, outward-oriented) by the vertical plane through the
/// z axis at `azimuth` [rad]. Vertices on the plane count as in front of it (a symbolic
/// perturbation), so every crossing edge is cut once and the cuts chain into closed loops.
/// \throws mcws::Error when the plane misses the surface or the surface is not closed there.
EnvelopeSection envelopeSection(const TriangleSurface& surface, double azimuth);

/// \brief The projection of the samples on the horizontal plane, seen from the z axis: for each
/// of `bins` equal azimuth bins (bin k centred on -pi + k bin) the nearest and farthest
/// horizontal distance from the axis of the samples in it.
///
/// From the samples rather than the envelope mesh: the mesh bridges gaps narrower than its
/// alpha balls, such as the few degrees a first joint of +-170 deg leaves behind the robot, where
/// the sparse far edge of the region has wide alpha balls; the samples leave such a gap empty.
struct EnvelopeTopView {
  double bin{0.0};                   ///< angular width of a bin [rad]
  std::vector<double> inner, outer;  ///< per bin [length unit]; NaN where no sample lies
  double max_reach{0.0};             ///< largest outer distance [length unit]
  double min_reach{0.0};             ///< smallest inner distance [length unit]
  /// The swept arc at full reach: the longest run of bins (around the circle) whose outer
  /// distance is at least kFullReachShare of max_reach, from its first bin's centre to its last's
  /// (counter-clockwise, in (-pi, pi]) [rad]; 2 pi when every bin reaches.
  double sweep_from{0.0}, sweep_to{0.0}, sweep{0.0};
};

/// \brief Share of the maximum reach that counts as full reach for EnvelopeTopView's sweep.
constexpr double kFullReachShare = 0.9;

/// \brief The top view of the samples in `bins` azimuth bins (non-finite points skipped).
/// \throws mcws::Error when bins < 8 or no point is finite.
EnvelopeTopView sampleTopView(const pcl::PointCloud<pcl::PointXYZ>& points, int bins = 360);

/// \brief A datasheet drawing: the side view of the envelope at an azimuth, the top view of the
/// samples (in the same length unit), the envelope's extreme heights.
struct EnvelopeDrawing {
  EnvelopeSection side;
  EnvelopeTopView top;
  double highest{0.0}, lowest{0.0};  ///< of the whole envelope [length unit]
};
EnvelopeDrawing envelopeDrawing(const TriangleSurface& surface,
                                const pcl::PointCloud<pcl::PointXYZ>& points, double azimuth,
                                int bins = 360);

/// \brief Picture formats of renderEnvelopeDrawing().
enum class DrawingFormat { kPng, kSvg };
/// \brief The format a file name's extension names (.png or .svg, any case).
/// \throws mcws::Error naming the file for any other extension.
DrawingFormat drawingFormatOf(const std::string& path);

/// \brief The two views side by side with dimension lines (reach in front and behind the axis,
/// highest and lowest point, maximum and minimum reach, the swept angle), drawn by gnuplot;
/// lengths in `unit`, under the title "<title>: working range of <tip> (lengths in <unit>)"
/// (without " of <tip>" when `tip` is empty).
/// \param title the robot's name (or, when it is not known, the cloud's file name).
/// \param tip the frame whose origin the samples are (a URDF tip link, "tool", "flange").
/// \return the file's bytes. \throws mcws::Error when gnuplot fails.
std::string renderEnvelopeDrawing(const EnvelopeDrawing& drawing, DrawingFormat format,
                                  const std::string& title, const std::string& unit,
                                  const std::string& tip = "");

}  // namespace mcws
