/* Compiled with -std=c99 -pedantic -Wall -Wextra -Werror by a ctest case: the header must be
 * plain C99, and its INIT macros must initialise the structs completely. */
#include "anitet.h"

int anitet_header_check(void);

int anitet_header_check(void) {
  anitet_options options = ANITET_OPTIONS_INIT;
  anitet_quality quality = ANITET_QUALITY_INIT;
  anitet_partition_options partition_options = ANITET_PARTITION_OPTIONS_INIT;
  anitet_partition_info partition_info = ANITET_PARTITION_INFO_INIT;
  anitet_run_stats run_stats = ANITET_RUN_STATS_INIT;
  anitet_adapt_options adapt_options = ANITET_ADAPT_OPTIONS_INIT;
  anitet_adapt_stats adapt_stats = ANITET_ADAPT_STATS_INIT;
  anitet_progress_fn progress = 0;
  anitet_log_fn log = 0;
  anitet_metric_fn metric = 0;
  (void)progress;
  (void)log;
  (void)metric;
  options.layer_scheme = ANITET_LAYERS_FACE_PUSH;
  options.size_scale = 2.0;
  partition_options.ghost_layers = 2;
  return options.version + quality.version + partition_options.version + partition_info.version + run_stats.version +
         adapt_options.version + adapt_stats.version +
         ANITET_VERSION_NUMBER + ANITET_ERR_INTERNAL;
}
