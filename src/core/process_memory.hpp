// The process's own memory figures, for the run reports (the peak per stage) and the benches.
#pragma once

namespace anitet {

// The peak resident memory of this process so far (VmHWM of /proc/self/status), in bytes; 0
// where it cannot be read (not Linux).
double peak_resident_bytes();

}  // namespace anitet
