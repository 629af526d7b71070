#pragma once
/// \file
/// \brief The NumPy record layout of the library's point types (WorkspacePoint, QualityPoint):
/// a structured dtype over the C++ struct itself, so an array of points is handed over as it is.

#include <pcl/common/io.h>

#include <string>

#include "bindings.h"
#include "mcws/points/point_types.h"

namespace mcws::python {

/// \brief NumPy's name of a PCL field type ("<f4", "<u4", ...).
inline std::string numpyFormat(std::uint8_t datatype) {
  switch (datatype) {
    case pcl::PCLPointField::INT8:
      return "i1";
    case pcl::PCLPointField::UINT8:
      return "u1";
    case pcl::PCLPointField::INT16:
      return "<i2";
    case pcl::PCLPointField::UINT16:
      return "<u2";
    case pcl::PCLPointField::INT32:
      return "<i4";
    case pcl::PCLPointField::UINT32:
      return "<u4";
    case pcl::PCLPointField::FLOAT32:
      return "<f4";
    case pcl::PCLPointField::FLOAT64:
      return "<f8";
    case pcl::PCLPointField::INT64:
      return "<i8";
    case pcl::PCLPointField::UINT64:
      return "<u8";
    default:
      return "";
  }
}

/// \brief The fields of PointT as a structured dtype of itemsize sizeof(PointT): x y z, the
/// first `joints` of q1..q8 (the others stay in the record, hidden), label, and QualityPoint's
/// manipulability and inverse_condition.
template <typename PointT>
py::dtype pointDtype(int joints) {
  py::list names, formats, offsets;
  for (const pcl::PCLPointField& field : pcl::getFields<PointT>()) {
    const bool joint = field.name.size() == 2 && field.name[0] == 'q';
    if (joint && field.name[1] - '0' > joints) continue;
    names.append(field.name);
    formats.append(numpyFormat(field.datatype));
    offsets.append(field.offset);
  }
  return py::dtype(names, formats, offsets, sizeof(PointT));
}

}  // namespace mcws::python
