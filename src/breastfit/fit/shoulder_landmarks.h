#pragma once
/// \file The acromion, the mid-axillary point and the pectoral insertion on the scan placed by the
/// sternum's proportions (the arms on boards; the pectoral insertion's height also arms hanging).
///
/// With the arms abducted the template's skin over the shoulder and the side of the chest follows
/// the arm: the fitted acromion slides onto the deltoid, 9–12 mm too lateral, the fitted
/// mid-axillary point rises with the axilla, 11–15 mm too high, and the pectoral insertion stays on
/// the chest, about 11 mm too medial (the signed errors of the landmark-free fits of the 14
/// benchmark and 16 generated supine torsos; arms hanging, the first two do not happen). The
/// skeleton does not follow the arm that way: on the 30 benchmark and generated torsos used to
/// choose them, standing and supine, the mid-axillary point lies 0.73 ± 0.01 sternum lengths (notch
/// to xiphoid) below the notch, and on the supine ones the acromio-clavicular joint 0.79 ± 0.04 and
/// the pectoral insertion 1.05 ± 0.04 sternum lengths to the side of the midline (16 hold-out
/// torsos: 0.73, 0.79, 1.04). The detectors take those proportions from the fitted sternum and the
/// rest from the scan:
/// - the mid-axillary point: the scan's chest wall at that height in the fitted point's coronal
///   plane (the scan vertex of a thin strip there closest to the fitted point across the body);
/// - the acromion: the top of the shoulder at that breadth in the fitted point's coronal plane
///   (the highest scan vertex of a thin strip there);
/// - the pectoral insertion: the front of the arm at that breadth and 0.28 ± 0.03 sternum lengths
///   below the notch (the most anterior scan vertex of a thin strip there: the insertion's skin
///   faces forward). It does not depend on the fitted point: on two of the 46 torsos the fit left
///   the arm's insertion 88 and 103 mm away (at the fitted height the detector found 10.3, 10.8 and
///   6.8 mm from the truth on the benchmark, validation and hold-out supine torsos where the fitted
///   point was near enough; at the proportion's height 8.3, 9.7 and 9.6 mm on all of them).
/// Each refuses (nullopt) when the strip holds no scan; the first two also when the point found
/// lies farther than `max_shift_mm` from the fitted one.
///
/// Arms hanging, the pectoral insertion found at the anterior axillary fold (fit/pectoral_insertion.h)
/// lies 7–8 mm too low on average (the first slice showing the crease is below the fold's border);
/// the truth lies 0.50 ± 0.03 sternum lengths below the notch (hold-out: 0.51).
/// hanging_pectoral_insertion_on_scan keeps the arm found there and takes its most anterior point
/// at that height.
///
/// Used by `breastfit landmarks` (pipeline/detect_landmarks.h) after the fit; the acromion and the
/// mid-axillary point for arms on boards only (arms hanging the fitted points were no worse: the
/// arm hangs against the side of the chest, and the shoulder is not abducted), the caller checking
/// arms_abducted_on_scan. The same detectors hold these landmarks, when not given, for the refine
/// stage of `register` (fit/registration.h, FitOptions::anatomical_shoulders).
#include <optional>

#include "breastfit/core/types.h"

