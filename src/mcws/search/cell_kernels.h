#pragma once
/// \file
/// \brief The inner loops of the cell grid's searches (CellGridSearch): squared distances of a
/// row of cells, the left-packing of values below a bound, the k-th smallest of a short list;
/// with AVX2 where the processor has it, with the same results without.

#include <cstddef>
#include <cstdint>

namespace mcws::detail {

/// \brief How many entries past the end of its inputs a kernel may read, and past the end of its
/// outputs it may write: the callers leave that much room.
constexpr std::size_t kKernelSlack = 8;

/// \brief A run of points [begin, end) in the grid's arrays: the cells of one row that a search
/// visits.
struct RowSpan {
  std::uint32_t begin, end;
};

/// \brief The candidates of a search, row after row: the squared distances from (px, py, pz) of
/// the points of `rows` (coordinates in the parallel arrays xs, ys, zs) into d2, their slots
/// (places in those arrays) into slot, and those with d^2 < `bound` (d2 and slot, in order) into
/// near_d2 and near_slot; returns how many of those. Distances as FLANN's L2_Simple computes them
/// (float, point minus query, summed x, y, z in that order, IEEE operations without fused
/// multiply-adds).
std::size_t rowDistances(const float* xs, const float* ys, const float* zs, const RowSpan* rows,
                         std::size_t row_count, float px, float py, float pz, float bound,
                         float* d2, std::uint32_t* slot, float* near_d2, std::uint32_t* near_slot);

/// \brief The places k (in order) of the values with v[k] < bound into `out`; returns how many.
std::size_t placesBelow(const float* v, std::size_t n, float bound, std::uint32_t* out);

/// \brief The values v[k] < bound (in order) into `out`; returns how many.
std::size_t valuesBelow(const float* v, std::size_t n, float bound, float* out);

/// \brief The `count`-th smallest (1 <= count <= m) of v[0, m), exact, ties counted; v (which
/// must hold m + kKernelSlack entries) may be overwritten past m and reordered.
float kthSmallest(float* v, std::size_t m, int count);

/// \brief The kernels above without vector instructions (what a processor without AVX2 runs),
/// for tests that compare the two.
namespace plain {
std::size_t rowDistances(const float* xs, const float* ys, const float* zs, const RowSpan* rows,
                         std::size_t row_count, float px, float py, float pz, float bound,
                         float* d2, std::uint32_t* slot, float* near_d2, std::uint32_t* near_slot);
std::size_t valuesBelow(const float* v, std::size_t n, float bound, float* out);
std::size_t placesBelow(const float* v, std::size_t n, float bound, std::uint32_t* out);
float kthSmallest(float* v, std::size_t m, int count);
}  // namespace plain

}  // namespace mcws::detail
