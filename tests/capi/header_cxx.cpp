// The header compiles as C++ too (extern "C", no C-only constructs).
#include "anitet.h"

int anitet_header_check_cxx();

int anitet_header_check_cxx() {
  anitet_options options = ANITET_OPTIONS_INIT;
  anitet_quality quality = ANITET_QUALITY_INIT;
  anitet_partition_options partition_options = ANITET_PARTITION_OPTIONS_INIT;
  anitet_partition_info partition_info = ANITET_PARTITION_INFO_INIT;
  anitet_run_stats run_stats = ANITET_RUN_STATS_INIT;
  anitet_adapt_options adapt_options = ANITET_ADAPT_OPTIONS_INIT;
  anitet_adapt_stats adapt_stats = ANITET_ADAPT_STATS_INIT;
  partition_options.tet_weights = nullptr;
  options.layer_scheme = ANITET_LAYERS_FACE_PUSH;
  options.progress = nullptr;
  return options.version + quality.version + options.layers + partition_options.version + partition_info.version +
         run_stats.version + adapt_options.version + adapt_stats.version;
}
