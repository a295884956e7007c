#pragma once
/// \file The 12 anatomical landmarks (Farinella et al. 2006; definitions in docs/LANDMARKS.md).
#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace breastfit {

/// In the paper's order (sternum top to bottom, then symmetric pairs top to bottom, R before L).
inline constexpr std::array<std::string_view, 12> kLandmarkNames = {
    "sternal_notch",        "xiphoid",
    "acromion_R",           "acromion_L",
    "midaxillary_R",        "midaxillary_L",
    "pectoral_insertion_R", "pectoral_insertion_L",
    "nipple_R",             "nipple_L",
    "lowest_breast_R",      "lowest_breast_L"};

/// Index of a landmark name in kLandmarkNames, or nullopt when unknown.
inline std::optional<int> landmark_index(std::string_view name) {
  for (size_t i = 0; i < kLandmarkNames.size(); ++i)
    if (kLandmarkNames[i] == name) return static_cast<int>(i);
  return std::nullopt;
}

/// "sternal_notch, xiphoid, ..." for error messages.
inline std::string landmark_name_list() {
  std::string s;
  for (auto n : kLandmarkNames) {
    if (!s.empty()) s += ", ";
    s += n;
  }
  return s;
}

/// The mirrored name (nipple_R <-> nipple_L); the name itself for midline landmarks.
inline std::string mirrored_landmark_name(std::string_view name) {
  std::string s(name);
  if (s.size() > 2 && s.compare(s.size() - 2, 2, "_R") == 0) return s.substr(0, s.size() - 2) + "_L";
  if (s.size() > 2 && s.compare(s.size() - 2, 2, "_L") == 0) return s.substr(0, s.size() - 2) + "_R";
  return s;
}

}  // namespace breastfit
