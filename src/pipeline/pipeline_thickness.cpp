// Copyright (c) 2026 CGAL Metric Frames contributors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The thickness stage of the generate pipeline (Frame_field_pipeline.h). A
// translation unit of its own: it instantiates the segment walk, which the
// frame field's unit does not need, and the two compile in parallel.
#include <CGAL_ext/Domain_thickness_3.h>
#include <CGAL_ext/Frame_field_pipeline.h>

#include <CGAL/Real_timer.h>

#include <cstdio>
#include <string>

namespace CGAL_ext {

Pipeline_thickness measure_pipeline_thickness(const Pipeline_metric& metric, const Pipeline_stage_callback& stage) {
  CGAL::Real_timer timer;
  timer.start();
  Pipeline_thickness r;
  r.cap = 4;
  const Domain_thickness_3<Pipeline_metric_field_3> thickness(*metric.field, r.cap);
  r.facets = thickness.facets().size();
  r.fraction_below_hex_edge = thickness.area_fraction_below(1);
  r.thickness_at_10_percent = thickness.area_quantile(0.1);
  if (stage) {
    char detail[300];
    std::snprintf(detail, sizeof detail,
                  "%zu boundary facets; %.1f%% of the boundary is less than one hex edge from the opposite side, %s",
                  r.facets, 100 * r.fraction_below_hex_edge, r.tenth_text().c_str());
    stage("thickness", timer.time(), detail);
  }
  return r;
}

} // namespace CGAL_ext
