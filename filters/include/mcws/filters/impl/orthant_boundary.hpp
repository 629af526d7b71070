#pragma once

#include <omp.h>

#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "mcws/core/error.h"
#include "mcws/filters/orthant/cloud_stages.h"
#include "mcws/filters/orthant_boundary.h"
#include "mcws/points/unique_positions.h"
#include "mcws/search/grid_then_tree_search.h"

namespace mcws {

template <typename PointT>
void OrthantBoundary<PointT>::applyFilter(pcl::Indices& indices) {
  const int dimensions = boundaryDimensions(plane_);
  checkSettings(dimensions);

  // The points in the method's plane (or 3-D), finite ones only; copies of a point are one
  // position, which the test sees once and whose answer every copy gets.
  pcl::PointCloud<pcl::PointXYZ> finite;
  pcl::Indices source;
  projectToPlane(*input_, *indices_, plane_, finite, source);
  std::vector<pcl::index_t> position_of;
  pcl::PointCloud<pcl::PointXYZ> positions = uniquePositions(finite, position_of);

  const orthant::PointTestSettings test = resolveSettings(positions, dimensions);
  // An automatic radius of 0 (every point a copy of one) leaves each point alone: boundary.
  std::vector<char> boundary(positions.size(),
                             radius_mode_ == RadiusMode::kAutomatic && !(test.radius > 0.0));
  if (!positions.empty() && (test.adaptive || test.radius > 0.0)) {
    const int threads = threads_ > 0 ? threads_ : omp_get_num_procs();
    GridThenTreeSearch search(std::move(positions), position_of, dimensions,
                              orthant::typicalOuterRadius(test, used_spacing_), used_spacing_,
                              grid_search_, threads);
    orthant::CloudDecisions decisions = orthant::testEveryPoint(search, test, threads);
    if (getHullDepth() > 0.0) {
      orthant::keepShallowPoints(search, test, getHullDepth(), threads, decisions);
    }
    if (test.adaptive) used_radius_ = orthant::medianRadius(search, test, decisions);
    boundary = std::move(decisions.boundary);
  }

  splitByBoundary(
      *indices_, source, [&](std::size_t k) { return boundary[position_of[k]] != 0; }, negative_,
      extract_removed_indices_, indices, *removed_indices_);
}

template <typename PointT>
void OrthantBoundary<PointT>::checkSettings(int dimensions) const {
  auto fail = [this](const auto&... what) {
    std::ostringstream msg;
    msg << filter_name_ << ": ";
    (msg << ... << what);
    throw Error(msg.str());
  };
  if (radius_mode_ == RadiusMode::kAdaptive) {
    if (getAdaptiveNeighbours() < 1) fail("adaptive k must be at least 1");
    if (!(adaptive_scale_ > 0.0 && std::isfinite(adaptive_scale_))) {
      fail("adaptive radius scale must be a positive number");
    }
  }
  if (radius_mode_ == RadiusMode::kFixed && !(radius_ > 0.0 && std::isfinite(radius_))) {
    fail("radius ", radius_, " must be a positive number");
  }
  if (radius_mode_ == RadiusMode::kAutomatic &&
      !(auto_factor_ >= 0.0 && std::isfinite(auto_factor_))) {
    fail("radius factor ", auto_factor_, " must be 0 (automatic) or a positive number");
  }
  if (outer_radius_ < 0.0 || !std::isfinite(outer_radius_)) {
    fail("outer radius must be 0 (off) or positive");
  }
  if (!(minimum_gap_ >= M_PI / 2 - 1e-9 && minimum_gap_ < M_PI)) {
    fail("minimum gap must be in [pi/2, pi) rad");
  }
  const double hull_depth = getHullDepth();
  if (!(hull_depth >= 0.0 && std::isfinite(hull_depth))) {
    fail("hull depth must be 0 (off) or a positive number of spacings");
  }
  if (hull_depth > 0.0 && dimensions != 2) {
    fail("the hull depth test works in a plane; set a plane (xy, xz, yz)");
  }
}

template <typename PointT>
orthant::PointTestSettings OrthantBoundary<PointT>::resolveSettings(
    const pcl::PointCloud<pcl::PointXYZ>& positions, int dimensions) {
  const std::size_t n = positions.size();
  const bool adaptive = radius_mode_ == RadiusMode::kAdaptive;
  used_spacing_ =
      radius_mode_ != RadiusMode::kFixed && n > 1 ? meanSpacing(positions, dimensions) : 0.0;
  double radius = radius_;
  if (radius_mode_ == RadiusMode::kAutomatic) {
    radius = (auto_factor_ > 0.0 ? auto_factor_ : orthantAutoFactor(n, dimensions)) * used_spacing_;
  }
  if (adaptive && outer_radius_ > 0.0 && outer_radius_ <= 1.0) {
    std::ostringstream msg;
    msg << filter_name_ << ": with an adaptive radius the outer radius is a factor of each point's "
        << "radius and must exceed 1, not " << outer_radius_;
    throw Error(msg.str());
  }
  if (!adaptive && outer_radius_ > 0.0 && outer_radius_ < radius) {
    std::ostringstream msg;
    msg << filter_name_ << ": outer radius " << outer_radius_ << " is smaller than radius "
        << radius;
    throw Error(msg.str());
  }
  used_radius_ = adaptive ? 0.0 : radius;

  orthant::PointTestSettings test;
  test.dimensions = dimensions;
  test.frames = resolveFrames(frames_, dimensions);
  test.gap = orthant::sectorGap(minimum_gap_);
  if (adaptive) test.adaptive = orthant::AdaptiveRadius{getAdaptiveNeighbours(), adaptive_scale_};
  test.radius = radius;
  test.outer = outer_radius_;
  return test;
}

}  // namespace mcws
