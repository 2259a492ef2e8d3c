// The header compiles as C++ too (extern "C", no C-only constructs).
#include "anitet.h"

int anitet_header_check_cxx();

int anitet_header_check_cxx() {
  anitet_options options = ANITET_OPTIONS_INIT;
  anitet_quality quality = ANITET_QUALITY_INIT;
  options.layer_scheme = ANITET_LAYERS_FACE_PUSH;
  options.progress = nullptr;
  return options.version + quality.version + options.layers;
}
