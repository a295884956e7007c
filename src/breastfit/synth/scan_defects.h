#pragma once
/// \file The defects of a simulated handheld scan: disc holes, normal noise (white + smooth),
/// floating fragments and, for supine scans, strips of the table. Body frame, mm.
#include <vector>

#include "breastfit/core/rng.h"
#include "breastfit/core/types.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/synth/synth_options.h"

namespace breastfit::synth {

/// A disc removed from the scan.
struct Hole {
  Vec3 centre = Vec3::Zero();  ///< a scan vertex, mm
  double radius_mm = 0.0;
};

/// Removes up to options.n_holes discs: every triangle with a vertex within the radius of the
/// centre. Centres are scan vertices at least (clearance + radius) from every point of
/// `keep_clear` (the landmarks), at least radius + 6 mm from the scan's open border (so each hole
/// is a new border loop) and apart from each other. Fewer holes are made when no place is found
/// within a few hundred draws. Vertices are kept (remove unreferenced ones afterwards).
/// \return the holes made
std::vector<Hole> punch_holes(TriangleMesh& scan, const std::vector<Vec3>& keep_clear, const ArtifactOptions& options,
                              Rng& rng);

/// Moves every vertex along its normal by white Gaussian noise (sd white_noise_mm) plus a smooth
/// field (a sum of 6 random plane waves with wavelengths in lowfreq_wavelength_mm, RMS about
/// lowfreq_noise_mm), and tangentially by Gaussian jitter (sd tangential_jitter_mm).
/// \param[in,out] V  #V by 3 positions
/// \param[in] N      #V by 3 unit normals
void add_scan_noise(Points& V, const Points& N, const ArtifactOptions& options, Rng& rng);

/// A floating fragment (small, slightly curved disc patch of ~3 mm triangles) hovering
/// fragment_distance_mm off the surface along the normal of a random scan vertex.
struct Fragment {
  Vec3 centre = Vec3::Zero();
  double radius_mm = 0.0;
  double distance_mm = 0.0;  ///< from the surface point it floats over
};

/// options.n_fragments fragments around `scan` (#V by 3 normals N), as one mesh; their
/// descriptions go to `fragments`.
TriangleMesh make_fragments(const TriangleMesh& scan, const Points& N, const ArtifactOptions& options, Rng& rng,
                            std::vector<Fragment>& fragments);

/// Supine only: two flat strips of the table (normal anterior, −y) at the back's level (the most
/// posterior point of `body`), beside the lower half of the torso, ~5 mm triangles.
/// \param[in] body  #V by 3 truth vertices, body frame
TriangleMesh make_table_strips(const Points& body, Rng& rng);

/// Appends mesh b to mesh a (V and F only).
void append_mesh(TriangleMesh& a, const TriangleMesh& b);

}  // namespace breastfit::synth
