/// \file Example consumer of the installed breastfit library: loads the default template, poses
/// it (global scale 1.1) and prints its sizes, the posed height ratio and its body frame.
#include <cstdio>
#include <exception>

#include "breastfit/mesh/body_frame.h"
#include "breastfit/mesh/triangle_mesh.h"
#include "breastfit/model/gltf_io.h"
#include "breastfit/model/pose_evaluator.h"
#include "breastfit/model/pose_params.h"
#include "breastfit/model/rigged_model.h"

using namespace breastfit;

/// Superior–inferior (z) extent of the vertices, mm.
double height(const Points& V) { return V.col(2).maxCoeff() - V.col(2).minCoeff(); }

int main(int argc, char** argv) {
  try {
    const char* path = argc > 1 ? argv[1] : BREASTFIT_EXAMPLE_TEMPLATE;
    const model::RiggedModel m = model::load_gltf(path);
    m.validate();
    std::printf("template: %s\n", path);
    std::printf("vertices: %d faces: %d bones: %d blendshapes: %d\n", static_cast<int>(m.num_vertices()),
                static_cast<int>(m.rest.F.rows()), m.num_bones(), m.num_blendshapes());

    model::PoseParams params = model::PoseParams::identity(m);
    params.global.scale = 1.1;
    TriangleMesh posed;
    posed.V = model::pose_vertices(m, params);
    posed.F = m.rest.F;
    std::printf("height ratio: %.3f\n", height(posed.V) / height(m.rest.V));

    mesh::NamedPositions landmarks;
    for (const auto& l : m.landmarks) landmarks[l.name] = l.point.position(posed.V, posed.F);
    const mesh::BodyFrame frame = mesh::estimate_body_frame(posed, landmarks);
    std::printf("body frame: %s\n", frame.description.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "breastfit_example: %s\n", e.what());
    return 1;
  }
}
