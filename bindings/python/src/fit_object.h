#pragma once
/// \file The Python Fit (a registration's result with its template and inputs) and Drawing,
/// shared by register.cpp and transfer.cpp.
#include <filesystem>
#include <memory>
#include <vector>

#include "bindings.h"
#include "breastfit/pipeline/register_scan.h"

namespace breastfit::python {

struct Fit {
  pipeline::RegisterResult result;
  std::shared_ptr<const model::RiggedModel> model;
  std::vector<std::filesystem::path> inputs;  ///< files the fit read (never overwritten by save)
  std::filesystem::path template_path;         ///< the template's file (empty: unknown)
};

/// A transferred drawing in the scan's units.
struct TransferredDrawing {
  std::string name;
  bool closed = false;
  Points points;
  std::vector<bool> supported;
  double supported_fraction = 0;
  double length = 0;
};

inline TransferredDrawing transferred_drawing(const transfer::TransferredCurve& c, double scale) {
  return {c.name, c.closed, c.points * scale, c.supported, c.supported_fraction, c.length_mm * scale};
}

}  // namespace breastfit::python
