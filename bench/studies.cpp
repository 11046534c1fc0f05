#include "studies.h"

namespace penumbra::bench {

const std::vector<Study>& studyTable() {
  // Full runs use each study's defaults (the sizes of its README section); --quick shrinks
  // images, maps and frame counts so that the whole suite is a smoke run of a few minutes.
  static const std::vector<Study> table = {
      {"speed-error", "speed against error on every shipped scene, the headline table and plot", speedErrorStudy, {},
       {"-W", "96", "--samples", "8,16", "--frames", "1"}},
      {"dcs", "DCS paper: covered-sample modes, sample counts, shading modes, interleaving, semi-opaque", dcsStudies, {},
       {"-W", "256", "-H", "256", "--frames", "2"}},
      {"multiview", "VWSS paper tables 1-2, figures 8 and 13, map-resolution convergence", multiviewStudies, {},
       {"-W", "128", "-H", "128", "--map", "512", "--copies", "1,2", "--maps", "8,24", "--frames", "1", "--study", "1,2,5"}},
      {"single-map", "Sterna table 1, VSSM against PCSS as the light grows, VSSM stages, single-map errors",
       singleMapStudies, {}, {"-W", "256", "-H", "256", "--map", "1024", "--frames", "2", "--error-size", "128"}},
      {"techniques", "per-stage timings of the main techniques on the engine", techniqueTimings,
       {"-W", "256", "-H", "256", "--samples", "16,64", "--techniques", "hard-sv,dcs,mvr,vwss,reproject,pcss,vssm"},
       {"-W", "128", "-H", "128", "--samples", "16", "--frames", "2", "--techniques", "hard-sv,dcs,mvr,vwss,pcss,vssm"}},
  };
  return table;
}

}  // namespace penumbra::bench