namespace breastfit::fit {

/// The fitted body's frame at the sternum, one side.
struct SternumFrame {
  Vec3 notch = Vec3::Zero();    ///< the sternal notch (mm)
  double length_mm = 0;         ///< notch to xiphoid
  Vec3 up = Vec3::UnitZ();      ///< superior (unit, along the sternum)
  Vec3 front = Vec3::UnitY();   ///< anterior (unit, orthogonal to up)
  Vec3 lateral = Vec3::UnitX(); ///< towards the side whose landmark is sought (unit, orthogonal to both)
};

/// A point's coordinates in the frame (mm): height above the notch, depth in front of it, distance
/// towards the side.
struct SternumCoordinates {
  double height = 0, front = 0, lateral = 0;
};

/// The sternum's frame on one side ('R' or 'L') from the fitted notch, xiphoid and nipples: up
/// along the sternum (xiphoid → notch), front orthogonal to it and to the line through the nipples
/// (towards the nipples), lateral towards `side`; nullopt when degenerate.
std::optional<SternumFrame> sternum_frame(const Vec3& notch, const Vec3& xiphoid, const Vec3& nipple_R,
                                          const Vec3& nipple_L, char side);

/// `p` in `frame`'s coordinates.
SternumCoordinates sternum_coordinates(const SternumFrame& frame, const Vec3& p);

/// The proportions and the strips' sizes.
struct ShoulderLandmarkOptions {
  double midaxillary_drop = 0.73;  ///< the mid-axillary point's depth below the notch, in sternum lengths
  double acromion_breadth = 0.79;  ///< the acromion's distance from the midline, in sternum lengths
  double pectoral_breadth = 1.05;  ///< the pectoral insertion's distance from the midline, in sternum lengths
  double pectoral_drop = 0.28;     ///< the pectoral insertion's depth below the notch, in sternum lengths
  double hanging_pectoral_drop = 0.50;  ///< the same, arms hanging
  double max_behind_mm = 40.0;     ///< arms hanging: scan this far behind the arm's front found is ignored
  double strip_half_width_mm = 4.0;  ///< half-width of the strips (height and antero-posterior)
  double acromion_height_window_mm = 40.0;  ///< the shoulder's top is sought this far above and below the fitted acromion
  double max_shift_mm = 40.0;      ///< a point farther than this from the fitted one = refused
  /// Arms abducted: the scan reaches at least this far to each side of the midline (in sternum
  /// lengths) between the notch's height and `reach_band` below it (arms on boards 1.29–1.46, arms
  /// hanging 0.99–1.14 on the 46 benchmark and generated torsos).
  double abducted_reach = 1.2;
  double reach_band = 0.4;  ///< the band's depth below the notch, in sternum lengths
};

/// Whether the scan's arms reach out sideways at the shoulders on both sides (`abducted_reach`): the
/// proportions below are those of abducted arms. A wide standing torso can pass the orientation
/// search's supine test (a template-made one of the test suite with its arms 20° out did, reaching
/// 1.11 sternum lengths; its insertions went 50–60 mm off).
bool arms_abducted_on_scan(const Points& scan_vertices, const SternumFrame& frame,
                           const ShoulderLandmarkOptions& options = {});

/// The mid-axillary point on the scan, or nullopt when unsure.
/// \param scan_vertices the scan (mm), \param fitted the fitted model's mid-axillary point
std::optional<Vec3> midaxillary_on_scan(const Points& scan_vertices, const Vec3& fitted, const SternumFrame& frame,
                                        const ShoulderLandmarkOptions& options = {});

/// The acromion on the scan, or nullopt when unsure.
/// \param scan_vertices the scan (mm), \param fitted the fitted model's acromion
std::optional<Vec3> acromion_on_scan(const Points& scan_vertices, const Vec3& fitted, const SternumFrame& frame,
                                     const ShoulderLandmarkOptions& options = {});

/// The pectoral insertion on the scan of abducted arms, or nullopt when unsure (arms hanging:
/// fit/pectoral_insertion.h).
/// \param scan_vertices the scan (mm)
std::optional<Vec3> abducted_pectoral_insertion_on_scan(const Points& scan_vertices, const SternumFrame& frame,
                                                        const ShoulderLandmarkOptions& options = {});

/// The pectoral insertion of a hanging arm, or nullopt when unsure: the arm's most anterior scan
/// vertex at the proportion's height, in a strip along the body through `arm_front` (the point the
/// anterior axillary fold gave, or the fitted insertion).
/// \param scan_vertices the scan (mm)
std::optional<Vec3> hanging_pectoral_insertion_on_scan(const Points& scan_vertices, const Vec3& arm_front,
                                                       const SternumFrame& frame,
                                                       const ShoulderLandmarkOptions& options = {});

}  // namespace breastfit::fit
