// The header compiles as C++ too (extern "C", no C-only constructs).
#include "anitet.h"

int anitet_header_check_cxx();

int anitet_header_check_cxx() {
  anitet_options options = ANITET_OPTIONS_INIT;
  anitet_quality quality = ANITET_QUALITY_INIT;
  return options.version + quality.version;
}
