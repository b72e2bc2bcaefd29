// Example: the generate pipeline from C++, step by step, as the CLI runs it.
//
//   pipeline_example MESH OUTDIR
//
// The calls that `metric-frames generate MESH --metric G.sol --hex-size 0.25
// -o OUTDIR --force` makes, G.sol holding the tensors given here per vertex,
// and so the same files, bit for bit (test_cli_generate checks it):
// frames.fra, frames.perm, mesh.mesh, frames.vtu, singularities.vtu,
// report.json. The metric has the shape of frame_field_example's: hexes of
// edge 0.25 / (1 + z) along x and z, half that along y (about 400 hexes,
// coarser than the 1175 tets, as a hex mesh from this tet mesh should be).
// 1. load_tet_mesh() reads the .mesh (or meshes a surface with Mesh_3).
// 2. make_pipeline_metric() divides the metric by h^2 and checks it;
//    measure_pipeline_thickness() finds the parts thinner than a hex edge.
// 3. generate_pipeline_frame_field() computes, repairs and classifies, then
//    straightens the singular curves (pipeline_straightening_options()).
// 4. write_pipeline_outputs() writes the files; pipeline_report() makes the
//    report, a JSON value (nlohmann-json), and write_pipeline_report() writes it.
#include <CGAL_ext/Frame_field_pipeline.h>
#include <CGAL_ext/Frame_field_pipeline_report.h>

#include <Eigen/Core>

#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: pipeline_example MESH OUTDIR\n";
    return 2;
  }
  const std::string input = argv[1], out_dir = argv[2];
  CGAL_ext::check_pipeline_output_directory(out_dir, {input}, /*force=*/true);
  CGAL_ext::Pipeline_report_context context;
  context.input = input;
  const auto stage = [&](const std::string& name, double seconds, const std::string& detail) {
    std::printf("%-22s %7.3f s  %s\n", name.c_str(), seconds, detail.c_str());
    context.stage_seconds.emplace_back(name, seconds);
  };

  //! [pipeline]
  const CGAL_ext::Pipeline_tet_mesh mesh = CGAL_ext::load_tet_mesh(input, {}, stage);

  // g = diag(1, 4, 1) (1 + z)^2 per vertex, divided by h^2 below.
  CGAL_ext::Pipeline_metric_input metric;
  metric.per_vertex.emplace();
  for (const auto& p : mesh.mesh.vertices)
    metric.per_vertex->push_back(Eigen::Vector3d(1, 4, 1).asDiagonal() * ((1 + p[2]) * (1 + p[2])));
  metric.source = "pipeline_example";
  metric.name = "diag(1, 4, 1) (1 + z)^2";
  metric.hex_size = 0.25;
  const CGAL_ext::Pipeline_metric field = CGAL_ext::make_pipeline_metric(mesh, metric, stage);
  context.thickness = CGAL_ext::measure_pipeline_thickness(field, stage);

  CGAL_ext::Frame_field_options options;
  options.progress = stage;
  const CGAL_ext::Pipeline_frame_field frames =
      CGAL_ext::generate_pipeline_frame_field(field, options, CGAL_ext::Singularity_repair_options(), stage,
                                              CGAL_ext::pipeline_straightening_options(mesh));

  CGAL_ext::write_pipeline_outputs(out_dir, mesh, frames);
  const std::string report =
      CGAL_ext::write_pipeline_report(out_dir, CGAL_ext::pipeline_report_json(mesh, field, frames, context));
  //! [pipeline]
  std::printf("%s  wrote %s and the files of CubeCover and ParaView\n",
              CGAL_ext::pipeline_summary_text(mesh, field, frames, context).c_str(), report.c_str());
  return 0;
}
